// test_workbench_views.cpp: the workbench's Qt Test cases on picking, views, undo, the error
// and split views, comparisons, tooltips, 100,000 parts, an assembly's parts tree and dropped
// files (workbench_test.h).
#include "workbench_test.h"

void WorkbenchTest::clicking_a_part_selects_it()
{
    frame();
    QPoint centre(view_size.width() / 2, view_size.height() / 2);
    std::vector<float> storage;
    oit_frame_settings f = window->view()->current_frame(storage);
    std::string error;
    ContributorPick expected = pick_contributor(*window->model(), f, centre.x(), centre.y(), 1, error);
    QVERIFY2(expected.component >= 0, "the gearbox covers the centre of the view");
    QTest::mouseClick(window->view(), Qt::LeftButton, Qt::NoModifier, centre);
    QCOMPARE(window->parts_panel()->selected_parts(), std::vector<int>{expected.component});
    QVERIFY2(window->status_text().startsWith("picked part " +
                                               QString(window->model()->components[expected.component].name)),
             qPrintable(window->status_text()));
    // a drag is not a click: it turns the model and keeps the selection
    QTest::mousePress(window->view(), Qt::LeftButton, Qt::NoModifier, QPoint(5, 5));
    QMouseEvent move(QEvent::MouseMove, QPoint(40, 5), Qt::LeftButton, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(window->view(), &move);
    QTest::mouseRelease(window->view(), Qt::LeftButton, Qt::NoModifier, QPoint(40, 5));
    QCOMPARE(window->parts_panel()->selected_parts(), std::vector<int>{expected.component});
    // a click on the background selects nothing new
    window->view()->reset_camera();
    frame();
    QTest::mouseClick(window->view(), Qt::LeftButton, Qt::NoModifier, QPoint(1, 1));
    QCOMPARE(window->status_text(), QString("nothing under the pointer"));
}

// The click picks what `oit pick` names for the copied command at that pixel:
// through the housing at 5% the part behind it, Alt+click the next one, and the
// housing itself when it is opaque (issue 27).
void WorkbenchTest::a_click_picks_what_oit_pick_names()
{
    QString oit = qEnvironmentVariable("OIT_CLI");
    if (oit.isEmpty())
        QSKIP("OIT_CLI is not set");
    const oit_model *model = window->model();
    int housing = -1;
    for (uint32_t i = 0; i < model->component_count; ++i)
        if (QString(model->components[i].name) == "housing")
            housing = int(i);
    QVERIFY2(housing >= 0, "the gearbox has a housing");
    QPoint centre(view_size.width() / 2, view_size.height() / 2);
    // `oit pick` with the view's copied command: the same camera, opacities and size
    auto oit_pick = [&](int rank) {
        QString command = window->render_command_for_view(work + "/pick-unused.png");
        int at = command.indexOf(" render ");
        if (at >= 0)
            command.replace(at, 8, " pick ");
        command += QString(" --json --pixel %1,%2 --rank %3").arg(centre.x()).arg(centre.y()).arg(rank);
        QProcess process;
        process.start("bash", {"-c", command});
        process.waitForFinished(60000);
        if (process.exitCode() != 0)
            qWarning().noquote() << command << process.readAllStandardError();
        return QJsonDocument::fromJson(process.readAllStandardOutput()).object();
    };
    auto picked = [&]() {
        std::vector<int> selected = window->parts_panel()->selected_parts();
        return selected.size() == 1 ? selected[0] : -1;
    };
    settings().alpha = 1.0f;
    window->set_part_alpha(housing, 0.05f);
    window->settings_changed();
    frame();
    QJsonObject first = oit_pick(1), second = oit_pick(2);
    QVERIFY2(!first.isEmpty() && !second.isEmpty(), "oit pick answers");
    QVERIFY2(first["index"].toInt() != housing, "through the housing at 5% a part behind it is picked");
    QTest::mouseClick(window->view(), Qt::LeftButton, Qt::NoModifier, centre);
    QCOMPARE(picked(), first["index"].toInt());
    QVERIFY2(window->status_text().contains("contributor 1 of"), qPrintable(window->status_text()));
    QTest::mouseClick(window->view(), Qt::LeftButton, Qt::AltModifier, centre);
    QCOMPARE(picked(), second["index"].toInt());
    QVERIFY2(window->status_text().contains("contributor 2 of"), qPrintable(window->status_text()));
    // the housing opaque: the housing, as `oit pick` says
    window->set_part_alpha(housing, 1.0f);
    window->settings_changed();
    frame();
    first = oit_pick(1);
    QCOMPARE(first["index"].toInt(), housing);
    QTest::mouseClick(window->view(), Qt::LeftButton, Qt::NoModifier, centre);
    QCOMPARE(picked(), housing);
}

void WorkbenchTest::frame_selection_and_standard_views()
{
    QImage whole = frame();
    const oit_model *model = window->model();
    // the part with the smallest bounds: framing it fills the view with it
    auto bounds = [model](int part, glm::vec3 &lo, glm::vec3 &hi) {
        const oit_component &c = model->components[part];
        lo = glm::vec3(INFINITY);
        hi = glm::vec3(-INFINITY);
        for (uint32_t t = c.first_triangle; t < c.first_triangle + c.triangle_count; ++t)
            for (int k = 0; k < 3; ++k) {
                const float *p = model->positions + size_t(model->indices[t * 3 + k]) * 3;
                lo = glm::min(lo, glm::vec3(p[0], p[1], p[2]));
                hi = glm::max(hi, glm::vec3(p[0], p[1], p[2]));
            }
    };
    int smallest = 0;
    float smallest_size = INFINITY;
    glm::vec3 lo, hi;
    for (uint32_t i = 0; i < model->component_count; ++i) {
        bounds(int(i), lo, hi);
        if (glm::length(hi - lo) < smallest_size) {
            smallest_size = glm::length(hi - lo);
            smallest = int(i);
        }
    }
    QVERIFY(smallest_size < 0.5f * model->radius);
    window->frame_parts({smallest});
    bounds(smallest, lo, hi);
    // bounds are relative to the model's origin; the camera is in file coordinates
    const glm::dvec3 origin(model->origin[0], model->origin[1], model->origin[2]);
    QVERIFY(glm::length(camera().target - origin - 0.5 * glm::dvec3(lo + hi)) < 1e-4 * model->radius);
    QVERIFY2(compare(whole, frame(), 8).share_over > 0.05, "framing a part changes the view");
    // standard views look along the axes (View > Standard view, Alt+1..7)
    auto forward = [this] { return glm::vec3(camera().orientation * glm::dvec3(0, 0, -1)); };
    auto trigger = [this](const QString &text, const QKeySequence &key) {
        for (QAction *action : window->findChildren<QAction *>())
            if (action->text() == text && action->shortcut() == key) {
                action->trigger();
                return true;
            }
        return false;
    };
    QVERIFY(trigger("&Top", QKeySequence("Alt+5")));
    QVERIFY(glm::length(forward() - glm::vec3(0, -1, 0)) < 1e-5f);
    QVERIFY(trigger("&Front", QKeySequence("Alt+1")));
    QVERIFY(glm::length(forward() - glm::vec3(0, 0, -1)) < 1e-5f);
    QVERIFY(trigger("&Right", QKeySequence("Alt+4"))); // looking towards -x
    QVERIFY(glm::length(forward() - glm::vec3(-1, 0, 0)) < 1e-5f);
    QImage right = frame();
    QVERIFY(ink(right) > 0.01);
}

void WorkbenchTest::undo_and_redo_settings()
{
    RenderSettings &s = settings();
    window->reset_settings_history(); // init()'s reset is not a step
    QVERIFY(!window->undo_settings());
    window->alpha_slider()->setValue(window->alpha_slider()->maximum() / 4);
    window->alpha_slider()->setValue(window->alpha_slider()->maximum() / 5); // the same step (coalesced)
    float dragged = s.alpha;
    QTest::qWait(SettingsModel::kUndoCoalesceMs + 100);
    window->set_algorithm("ddp");
    QVERIFY(window->undo_settings());
    QCOMPARE(QString::fromStdString(s.algorithm), QString("ll"));
    QCOMPARE(s.alpha, dragged);
    QVERIFY(window->undo_settings());
    QCOMPARE(s.alpha, 0.5f); // before the drag
    QVERIFY(window->redo_settings());
    QCOMPARE(s.alpha, dragged);
    QVERIFY(window->redo_settings());
    QCOMPARE(QString::fromStdString(s.algorithm), QString("ddp"));
    QVERIFY(!window->redo_settings());
    // the panel follows: the algorithm menu's check and the combo box
    frame();
    bool checked = false;
    for (QAction *action : window->findChildren<QAction *>())
        if (action->text() == "ddp")
            checked = action->isChecked();
    QVERIFY(checked);
    window->set_camera_mode(Camera::Mode::Orbit, true);
    for (QAction *action : window->findChildren<QAction *>())
        if (action->text() == "&Orthographic")
            QVERIFY(action->isChecked());
    window->set_camera_mode(Camera::Mode::Orbit, false);
}

// The error view: the map against the CPU reference, its legend and figures.
void WorkbenchTest::error_view_maps_the_difference_against_the_reference()
{
    RenderView *view = window->view();
    window->set_algorithm("dp");
    QImage plain = frame();
    // on: dp is exact here: every pixel of the map is black
    window->set_error_view(true);
    QImage shown = frame();
    FrameResultPointer dp = view->last_result();
    QVERIFY2(dp->error_map.present, qPrintable(dp->error_map.problem));
    QCOMPARE(dp->error_map.map.size(), view_size);
    QCOMPARE(dp->error_map.figures.max, 0);
    QVERIFY(!dp->error_map.reference_cached); // the first time: rendered
    QRect legend = view->legend()->geometry();
    QVERIFY2(view->legend()->isVisible(), "the legend shows with the map");
    QVERIFY(legend.width() < view_size.width() && legend.height() < view_size.height() / 2);
    QImage black(view_size, QImage::Format_RGBA8888);
    black.fill(Qt::black);
    QCOMPARE(compare(dp->error_map.map, black, 0).max, 0);
    // what the widget shows is the map (outside the legend's corner)
    QRect above_legend(0, 0, view_size.width(), legend.top());
    QCOMPARE(max_difference_in(shown, black, above_legend), 0);
    QVERIFY2(window->status_text().contains("vs reference: rmse 0.000, psnr inf, ssim 1.00000, max 0"),
             qPrintable(window->status_text()));
    auto *figures = window->compare_panel()->findChild<QLabel *>("error_figures");
    QVERIFY(figures && figures->text().contains("dp vs reference"));
    // ll: the same camera, so the reference comes from the cache; exact within 1/255
    // (ll composites in float: a few channels round the other way)
    window->set_algorithm("ll");
    frame();
    FrameResultPointer ll = view->last_result();
    QVERIFY(ll->error_map.present);
    QVERIFY2(ll->error_map.reference_cached,
             "switching algorithm with the same camera reuses the reference");
    qInfo("ll vs reference: %s", qPrintable(error_figures_text(ll->error_map.figures)));
    QVERIFY(ll->error_map.figures.max <= 1);
    QCOMPARE(hot_pixels(ll->error_map.map), 0);
    // blend: submission order, far from the reference: yellow and red pixels
    window->set_algorithm("blend");
    QImage blend_map = frame();
    FrameResultPointer blend = view->last_result();
    QVERIFY(blend->error_map.present && blend->error_map.reference_cached);
    qInfo("blend vs reference: %s, %d hot pixels",
          qPrintable(error_figures_text(blend->error_map.figures)), hot_pixels(blend->error_map.map));
    QVERIFY(blend->error_map.figures.max > 32);
    QVERIFY(hot_pixels(blend->error_map.map) > 20);
    QVERIFY(hot_pixels(blend_map.copy(above_legend)) > 0);
    // the legend's bar follows the core's scale: 1 at its left end, 64+ at its right
    QCOMPARE(ErrorLegend::difference_at(0, 100), 1);
    QCOMPARE(ErrorLegend::difference_at(99, 100), OIT_ERROR_MAP_SATURATION);
    // a turned camera needs its own reference; coarse frames skip it and show the plain image
    view->set_slow_frame_ms(0.0);
    FrameResultPointer coarse;
    QImage coarse_shown;
    bool legend_with_coarse = true;
    QMetaObject::Connection on_coarse = connect(view, &RenderView::coarse_frame_rendered, this, [&] {
        coarse = view->last_result();
        coarse_shown = view->shown_a();
        legend_with_coarse = view->legend()->isVisible();
    });
    camera().trackball(glm::vec2(80, 60), glm::vec2(95, 55), view_size.width(), view_size.height());
    view->request_frame(true);
    QTRY_VERIFY_WITH_TIMEOUT(coarse != nullptr, 60000);
    disconnect(on_coarse);
    QVERIFY(!coarse->error_map.present && coarse->error_map.reference_ms == 0.0);
    QCOMPARE(compare(coarse_shown, coarse->image, 0).max, 0);
    QVERIFY(!legend_with_coarse);
    frame(); // refined once the input rests: with its map, from a new reference
    QVERIFY(view->last_result()->error_map.present && !view->last_result()->error_map.reference_cached);
    view->set_slow_frame_ms(RenderView::kSlowFrameMs);
    // Copy as command adds the command line's error flags
    QString command = window->render_command_for_view("view.png");
    QVERIFY2(command.contains("--error-vs-reference --error-map view-error.png --out view.png"),
             qPrintable(command));
    // off again: the plain image, no legend
    view->reset_camera();
    window->set_algorithm("dp");
    window->set_error_view(false);
    QCOMPARE(compare(frame(), plain, 0).max, 0);
    QVERIFY(!view->legend()->isVisible());
    QVERIFY(!window->render_command_for_view("view.png").contains("--error"));
}

// The split view: A left of the wipe line, B right, the same camera.
void WorkbenchTest::split_view_shows_two_algorithms()
{
    RenderView *view = window->view();
    const int w = view_size.width(), h = view_size.height();
    window->set_algorithm("ll");
    QImage ll = frame();
    window->set_algorithm("blend");
    QImage blend = frame();
    window->set_algorithm("ll");
    window->set_split(SplitMode::Wipe, "blend");
    QCOMPARE(window->compare_panel()->split_combo()->currentIndex(), int(SplitMode::Wipe));
    QCOMPARE(window->compare_panel()->algorithm_b_combo()->currentText(), QString("blend"));
    QImage split = frame();
    FrameResultPointer result = view->last_result();
    QVERIFY(result->split && result->b.status == OIT_OK);
    QCOMPARE(QString::fromStdString(result->b.algorithm), QString("blend"));
    // left of the line (less its band and the labels) is ll's image, right of it blend's
    int line = split_view::wipe_x(0.5f, w);
    QCOMPARE(line, w / 2);
    const int band = split_view::kHandleRadius + 3, top = 30;
    QRect left(0, top, line - band, h - top), right(line + band, top, w - line - band, h - top);
    QCOMPARE(max_difference_in(split, ll, left), 0);
    QCOMPARE(max_difference_in(split, blend, right), 0);
    QVERIFY2(max_difference_in(ll, blend, left) > 8 && max_difference_in(ll, blend, right) > 8,
             "ll and blend differ on both sides (else this case proves nothing)");
    // drag the line to a quarter of the view: what was ll between there and the middle is blend now
    QSignalSpy done(view->worker(), &RenderWorker::frame_done);
    QPoint grab(line + 2, h - 20);
    QTest::mousePress(view, Qt::LeftButton, Qt::NoModifier, grab);
    QMouseEvent move(QEvent::MouseMove, QPoint(w / 4, h - 20), Qt::LeftButton, Qt::LeftButton,
                     Qt::NoModifier);
    QApplication::sendEvent(view, &move);
    QTest::mouseRelease(view, Qt::LeftButton, Qt::NoModifier, QPoint(w / 4, h - 20));
    QCOMPARE(settings().wipe, 0.25f);
    QCOMPARE(window->compare_panel()->findChild<QDoubleSpinBox *>("wipe")->value(), 0.25);
    QTest::qWait(50);
    QCOMPARE(done.count(), 0); // only the boundary moved: nothing rendered
    QVERIFY(!view->rendering());
    QImage dragged = view->grab().toImage().convertToFormat(QImage::Format_RGBA8888);
    int moved = split_view::wipe_x(0.25f, w);
    QRect now_b(moved + band, top, line - moved - band, h - top);
    QCOMPARE(max_difference_in(dragged, blend, now_b), 0);
    QVERIFY(max_difference_in(dragged, ll, now_b) > 8);
    QCOMPARE(max_difference_in(dragged, ll, QRect(0, top, moved - band, h - top)), 0);
    // the camera still turns with a drag away from the line
    settings().wipe = 0.5f;
    window->sync_panel_from_settings();

    // error view and split view together: each side's map, one reference
    window->set_error_view(true);
    QImage maps = frame();
    result = view->last_result();
    QVERIFY(result->error_map.present && result->b.error_map.present);
    QVERIFY(result->error_map.figures.max <= 1);   // ll
    QVERIFY(result->b.error_map.figures.max > 32); // blend
    QVERIFY2(result->b.error_map.reference_cached, "side B reuses side A's reference (the same frame)");
    int legend_top = view->legend()->geometry().top(); // the legend's bar is hot on its right
    QCOMPARE(hot_pixels(maps.copy(left.intersected(QRect(0, 0, w, legend_top)))), 0);
    QVERIFY(hot_pixels(maps.copy(right.intersected(QRect(0, 0, w, legend_top)))) > 0);
    window->set_error_view(false);

    // side by side: each side at half the width, the same camera for that aspect
    window->set_split(SplitMode::SideBySide);
    QImage pair = frame();
    result = view->last_result();
    QCOMPARE(result->image.size(), QSize(w / 2, h));
    QCOMPARE(result->b.image.size(), QSize(w / 2, h));
    QCOMPARE(view->side_pixel_size(), QSize(w / 2, h));
    QRect half_left(0, top, w / 2, h - top), half_right(w / 2 + 1, top, w / 2 - 1, h - top);
    QCOMPARE(max_difference_in(pair.copy(0, 0, w / 2, h), result->image, half_left), 0);
    QCOMPARE(max_difference_in(pair.copy(w / 2, 0, w / 2, h), result->b.image,
                               half_right.translated(-w / 2, 0)),
             0);
    // each half is what that algorithm renders alone at that size (Export PNG: `oit render`'s frame)
    QString error;
    QVERIFY2(window->export_png(work + "/side-a.png", w / 2, h, error), qPrintable(error));
    QCOMPARE(compare(QImage(work + "/side-a.png"), result->image, 0).max, 0);
    QImage b_half = result->b.image;
    // Copy as command: side A at the half's size, and the Messages say so
    window->copy_command();
    if (auto *dialog = window->findChild<QDialog *>("copied_command"))
        dialog->close();
    QString command = window->render_command_for_view("view.png");
    QVERIFY2(command.contains("--algorithm ll --size 80x120"), qPrintable(command));
    QVERIFY2(window->messages().last().contains("split view: the command line has no split view: the "
                                                "command renders side A (ll) at half the view's width"),
             qPrintable(window->messages().last()));
    // blend as side A (a half's matrices are widened to frame what the whole view
    // frames, so the export stays side by side) renders what side B showed
    window->set_algorithm("blend");
    QVERIFY2(window->export_png(work + "/side-b.png", w / 2, h, error), qPrintable(error));
    QCOMPARE(compare(QImage(work + "/side-b.png"), b_half, 0).max, 0);
    window->set_split(SplitMode::Off);
    QCOMPARE(compare(frame(), blend, 0).max, 0); // back to one algorithm over the whole view
}

// The split and error views are settings: presets, undo and the menu follow them.
void WorkbenchTest::comparisons_are_settings()
{
    window->set_error_view(true);
    window->set_split(SplitMode::SideBySide, "wboit");
    QString path = work + "/compare.json";
    QString error;
    QVERIFY2(window->save_preset(path, error), qPrintable(error));
    window->set_error_view(false);
    window->set_split(SplitMode::Off);
    QVERIFY2(window->load_preset(path, error), qPrintable(error));
    const RenderSettings &s = settings();
    QVERIFY(s.error_view);
    QCOMPARE(int(s.split), int(SplitMode::SideBySide));
    QCOMPARE(QString::fromStdString(s.split_algorithm), QString("wboit"));
    bool checked = false;
    for (QAction *action : window->findChildren<QAction *>())
        if (action->text() == "Side &by side")
            checked = action->isChecked();
    QVERIFY(checked);
    QVERIFY(window->compare_panel()->error_check()->isChecked());
    frame();
    // undo steps back through the load, and redo returns
    window->reset_settings_history();
    window->set_split(SplitMode::Wipe, "ddp");
    QVERIFY(window->undo_settings());
    QCOMPARE(int(s.split), int(SplitMode::SideBySide));
    QCOMPARE(QString::fromStdString(s.split_algorithm), QString("wboit"));
    QVERIFY(window->redo_settings());
    QCOMPARE(QString::fromStdString(s.split_algorithm), QString("ddp"));
    // bad values name the key
    QFile bad(work + "/bad-split.json");
    QVERIFY(bad.open(QIODevice::WriteOnly));
    bad.write("{\n\"split\": \"diagonal\"\n}\n");
    bad.close();
    QVERIFY(!window->load_preset(work + "/bad-split.json", error));
    QVERIFY2(error.endsWith("bad-split.json:2: \"split\": must be off, wipe or side-by-side"),
             qPrintable(error));
    window->set_error_view(false);
    window->set_split(SplitMode::Off);
    frame();
}

void WorkbenchTest::every_control_has_a_tooltip()
{
    auto *tabs = window->findChild<QTabWidget *>();
    QStringList missing;
    for (QWidget *w : tabs->findChildren<QWidget *>()) {
        bool control = qobject_cast<QAbstractButton *>(w) || qobject_cast<QComboBox *>(w) ||
                       qobject_cast<QAbstractSpinBox *>(w) || qobject_cast<QAbstractSlider *>(w) ||
                       qobject_cast<QLineEdit *>(w);
        // Qt's own parts of a control (a spin box's line edit, a clear button, a tab bar's arrows) are its
        bool qt_internal = w->objectName().startsWith("qt_") || w->inherits("QLineEditIconButton") ||
                           qobject_cast<QTabBar *>(w->parentWidget()) || qobject_cast<QScrollBar *>(w);
        if (control && !qt_internal && w->toolTip().isEmpty())
            missing << QString("%1 '%2'").arg(w->metaObject()->className(), w->objectName());
    }
    QVERIFY2(missing.isEmpty(), qPrintable(missing.join(", ")));
}

// A 100,000-part assembly (docs/cli.md, "Assemblies"): the load shows
// progress, the parts list is a model/view that appears at once, and the GUI
// never waits long, while loading, rendering and scrolling.
void WorkbenchTest::hundred_thousand_parts()
{
    QString path = work + "/parts100k.obj";
    {
        QFile file(path);
        QVERIFY(file.open(QIODevice::WriteOnly));
        QTextStream out(&file);
        int v = 1;
        for (int part = 0; part < 100000; ++part) {
            float x = float(part % 316), y = float(part / 316);
            out << "o part_" << QString("%1").arg(part, 6, 10, QChar('0')) << "\n";
            out << "v " << x << " " << y << " 0\nv " << x + 0.8f << " " << y << " 0\nv " << x << " " << y + 0.8f
                << " 0.5\n";
            out << "f " << v << " " << v + 1 << " " << v + 2 << "\n";
            v += 3;
        }
    }
    QSignalSpy loaded(window, &MainWindow::model_loaded);
    LatencyProbe probe;
    window->load_model(path);
    auto *progress = window->findChild<QProgressBar *>();
    QVERIFY2(progress && progress->isVisible(), "the load shows progress");
    QElapsedTimer clock;
    clock.start();
    while (loaded.isEmpty() && clock.elapsed() < 120000) {
        probe.post();
        QVERIFY(ms_until([&probe] { return !probe.pending(); }, 10000) >= 0.0);
        QTest::qWait(5);
    }
    QCOMPARE(loaded.count(), 1);
    QCOMPARE(window->model()->component_count, 100000u);
    QCOMPARE(window->parts_panel()->view()->model()->rowCount(), 100000);
    // first frames and scrolling the list, while the worker renders
    window->show_tab("parts");
    for (int step = 0; step < 20; ++step) {
        probe.post();
        QVERIFY(ms_until([&probe] { return !probe.pending(); }, 10000) >= 0.0);
        window->parts_panel()->view()->verticalScrollBar()->setValue(
            window->parts_panel()->view()->verticalScrollBar()->maximum() * step / 19);
        QTest::qWait(20);
    }
    frame();
    qInfo("100,000 parts: %d posted events, the longest wait %.1f ms", probe.handled, probe.worst_ms);
    // The load's one long event (the model installed, 100,000 rows made, the
    // settings written) takes 20-40 ms here; AddressSanitizer's checks make it
    // 3-4 times slower (75-120 ms measured), so that build gets 3 times the budget.
#if defined(__SANITIZE_ADDRESS__)
    const double budget_ms = 300.0;
#else
    const double budget_ms = 100.0;
#endif
    QVERIFY2(probe.worst_ms < budget_ms, qPrintable(QString("an event waited %1 ms").arg(probe.worst_ms)));
    // a part past the GPU's per-part limit is picked and selected as any other
    window->parts_panel()->select_part(99999);
    QCOMPARE(window->parts_panel()->selected_parts(), std::vector<int>{99999});
    window->load_model(MainWindow::default_model_path());
    QVERIFY(loaded.wait(60000));
    window->show_tab("algorithm");
}

// A glTF with an assembly tree (tests/assembly_gltf.py): an assembly's slider
// is one undo step over every part under it, and a click on a part in the view
// opens its assemblies in the Parts tab.
void WorkbenchTest::parts_tree_of_an_assembly()
{
    const QString path = work + "/assembly.gltf";
    QProcess python;
    python.start("python3", {MainWindow::source_root() + "/tests/assembly_gltf.py", path});
    QVERIFY(python.waitForFinished(30000));
    QCOMPARE(python.exitCode(), 0);
    const QJsonArray expected = QJsonDocument::fromJson(python.readAllStandardOutput()).array(); // [name, path]
    QSignalSpy loaded(window, &MainWindow::model_loaded);
    window->load_model(path);
    QVERIFY(loaded.wait(60000));
    QCOMPARE(int(window->model()->component_count), expected.size());
    window->show_tab("parts");
    PartsPanel *panel = window->parts_panel();
    auto *tree = qobject_cast<QTreeView *>(panel->view());
    QAbstractItemModel *rows = tree->model();
    QCOMPARE(rows->rowCount(), 1); // gearbox
    const QModelIndex gearbox = rows->index(0, 0);
    QModelIndex output;
    for (int r = 0; r < rows->rowCount(gearbox); ++r)
        if (rows->index(r, 0, gearbox).data().toString() == "output_shaft")
            output = rows->index(r, 0, gearbox);
    QVERIFY(output.isValid());

    // output_shaft's slider: every part under it, one undo step
    window->reset_settings_history();
    QVERIFY(rows->setData(output.siblingAtColumn(PartsModel::OpacityColumn), 0.25, PartsModel::AlphaRole));
    int under = 0;
    for (int c = 0; c < expected.size(); ++c) {
        const bool in = expected[c].toArray()[1].toString().startsWith("gearbox/output_shaft/");
        QCOMPARE(settings().part_alpha[size_t(c)], in ? 0.25f : 1.0f);
        under += in;
    }
    QVERIFY(under >= 2);
    const QImage faded = frame();
    QVERIFY(window->undo_settings());
    QVERIFY(!window->undo_settings()); // one step, not one per part
    for (int c = 0; c < expected.size(); ++c) {
        QCOMPARE(settings().part_alpha[size_t(c)], 1.0f);
        QCOMPARE(panel->alpha()[size_t(c)], 1.0f);
    }
    QVERIFY(compare(faded, frame(), 0).max > 0);

    // a click on a part two assemblies down, in a closed tree, reveals it
    tree->collapseAll();
    std::vector<float> storage;
    oit_frame_settings f = window->view()->current_frame(storage);
    QPoint target(-1, -1);
    int part = -1;
    for (int y = 4; y < view_size.height() && part < 0; y += 8)
        for (int x = 4; x < view_size.width() && part < 0; x += 8) {
            const PickResult hit = pick(*window->model(), f.modelview, f.projection, f.width, f.height, x + 0.5,
                                        y + 0.5, settings().part_alpha, settings().part_visible);
            if (hit.component >= 0 && expected[hit.component].toArray()[1].toString().count('/') >= 2) {
                part = hit.component;
                target = QPoint(x, y);
            }
        }
    QVERIFY2(part >= 0, "a part under a subassembly is in view");
    QTest::mouseClick(window->view(), Qt::LeftButton, Qt::NoModifier, target);
    QCOMPARE(panel->selected_parts(), std::vector<int>{part});
    const QModelIndex current = tree->currentIndex().siblingAtColumn(0);
    QCOMPARE(current.data().toString(), expected[part].toArray()[0].toString());
    for (QModelIndex parent = current.parent(); parent.isValid(); parent = parent.parent())
        QVERIFY(tree->isExpanded(parent));
    QVERIFY(tree->viewport()->rect().contains(tree->visualRect(current).center()));
    QVERIFY2(window->status_text().startsWith("picked part " + expected[part].toArray()[1].toString() + " ("),
             qPrintable(window->status_text()));

    window->load_model(MainWindow::default_model_path());
    QVERIFY(loaded.wait(60000));
    window->show_tab("algorithm");
}

void WorkbenchTest::dropping_files()
{
    // a preset dropped on the window is applied
    QString preset = work + "/dropped.json";
    QFile file(preset);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write("{\"algorithm\": \"wboit\", \"alpha\": 0.25}\n");
    file.close();
    auto drop = [this](const QString &path) {
        QMimeData data;
        data.setUrls({QUrl::fromLocalFile(path)});
        QDragEnterEvent enter(QPoint(10, 10), Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(window, &enter);
        QVERIFY(enter.isAccepted());
        QDropEvent event(QPointF(10, 10), Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(window, &event);
    };
    drop(preset);
    QCOMPARE(QString::fromStdString(settings().algorithm), QString("wboit"));
    QCOMPARE(settings().alpha, 0.25f);
    // a model file dropped on the window is loaded
    QSignalSpy loaded(window, &MainWindow::model_loaded);
    drop("/usr/share/assimp/models/OBJ/spider.obj");
    QVERIFY(loaded.wait(60000));
    QVERIFY(window->model_path().endsWith("spider.obj"));
    QCOMPARE(window->model()->component_count, 19u);
    QVERIFY(ink(frame()) > 0.01);
}
