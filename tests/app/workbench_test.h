// workbench_test.h: what the workbench's Qt Test cases share (tests/app/test_workbench.cpp,
// test_workbench_views.cpp): image measures, the latency probe and the test class, whose
// cases are defined in those two files.
#ifndef OIT_WORKBENCH_TEST_H
#define OIT_WORKBENCH_TEST_H

#include <QApplication>
#include <QDialog>
#include <QStandardItemModel>
#include <QAction>
#include <QAbstractItemView>
#include <QComboBox>
#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QTimer>
#include <QProgressBar>
#include <QScrollBar>
#include <QDir>
#include <QFile>
#include <QMimeData>
#include <QProcess>
#include <QSignalSpy>
#include <QSlider>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QTabBar>
#include <QTabWidget>
#include <QStandardPaths>
#include <QImageReader>
#include <QtTest/QtTest>
#include <QTreeView>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>

#include <QElapsedTimer>

#include <cmath>

#include "camera_panel.h"
#include "compare_panel.h"
#include "error_legend.h"
#include "main_window.h"
#include "parts_panel.h"
#include "split_view.h"
#include "pick.h"


const QSize view_size(160, 120);

// largest channel difference and the share of pixels differing by more than tolerance
struct Difference {
    int max = 0;
    double share_over = 0.0;
};

inline Difference compare(const QImage &a, const QImage &b, int tolerance)
{
    Difference d;
    if (a.size() != b.size()) {
        d.max = 256;
        d.share_over = 1.0;
        return d;
    }
    QImage x = a.convertToFormat(QImage::Format_RGBA8888), y = b.convertToFormat(QImage::Format_RGBA8888);
    long over = 0;
    for (int row = 0; row < x.height(); ++row) {
        const uchar *p = x.constScanLine(row), *q = y.constScanLine(row);
        for (int col = 0; col < x.width(); ++col) {
            int worst = 0;
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(int(p[col * 4 + c]) - int(q[col * 4 + c])));
            d.max = std::max(d.max, worst);
            over += worst > tolerance;
        }
    }
    d.share_over = double(over) / double(x.width() * x.height());
    return d;
}

// how far the image is from the white background, summed over pixels (0..1 per pixel)
inline double ink(const QImage &image)
{
    QImage x = image.convertToFormat(QImage::Format_RGBA8888);
    double total = 0.0;
    for (int row = 0; row < x.height(); ++row) {
        const uchar *p = x.constScanLine(row);
        for (int col = 0; col < x.width(); ++col)
            total += (765 - p[col * 4] - p[col * 4 + 1] - p[col * 4 + 2]) / 765.0;
    }
    return total / (x.width() * x.height());
}

// The largest channel difference between a and b inside rect (both the same size).
inline int max_difference_in(const QImage &a, const QImage &b, const QRect &rect)
{
    QImage x = a.convertToFormat(QImage::Format_RGBA8888), y = b.convertToFormat(QImage::Format_RGBA8888);
    int worst = 0;
    for (int row = rect.top(); row <= rect.bottom(); ++row)
        for (int col = rect.left(); col <= rect.right(); ++col)
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(int(x.constScanLine(row)[col * 4 + c]) -
                                                 int(y.constScanLine(row)[col * 4 + c])));
    return worst;
}

// Pixels of an error map in the hot half of its scale: yellow to red (a difference of about 13 and more).
inline int hot_pixels(const QImage &map)
{
    QImage x = map.convertToFormat(QImage::Format_RGBA8888);
    int hot = 0;
    for (int row = 0; row < x.height(); ++row)
        for (int col = 0; col < x.width(); ++col) {
            const uchar *p = x.constScanLine(row) + col * 4;
            hot += p[0] >= 200 && p[2] <= 40;
        }
    return hot;
}

