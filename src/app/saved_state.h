// saved_state.h: what the workbench keeps between runs (the last settings,
// the last model, the recent models, the window's layout) in one JSON file,
// $XDG_CONFIG_HOME/oit-workbench/settings.json (~/.config/... without it;
// the format is settings.h's SavedStateText).
//
// Read and written on the terms of file_io.h rather than QSettings': QSettings
// opened its file blocking (a FIFO hung the start, even with --screenshot)
// and saved through QSaveFile, which replaced whatever a link pointed at (a
// link to /dev/zero turned the device into a settings file). Here the file is
// read only if it is a regular file, and written only over a regular file or
// a new name. A file that cannot be used is said (the Messages) and never
// overwritten: one that does not parse or holds a bad value is moved aside to
// settings.json.bad; one that is not a regular file, or cannot be read or moved
// aside, stays as it is and this run's state is not saved over it.
#pragma once

#include <QString>

#include "settings.h"

class SettingsFile {
public:
    explicit SettingsFile(const QString &path = default_path());
    // GenericConfigLocation/ORGANISATION/settings.json (Qt Test's test mode
    // moves GenericConfigLocation under ~/.qttest)
    static QString default_path();
    QString path() const { return path_; }
    QString bad_path() const { return path_ + ".bad"; }

    // Reads the file into state (left as it is when the file does not exist).
    // Returns "" or the one line to report: why the file was not used and
    // what became of it. Never blocks.
    QString load(SavedStateText &state);
    // Writes state; false with the reason in error (not a regular file, a
    // read-only folder, a file found unusable at load that was left in place).
    bool save(const SavedStateText &state, QString &error);

private:
    QString path_;
    QString keep_; // why the file found at load must not be overwritten ("" if it may)
};
