// file_io.h: the workbench's files on the core's terms (oit.h, "files").
// Inputs must be regular files, checked without blocking (a FIFO would hang
// the GUI thread, /dev/zero never end). Outputs (settings, presets, exports,
// screenshots) replace only a regular file or create a new name: the resolved
// target (through symbolic links) is checked first, so a link to a device or
// a FIFO is refused rather than replaced (QSaveFile replaced whatever a link
// pointed at) or written into (opening a FIFO for writing blocks).
#pragma once

#include <QByteArray>
#include <QString>

// The whole file; false with "WHAT PATH: problem" (or "PATH: problem") in error.
bool read_regular_file(const QString &path, const char *what, QByteArray &bytes, QString &error);
// True if path names nothing yet or a regular file (through links), else
// false with the core's "WHAT PATH: not a regular file (a FIFO)". Never opens it.
bool check_output_path(const QString &path, const char *what, QString &error);
// check_output_path, then written atomically (oit_atomic_file: beside the
// target, renamed over it once whole; a failed write leaves the previous file).
bool write_output_file(const QString &path, const char *what, const QByteArray &bytes, QString &error);
