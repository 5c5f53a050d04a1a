// window_test_main.h: main() of a Qt Test program that opens the workbench's
// window. The window imports models by running the program itself as a
// contained worker (oit_model_load_contained), so main answers that first.
#pragma once

#include <QApplication>
#include <QtTest/QtTest>

#include "oit.h"

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
