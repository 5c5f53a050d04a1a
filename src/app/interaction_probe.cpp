// interaction_probe.cpp: oit-interaction-probe, the measuring half of
// bat/interaction_latency.py (not installed). It opens the real window (any
// QPA platform: the script uses offscreen), loads MODEL with ALGORITHM, waits
// for the full frame, then replays a left-button drag across the view (a move
// every 16 ms for DRAG_MS) and prints one JSON line:
//   first_motion_ms  from the drag's first move to the first frame of the moved
//                    camera reaching the view (the view's coarse_frame_rendered
//                    or frame_rendered signal: the image is handed to paint),
//   first_motion     that frame's algorithm and scale,
//   frames_during_drag, longest_gap_ms  frames shown while the drag lasts,
//   refined_ms       from the release to the full frame of the chosen algorithm.
// It uses only what the window offered before preview-then-refine (issue 27), so
// the script builds it against an older commit too and compares the two.
//
//   oit-interaction-probe MODEL ALGORITHM [WxH] [DRAG_MS]
#include <QApplication>
#include <QElapsedTimer>
#include <QMouseEvent>
#include <QTimer>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <vector>

#include "main_window.h"
#include "render_view.h"

namespace {

bool wait_for(QApplication &app, const std::function<bool()> &done, int timeout_ms)
{
    QElapsedTimer clock;
    clock.start();
    while (!done()) {
        if (clock.elapsed() > timeout_ms)
            return false;
        app.processEvents(QEventLoop::AllEvents, 5);
    }
    return true;
}

void send_mouse(QWidget *view, QEvent::Type type, QPoint position, Qt::MouseButton button, Qt::MouseButtons buttons)
{
    QMouseEvent event(type, position, view->mapToGlobal(position), button, buttons, Qt::NoModifier);
    QApplication::sendEvent(view, &event);
}

} // namespace

int main(int argc, char **argv)
{
    // models are imported by this program run again as a contained worker (as the workbench's)
    if (oit_import_worker_requested(argc, argv))
        return oit_import_worker_main(argc, argv);
    QApplication app(argc, argv);
    QCoreApplication::setOrganizationName("oit-workbench-probe");
    QCoreApplication::setApplicationName("oit-interaction-probe");
    if (argc < 3) {
        std::fprintf(stderr, "usage: oit-interaction-probe MODEL ALGORITHM [WxH] [DRAG_MS]\n");
        return 2;
    }
    int width = 1200, height = 760, drag_ms = 1500;
    if (argc > 3 && std::sscanf(argv[3], "%dx%d", &width, &height) != 2)
        return 2;
    if (argc > 4)
        drag_ms = std::atoi(argv[4]);

    MainWindow window(MainWindow::Start::Untouched);
    if (!window.startup_error().isEmpty()) {
        std::fprintf(stderr, "oit-interaction-probe: %s\n", window.startup_error().toLocal8Bit().constData());
        return 3;
    }
    window.set_algorithm(argv[2]);
    window.show();
    RenderView *view = window.view();
    view->setFixedSize(width, height);
    bool loaded = false, failed = false;
    QObject::connect(&window, &MainWindow::model_loaded, &app, [&loaded] { loaded = true; });
    QObject::connect(&window, &MainWindow::model_failed, &app, [&failed] { failed = true; });
    QElapsedTimer load_clock;
    load_clock.start();
    window.load_model(argv[1]);
    if (!wait_for(app, [&] { return failed || (loaded && view->settled()); }, 600000) || failed) {
        std::fprintf(stderr, "oit-interaction-probe: the first full frame did not come (%s)\n",
                     window.last_error().toLocal8Bit().constData());
        return 3;
    }
    double first_full_ms = double(load_clock.elapsed());
    uint64_t shown_before = view->last_result() ? view->last_result()->id : 0;

    QElapsedTimer clock;
    std::vector<double> shown_at;     // ms since the drag's first move
    FrameResultPointer first;         // the first frame of the moved camera
    double first_ms = -1.0;
    bool dragging = false;
    auto on_frame = [&] {
        FrameResultPointer r = view->last_result();
        if (!clock.isValid() || !r || r->id <= shown_before)
            return;
        double t = double(clock.nsecsElapsed()) / 1e6;
        if (!first) {
            first = r;
            first_ms = t;
        }
        if (dragging)
            shown_at.push_back(t);
    };
    QObject::connect(view, &RenderView::coarse_frame_rendered, &app, on_frame);
    QObject::connect(view, &RenderView::frame_rendered, &app, on_frame);

    QPoint at(width / 2, height / 2);
    send_mouse(view, QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::LeftButton);
    dragging = true;
    clock.start();
    int moves = 0;
    while (clock.elapsed() < drag_ms) {
        at += QPoint(moves % 2 ? 3 : 4, 1);
        send_mouse(view, QEvent::MouseMove, at, Qt::NoButton, Qt::LeftButton);
        ++moves;
        QElapsedTimer tick;
        tick.start();
        while (tick.elapsed() < 16)
            app.processEvents(QEventLoop::AllEvents, 16 - int(tick.elapsed()));
    }
    double drag_end = double(clock.nsecsElapsed()) / 1e6;
    dragging = false;
    send_mouse(view, QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton);
    // the first moved frame may come after the release (a slow coarse frame)
    bool refined = wait_for(app, [&] { return view->settled() && first; }, 600000);
    double refined_ms = double(clock.nsecsElapsed()) / 1e6 - drag_end;
    double longest_gap = 0.0, previous = 0.0;
    for (double t : shown_at) {
        longest_gap = std::max(longest_gap, t - previous);
        previous = t;
    }
    longest_gap = std::max(longest_gap, drag_end - previous);
    std::printf("{\"model\": \"%s\", \"algorithm\": \"%s\", \"size\": [%d, %d], \"drag_ms\": %.0f, \"moves\": %d, "
                "\"first_full_frame_ms\": %.0f, \"first_motion_ms\": %.1f, \"first_motion\": {\"algorithm\": \"%s\", "
                "\"coarse_scale\": %d}, \"frames_during_drag\": %zu, \"longest_gap_ms\": %.1f, \"refined_ms\": %.0f, "
                "\"refined\": %s}\n",
                argv[1], argv[2], width, height, drag_end, moves, first_full_ms, first_ms,
                first ? first->algorithm.c_str() : "", first ? first->coarse_scale : 0, shown_at.size(), longest_gap,
                refined ? refined_ms : -1.0, refined ? "true" : "false");
    return refined ? 0 : 3;
}
