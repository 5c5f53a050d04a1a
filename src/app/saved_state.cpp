// saved_state.cpp: see saved_state.h.
#include "saved_state.h"
#include "file_io.h"

#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QStandardPaths>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sys/stat.h>

namespace {

const char *const kWhat = "saved settings";

} // namespace

SettingsFile::SettingsFile(const QString &path) : path_(path) {}

QString SettingsFile::default_path()
{
    return QStandardPaths::writableLocation(QStandardPaths::GenericConfigLocation) + "/" +
           QCoreApplication::organizationName() + "/settings.json";
}

QString SettingsFile::load(SavedStateText &state)
{
    keep_.clear();
    QByteArray name = QFile::encodeName(path_);
    struct stat info;
    if (lstat(name.constData(), &info) != 0 && errno == ENOENT)
        return QString(); // the first run
    QByteArray bytes;
    QString error;
    if (!read_regular_file(path_, kWhat, bytes, error)) {
        if (stat(name.constData(), &info) != 0 && errno == ENOENT)
            return QString(); // a dangling link: as no file
        // a FIFO, a device, a directory, a file that cannot be opened: left as it is
        keep_ = error + ", left as it is";
        return error + ": not read, and left as it is: this run's settings will not be saved";
    }
    std::string problem;
    SavedStateText read;
    if (saved_state_from_json(path_.toStdString(), bytes.toStdString(), read, problem)) {
        state = read;
        return QString();
    }
    // kept for the user to look at, out of the way of the next save; rename
    // replaces only a regular file (an older .bad) or a new name
    QString why = QString::fromStdString(problem);
    QString bad = bad_path(), refused;
    QByteArray bad_name = QFile::encodeName(bad);
    if (lstat(bad_name.constData(), &info) == 0 && !S_ISREG(info.st_mode))
        refused = bad + " is not a regular file";
    else if (std::rename(name.constData(), bad_name.constData()) != 0)
        refused = QString("cannot rename it to %1: %2").arg(bad, QString::fromLocal8Bit(std::strerror(errno)));
    if (!refused.isEmpty()) {
        keep_ = QString("%1 %2 could not be read and could not be kept aside (%3)").arg(kWhat, path_, refused);
        return QString("%1 %2: not used; %3, so it is left as it is and this run's settings will not be saved")
            .arg(kWhat, why, refused);
    }
    return QString("%1 %2: not used (the defaults are), kept as %3").arg(kWhat, why, bad);
}

bool SettingsFile::save(const SavedStateText &state, QString &error)
{
    if (!keep_.isEmpty()) {
        error = keep_;
        return false;
    }
    QString folder = QFileInfo(path_).absolutePath();
    if (!QDir().mkpath(folder)) {
        error = QString("%1: cannot create the folder %2").arg(kWhat, folder);
        return false;
    }
    return write_output_file(path_, kWhat, QByteArray::fromStdString(saved_state_to_json(state)), error);
}
