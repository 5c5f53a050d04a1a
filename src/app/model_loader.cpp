// model_loader.cpp: see model_loader.h.
#include "model_loader.h"

#include <QFile>
#include <QtConcurrent/QtConcurrent>

struct ModelLoader::Result {
    oit_model model{};
    bool ok = false;
    QString path, error;
};

void ModelDeleter::operator()(oit_model *model) const
{
    oit_model_free(model);
    delete model;
}

ModelLoader::ModelLoader(QObject *parent) : QObject(parent)
{
    watcher_ = new QFutureWatcher<Result *>(this);
    connect(watcher_, &QFutureWatcher<Result *>::finished, this, &ModelLoader::finished);
}

ModelLoader::~ModelLoader()
{
    if (unclaimed_) {
        // a load that finished() never took (still running, or its signal
        // not delivered yet): its model is freed here
        watcher_->waitForFinished();
        std::unique_ptr<Result> result(watcher_->result());
        if (result->ok)
            oit_model_free(&result->model);
    }
}

bool ModelLoader::running() const
{
    return watcher_->isRunning();
}

bool ModelLoader::start(const QString &path, const oit_import_options &import)
{
    if (watcher_->isRunning())
        return false;
    unclaimed_ = true;
    watcher_->setFuture(QtConcurrent::run([path, import] {
        auto *result = new Result;
        result->path = path;
        oit_error err{};
        QByteArray bytes = QFile::encodeName(path);
        // in a contained worker process: a parser crash or hang is an error, not our crash
        result->ok =
            oit_model_load_contained_with(bytes.constData(), nullptr, &import, &result->model, &err) == OIT_OK;
        result->error = QString::fromUtf8(err.message);
        return result;
    }));
    return true;
}

void ModelLoader::finished()
{
    std::unique_ptr<Result> result(watcher_->result());
    unclaimed_ = false;
    if (!result->ok) {
        emit failed(result->path, result->error);
        return;
    }
    ModelPointer model(new oit_model(result->model), ModelDeleter());
    emit loaded(model, result->path);
}