// Posted events record how long they waited for the GUI thread's event loop.
class LatencyProbe : public QObject {
public:
    static const QEvent::Type kType = QEvent::Type(QEvent::User + 17);
    double worst_ms = 0.0;
    int handled = 0;
    void post()
    {
        auto *event = new QEvent(kType);
        posted_.start();
        pending_ = true;
        QCoreApplication::postEvent(this, event);
    }
    bool pending() const { return pending_; }

protected:
    bool event(QEvent *event) override
    {
        if (event->type() != kType)
            return QObject::event(event);
        worst_ms = std::max(worst_ms, double(posted_.nsecsElapsed()) / 1e6);
        ++handled;
        pending_ = false;
        return true;
    }

private:
    QElapsedTimer posted_;
    bool pending_ = false;
};

// A left click posted (not sent) to widget at pos: it waits in the event queue
// like a user's click.
inline void post_click(QWidget *widget, QPoint pos)
{
    QCoreApplication::postEvent(widget, new QMouseEvent(QEvent::MouseButtonPress, pos, widget->mapToGlobal(pos),
                                                         Qt::LeftButton, Qt::LeftButton, Qt::NoModifier));
    QCoreApplication::postEvent(widget, new QMouseEvent(QEvent::MouseButtonRelease, pos, widget->mapToGlobal(pos),
                                                        Qt::LeftButton, Qt::NoButton, Qt::NoModifier));
}

// Milliseconds until condition holds (spinning the event loop), or -1 after timeout_ms.
template <typename Condition>
inline double ms_until(Condition condition, int timeout_ms)
{
    QElapsedTimer clock;
    clock.start();
    while (!condition()) {
        if (clock.elapsed() > timeout_ms)
            return -1.0;
        QCoreApplication::processEvents(QEventLoop::AllEvents, 5);
    }
    return double(clock.nsecsElapsed()) / 1e6;
}


class WorkbenchTest : public QObject {
    Q_OBJECT
private:
    MainWindow *window = nullptr;
    QString work;
    int dumped = 0;

    // The window's render settings and camera (its settings model).
    RenderSettings &settings() { return window->settings_model()->render_settings(); }
    Camera &camera() { return window->settings_model()->camera(); }

    // Wait until the full frame of the current settings is shown (the worker
    // renders off the GUI thread) and return what the widget shows.
    QImage frame()
    {
        if (!QTest::qWaitFor([this] { return window->view()->settled(); }, 120000))
            qWarning("the view did not settle: %s", qPrintable(window->status_text()));
        QImage shown = window->view()->grab().toImage();
        if (qEnvironmentVariableIsSet("OIT_TEST_DUMP")) // for looking at what a case saw
            shown.save(QString("%1/frame_%2.png").arg(work).arg(dumped++, 3, 10, QChar('0')));
        return shown.convertToFormat(QImage::Format_RGBA8888);
    }

private slots:
    void initTestCase();
    void cleanupTestCase();
    void init();
    void opens_default_model();
    void switching_algorithm_changes_the_image();
    void a_layer_cap_that_cuts_says_so();
    void approximation_parameters_are_settings();
    void opacity_slider_changes_the_image();
    void hiding_a_part_changes_the_image();
    void camera_modes_change_the_image();
    void export_equals_oit_render();
    void bad_model_keeps_the_previous_one();
    void import_warnings_are_shown();
    void step_models_load_with_their_tessellation();
    void presets_round_trip_and_name_errors();
    void settings_persist();
    void saved_views_are_named_and_kept_with_the_model();
    void export_clears_its_progress_and_remembers_its_folder();
    void a_uhd_export_keeps_the_window_answering();
    void options_an_algorithm_cannot_express_are_left_out();
    void controls_an_algorithm_cannot_express_are_disabled();
    void messages_and_the_copied_command_stay_readable();
    void a_slow_frame_never_freezes_the_window();
    void a_slow_reference_is_superseded_without_freezing();
    void startup_does_not_replay_a_slow_state_blindly();
    void clicking_a_part_selects_it();
    void a_click_picks_what_oit_pick_names();
    void frame_selection_and_standard_views();
    void undo_and_redo_settings();
    void error_view_maps_the_difference_against_the_reference();
    void split_view_shows_two_algorithms();
    void comparisons_are_settings();
    void every_control_has_a_tooltip();
    void hundred_thousand_parts();
    void parts_tree_of_an_assembly();
    void dropping_files();
};

#endif
