// file_io.cpp: see file_io.h.
#include "file_io.h"

#include <QFile>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sys/stat.h>

#include "oit.h"

bool read_regular_file(const QString &path, const char *what, QByteArray &bytes, QString &error)
{
    // oit_open_regular_file opens without blocking and checks with fstat
    FILE *handle = nullptr;
    oit_error err{};
    if (oit_open_regular_file(QFile::encodeName(path).constData(), what, &handle, &err) != OIT_OK) {
        error = QString::fromUtf8(err.message);
        return false;
    }
    QFile file;
    if (!file.open(handle, QIODevice::ReadOnly, QFileDevice::AutoCloseHandle)) {
        std::fclose(handle);
        error = path + ": " + file.errorString();
        return false;
    }
    bytes = file.readAll();
    if (file.error() != QFileDevice::NoError) {
        error = path + ": " + file.errorString();
        return false;
    }
    return true;
}

bool check_output_path(const QString &path, const char *what, QString &error)
{
    QByteArray name = QFile::encodeName(path);
    struct stat info;
    if (stat(name.constData(), &info) != 0) {
        if (errno == ENOENT)
            return true; // a new name (or a dangling link: the core creates the file it names)
        oit_error err{};
        oit_check_regular_file(name.constData(), what, &err); // names the errno ("cannot open: ...")
        error = QString::fromUtf8(err.message);
        return false;
    }
    if (S_ISREG(info.st_mode))
        return true;
    // the core's message for what is there; it stats before it opens, so a
    // FIFO or a device is named without being opened
    oit_error err{};
    oit_check_regular_file(name.constData(), what, &err);
    error = QString::fromUtf8(err.message);
    return false;
}

bool write_output_file(const QString &path, const char *what, const QByteArray &bytes, QString &error)
{
    if (!check_output_path(path, what, error))
        return false;
    oit_atomic_file *file = nullptr;
    oit_error err{};
    if (oit_atomic_file_open(QFile::encodeName(path).constData(), what, 0, &file, &err) != OIT_OK) {
        error = QString::fromUtf8(err.message);
        return false;
    }
    std::fwrite(bytes.constData(), 1, size_t(bytes.size()), oit_atomic_file_stream(file));
    if (oit_atomic_file_commit(file, &err) != OIT_OK) { // a failed write is kept and reported here
        error = QString::fromUtf8(err.message);
        return false;
    }
    return true;
}
