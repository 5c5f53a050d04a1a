// window_test_main.h: what the Qt Test programs that open the workbench's
// window share: the window they start from, and main(). The window imports
// models by running the program itself as a contained worker
// (oit_model_load_contained), so main answers that first.
#pragma once

#include <QApplication>
#include <QDir>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QtTest/QtTest>

#include "main_window.h"
#include "oit.h"
#include "render_view.h"

// For initTestCase: a fresh window (the tests' saved state kept apart), shown,
// its view view_size, the default model loaded; work is the folder the test
// writes into ($OIT_TEST_WORK or the temporary folder, /oit-workbench-test,
// then subfolder). A failure is recorded (QTest::currentTestFailed()).
inline void open_test_window(MainWindow *&window, QString &work, QSize view_size, const QString &subfolder)
{
    QStandardPaths::setTestModeEnabled(true); // the saved state of the tests stays apart
    work = qEnvironmentVariable("OIT_TEST_WORK", QDir::tempPath() + "/oit-workbench-test") + subfolder;
    QDir().mkpath(work);
    window = new MainWindow(MainWindow::Start::Fresh);
    window->show();
    QVERIFY(QTest::qWaitForWindowExposed(window));
    window->view()->setFixedSize(view_size);
    QTRY_COMPARE(window->view()->size(), view_size);
    QSignalSpy loaded(window, &MainWindow::model_loaded);
    window->load_model(MainWindow::default_model_path());
    QVERIFY2(loaded.wait(60000), qPrintable(window->status_text() + " / " + window->last_error()));
}

#define OIT_WINDOW_TEST_MAIN(TestClass, application_name)                                                   \
    int main(int argc, char **argv)                                                                         \
    {                                                                                                       \
        if (oit_import_worker_requested(argc, argv))                                                        \
            return oit_import_worker_main(argc, argv);                                                      \
        QApplication app(argc, argv);                                                                       \
        QApplication::setOrganizationName("oit-workbench-test");                                            \
        QApplication::setApplicationName(application_name);                                                \
        TestClass test;                                                                                     \
        return QTest::qExec(&test, argc, argv);                                                             \
    }
