// model_loader.h: reading a model off the GUI thread. The importer runs in a
// contained worker process (oit_model_load_contained): a parser that crashes
// or hangs is an error, not the window's crash. One load at a time.
#pragma once

#include <QFutureWatcher>
#include <QObject>
#include <QString>

#include <memory>

#include "oit.h"

struct ModelDeleter {
    void operator()(oit_model *model) const;
};
// shared with the render worker, which may still draw the previous model
// while the window already holds the next one
using ModelPointer = std::shared_ptr<const oit_model>;

class ModelLoader : public QObject {
    Q_OBJECT
public:
    explicit ModelLoader(QObject *parent = nullptr);
    // A load still running is waited for, and its model freed.
    ~ModelLoader() override;

    // Start reading path off the GUI thread; false (nothing starts) while a load runs.
    // import: how STEP and IGES files are tessellated.
    bool start(const QString &path, const oit_import_options &import = oit_import_options{});
    bool running() const;

signals:
    // On the GUI thread, once the load ended.
    void loaded(ModelPointer model, const QString &path);
    void failed(const QString &path, const QString &message);

private:
    struct Result;
    void finished();

    QFutureWatcher<Result *> *watcher_ = nullptr;
    bool unclaimed_ = false; // a load's result that finished() has not taken
};
