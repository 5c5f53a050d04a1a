// main_window.cpp: see main_window.h.
#include "main_window.h"
#include "algorithm_panel.h"
#include "camera_panel.h"
#include "compare_panel.h"
#include "file_io.h"
#include "measure_tool.h"
#include "opacity_panel.h"
#include "parts_panel.h"
#include "pick.h"
#include "screen_fit.h"
#include "section_overlay.h"
#include "sections_panel.h"
#include "histogram_plot.h"
#include "stats_panel.h"
#include "views_panel.h"

#include <QAction>
#include <QCoreApplication>
#include <QCloseEvent>
#include <QDir>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileInfo>
#include <QGuiApplication>
#include <QLabel>
#include <QVBoxLayout>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QScreen>
#include <QPushButton>
#include <QStatusBar>
#include <QTabWidget>
#include <QTime>

#include <cmath>
#include <cstdio>

// ------------------------------------------------------------ construction

MainWindow::MainWindow(Start start, QWidget *parent)
    : QMainWindow(parent), capabilities_(capability_table()), start_(start)
{
    setWindowTitle("oit-workbench");
    setAcceptDrops(true);
    settings_ = new SettingsModel(this);
    view_ = new RenderView(*settings_, this);
    setCentralWidget(view_);

    QTabWidget *tabs = build_tabs();
    auto *dock = new QDockWidget("Settings", this);
    dock->setObjectName("settings");
    dock->setWidget(tabs);
    dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable |
                      QDockWidget::DockWidgetClosable);
    addDockWidget(Qt::RightDockWidgetArea, dock);
    // never wider than this, even from a layout saved before the panel was narrow (616 px)
    dock->setMaximumWidth(kSettingsPanelMaxWidth);
    settings_dock_ = dock;

    // loading and long frames: what runs, a busy bar, and a Cancel
    progress_label_ = new QLabel;
    progress_label_->hide();
    progress_ = new QProgressBar;
    progress_->setRange(0, 0); // busy: neither Assimp nor a peel count knows its end
    progress_->setMaximumWidth(120);
    progress_->hide();
    cancel_button_ = new QPushButton("Cancel");
    cancel_button_->setObjectName("cancel_frame");
    cancel_button_->setToolTip("abandon the frame being rendered (Esc); the view keeps the last frame");
    cancel_button_->hide();
    connect(cancel_button_, &QPushButton::clicked, this, [this] { view_->cancel_frame(); });
    status_label_ = new QLabel;
    statusBar()->addWidget(status_label_, 1);
    statusBar()->addPermanentWidget(progress_label_);
    statusBar()->addPermanentWidget(progress_);
    statusBar()->addPermanentWidget(cancel_button_);

    messages_ = new QPlainTextEdit;
    messages_->setObjectName("messages");
    messages_->setReadOnly(true);
    messages_->setMaximumBlockCount(2000);
    messages_->setToolTip("loads, exports, copies, warnings and errors, newest last");
    auto *messages_dock = new QDockWidget("Messages", this);
    messages_dock->setObjectName("messages_dock");
    messages_dock->setWidget(messages_);
    addDockWidget(Qt::BottomDockWidgetArea, messages_dock);
    resizeDocks({messages_dock}, {90}, Qt::Vertical);

    loader_ = new ModelLoader(this);
    connect(loader_, &ModelLoader::loaded, this, &MainWindow::load_finished);
    connect(loader_, &ModelLoader::failed, this, [this](const QString &path, const QString &message) {
        // a file that failed to open leaves Open recent, and the error says so
        load_failed(forget_recent(path) ? message + " (removed from Open recent)" : message);
    });
    connect(view_, &RenderView::frame_rendered, this, &MainWindow::update_stats);
    connect(view_, &RenderView::frame_progress, this, &MainWindow::frame_progress);
    // while the full frame is not up, the status line names what is on screen
    // ("dp refining…, showing ll preview"), not the last full frame's time
    connect(view_, &RenderView::status_changed, this, [this](const QString &text) {
        if (!text.isEmpty())
            status_label_->setText(text);
    });
    connect(view_, &RenderView::clicked, this, &MainWindow::pick_at);
    connect(view_, &RenderView::render_failed, this, [this](const QString &message) {
        last_error_ = message;
        status_label_->setText("render failed: " + message);
        log_message("error", "render failed: " + message);
        frame_progress(QString(), 0, 0.0);
    });
    connect(view_, &RenderView::frame_cancelled, this, [this](const QString &why) {
        status_label_->setText(why);
        log_message("cancelled", why);
        frame_progress(QString(), 0, 0.0);
    });
    connect(view_, &RenderView::options_left_out, this, [this](const QStringList &left_out) {
        // an option the algorithm cannot express is left out of the frame, and said
        QString text = left_out.join("; ");
        if (text != last_left_out_ && !text.isEmpty())
            log_message("left out", QString("%1 renders without what it cannot express: %2")
                                        .arg(QString::fromStdString(settings_->render_settings().algorithm), text));
        last_left_out_ = text;
    });
    // the camera's controls follow the view's drags, standard views, presets and saved views
    connect(settings_, &SettingsModel::camera_changed, this, &MainWindow::sync_panel_from_settings);
    connect(settings_, &SettingsModel::restored, this, &MainWindow::settings_restored);

    build_menus();
    QMenu *view_menu = nullptr;
    for (QAction *a : menuBar()->actions())
        if (a->text() == "&View")
            view_menu = a->menu();
    // the settings panel collapses with one key (its state is in saveState(), the saved state's "window")
    QAction *panel_action = dock->toggleViewAction();
    panel_action->setText("Settings &panel");
    panel_action->setShortcut(QKeySequence("F4"));
    panel_action->setToolTip("show or hide the settings panel: the view takes the width (F4)");
    if (view_menu)
        view_menu->addAction(panel_action);

    // 1200x760 where the screen has room, else what it has (less the window frame's)
    if (QScreen *screen = QGuiApplication::primaryScreen())
        resize(QSize(1200, 760).boundedTo(screen->availableGeometry().size() - QSize(16, 48)));
    else
        resize(1200, 760);
    // a narrow panel: the view dominates (docs/workbench.md measures its share)
    resizeDocks({dock}, {kSettingsPanelWidth}, Qt::Horizontal);
    // a window that cannot render is not shown: nothing to read or save
    if (!startup_error().isEmpty())
        start_ = Start::Untouched;
    if (start_ != Start::Untouched) {
        // checked and read without blocking; a file that cannot be used is said here
        QString problem = settings_file_.load(saved_);
        if (!problem.isEmpty())
            log_message("warning", problem);
    }
    for (const std::string &path : saved_.recent)
        recent_ << QString::fromStdString(path);
    rebuild_recent_menu();
    for (const std::string &path : saved_.recent_sessions)
        recent_sessions_ << QString::fromStdString(path);
    rebuild_recent_sessions_menu();
    if (start_ == Start::Restore)
        restore_saved_settings();
    // before the first sync, which takes out the rows the algorithm does not use
    give_every_control_a_tooltip(tabs_);
    sync_panel_from_settings();
    reset_settings_history();
}

MainWindow::~MainWindow()
{
    delete view_; // its GL resources go before the model they came from
    view_ = nullptr;
    delete tabs_; // the panels edit the settings model, a child created before them
    tabs_ = nullptr;
}

QTabWidget *MainWindow::build_tabs()
{
    algorithm_panel_ = new AlgorithmPanel(*settings_);
    opacity_panel_ = new OpacityPanel(*settings_, capabilities_);
    // a model/view list: fluid at 10,000 parts (parts_panel.h)
    parts_panel_ = new PartsPanel;
    camera_panel_ = new CameraPanel(*settings_);
    views_panel_ = new ViewsPanel(*settings_, capabilities_);
    stats_panel_ = new StatsPanel;
    compare_panel_ = new ComparePanel(settings_->render_settings());
    // sections and the exploded view (issue 28): the model as drawn frames new
    // planes and the offset slider; "cut only the selected parts" takes the Parts tab's selection
    sections_panel_ = new SectionsPanel(*settings_);
    sections_panel_->drawn_model = [this] { return view_ ? view_->drawn_model() : nullptr; };
    sections_panel_->selected_parts = [this] { return parts_panel_->selected_parts(); };
    connect(sections_panel_, &SectionsPanel::active_changed, view_, &RenderView::set_active_section);
    connect(view_, &RenderView::section_dragged, sections_panel_, [this] { sections_panel_->sync(); });
    connect(view_, &RenderView::open_cut_changed, this, &MainWindow::say_open_cut);

    for (SettingsPanel *panel : settings_panels()) {
        connect(panel, &SettingsPanel::edited, this, &MainWindow::render_now);
        connect(panel, &SettingsPanel::changed, this, &MainWindow::settings_changed);
    }
    // a STEP or IGES model is tessellated again (the other formats have their triangles)
    connect(algorithm_panel_, &AlgorithmPanel::tessellation_changed, this, [this] {
        static const QStringList brep = {"step", "stp", "iges", "igs"};
        if (!model_path_.isEmpty() && brep.contains(QFileInfo(model_path_).suffix().toLower()))
            load_model(model_path_);
    });
    connect(parts_panel_, &PartsPanel::parts_changed, this, [this] {
        settings_->render_settings().part_alpha = parts_panel_->alpha();
        settings_->render_settings().part_visible = parts_panel_->visible();
        render_now();
    });
    connect(parts_panel_, &PartsPanel::frame_selected_requested, this,
            [this](std::vector<int> parts) { frame_parts(parts); });
    connect(camera_panel_, &CameraPanel::reset_camera_requested, view_, &RenderView::reset_camera);
    connect(camera_panel_, &CameraPanel::saved_views_changed, this, [this] {
        if (model_path_.isEmpty())
            return;
        saved_.views[model_path_.toStdString()] = camera_panel_->saved_views();
        save_state(false); // kept at once: a crash or a kill does not lose them
    });
    connect(compare_panel_, &ComparePanel::changed, this, [this] { settings_changed(); });
    connect(compare_panel_, &ComparePanel::wipe_changed, view_, QOverload<>::of(&QWidget::update));
    connect(view_, &RenderView::wipe_moved, compare_panel_, [this] { compare_panel_->sync(); });

    tabs_ = new QTabWidget;
    tabs_->setTabPosition(QTabWidget::West); // eight tabs fit the narrow panel's height, not its width
    tabs_->addTab(scrolled(algorithm_panel_), "Algorithm");
    tabs_->addTab(scrolled(opacity_panel_), "Opacity");
    tabs_->addTab(parts_panel_, "Parts");
    tabs_->addTab(scrolled(camera_panel_), "Camera");
    tabs_->addTab(scrolled(views_panel_), "Views");
    tabs_->addTab(scrolled(sections_panel_), "Sections");
    // the Stats tab: the figures, and under them the frame's depth complexity
    auto *stats_tab = new QWidget;
    auto *stats_layout = new QVBoxLayout(stats_tab);
    stats_layout->setContentsMargins(0, 0, 0, 0);
    histogram_plot_ = new HistogramPlot;
    histogram_plot_->setObjectName("histogram_plot");
    auto *histogram_title = new QLabel("Depth complexity (list lengths) of the shown frame");
    histogram_title->setWordWrap(true); // unwrapped, its width alone widened the panel past 30% of the window
    stats_layout->addWidget(stats_panel_, 1);
    stats_layout->addWidget(histogram_title);
    stats_layout->addWidget(histogram_plot_);
    tabs_->addTab(stats_tab, "Stats");
    tabs_->addTab(scrolled(compare_panel_), "Compare");
    return tabs_;
}

std::array<SettingsPanel *, 5> MainWindow::settings_panels() const
{
    return {algorithm_panel_, opacity_panel_, camera_panel_, views_panel_, sections_panel_};
}

void MainWindow::closeEvent(QCloseEvent *event)
{
    save_state(true);
    QMainWindow::closeEvent(event);
}

// --------------------------------------------------------- the saved state

void MainWindow::restore_saved_settings()
{
    // the restored state may be slow (a deep model with dp): its first full
    // frame gets a budget, past which the coarse frame stays and the user decides
    view_->set_full_frame_budget(3000.0);
    QByteArray geometry = QByteArray::fromBase64(QByteArray::fromStdString(saved_.geometry));
    QByteArray layout = QByteArray::fromBase64(QByteArray::fromStdString(saved_.window));
    if ((!geometry.isEmpty() && !restoreGeometry(geometry)) || (!layout.isEmpty() && !restoreState(layout)))
        log_message("warning", "the saved window layout was not restored (Qt did not take it)");
    // saved on another monitor layout or a larger screen: moved (and shrunk) onto today's screens
    if (!geometry.isEmpty())
        keep_on_screen();
    export_folder_ = QString::fromStdString(saved_.export_folder);
    if (saved_.export_width > 0 && saved_.export_height > 0)
        export_size_ = QSize(saved_.export_width, saved_.export_height);
    pending_preset_ = saved_.settings;
    pending_preset_name_ = "saved settings";
    if (!pending_preset_.empty()) {
        Camera ignored = settings_->camera();
        bool has_camera;
        std::string error;
        RenderSettings restored = settings_->render_settings();
        if (preset_from_json("saved settings", pending_preset_, restored, ignored, has_camera, nullptr, error))
            settings_->render_settings() = restored;
    }
}

void MainWindow::save_state(bool closing)
{
    if (start_ == Start::Untouched)
        return;
    saved_.recent.clear();
    for (const QString &path : recent_)
        saved_.recent.push_back(path.toStdString());
    saved_.recent_sessions.clear();
    for (const QString &path : recent_sessions_)
        saved_.recent_sessions.push_back(path.toStdString());
    if (!model_path_.isEmpty())
        saved_.last_model = model_path_.toStdString();
    saved_.export_folder = export_folder_.toStdString();
    saved_.export_width = export_size_.isValid() ? export_size_.width() : 0;
    saved_.export_height = export_size_.isValid() ? export_size_.height() : 0;
    if (closing) {
        saved_.geometry = saveGeometry().toBase64().toStdString();
        saved_.window = saveState().toBase64().toStdString();
        saved_.settings = preset_to_json(settings_->render_settings(), settings_->camera(), model_.get());
    }
    QString error;
    if (settings_file_.save(saved_, error)) {
        last_save_error_.clear();
        return;
    }
    if (error != last_save_error_)
        log_message("warning", "settings not saved: " + error);
    if (closing)
        std::fprintf(stderr, "oit-workbench: warning: settings not saved: %s\n", error.toLocal8Bit().constData());
    last_save_error_ = error;
}

void MainWindow::keep_on_screen()
{
    QList<QRect> screens;
    for (QScreen *screen : QGuiApplication::screens())
        screens << screen->availableGeometry();
    QScreen *primary = QGuiApplication::primaryScreen();
    QRect fitted = fit_on_screens(geometry(), screens, primary ? screens.indexOf(primary->availableGeometry()) : 0);
    if (fitted.isValid() && fitted != geometry()) {
        log_message("window", QString("the saved window (%1x%2 at %3,%4) was moved onto the screen")
                                  .arg(geometry().width())
                                  .arg(geometry().height())
                                  .arg(geometry().x())
                                  .arg(geometry().y()));
        setGeometry(fitted);
    }
}

QString MainWindow::saved_last_model() const
{
    return start_ == Start::Restore ? QString::fromStdString(saved_.last_model) : QString();
}

int MainWindow::refuse_to_start(const QString &problem)
{
    // the command line's one line, and where the shaders are looked for
    QMessageBox box(QMessageBox::Critical, "oit-workbench cannot start", problem, QMessageBox::Ok);
    box.setObjectName("cannot_start");
    box.setInformativeText("The workbench renders with the shaders of its installation "
                           "(PREFIX/share/oit-workbench/shaders, or the source tree's shaders/ "
                           "for a build); OIT_SHADER_DIR names another folder.");
    box.exec();
    return 3;
}

// ----------------------------------------------------- settings, undo, redo

void MainWindow::render_now()
{
    settings_->record_change();
    if (view_)
        view_->request_frame(true);
}

void MainWindow::settings_changed()
{
    sync_panel_from_settings();
    render_now();
}

void MainWindow::sync_panel_from_settings()
{
    for (SettingsPanel *panel : settings_panels())
        panel->sync();
    compare_panel_->sync();
    for (auto &action : sync_actions_)
        action();
    if (model_)
        parts_panel_->set_values(settings_->render_settings().part_alpha, settings_->render_settings().part_visible);
}

void MainWindow::settings_restored()
{
    sync_panel_from_settings();
    view_->request_frame(false);
}

void MainWindow::reset_settings_history()
{
    settings_->reset_history();
}

bool MainWindow::undo_settings()
{
    if (!settings_->undo())
        return false;
    log_message("undo", "settings as before the last change");
    return true;
}

bool MainWindow::redo_settings()
{
    if (!settings_->redo())
        return false;
    log_message("redo", "the undone change again");
    return true;
}

void MainWindow::set_algorithm(const QString &name)
{
    if (!oit_algorithm_find(name.toUtf8().constData()))
        return;
    settings_->render_settings().algorithm = name.toStdString();
    settings_changed();
}

void MainWindow::set_error_view(bool on)
{
    settings_->render_settings().error_view = on;
    settings_changed();
}

void MainWindow::set_split(SplitMode mode, const QString &algorithm_b)
{
    RenderSettings &s = settings_->render_settings();
    s.split = mode;
    if (!algorithm_b.isEmpty() && oit_algorithm_find(algorithm_b.toUtf8().constData()))
        s.split_algorithm = algorithm_b.toStdString();
    settings_changed();
}

void MainWindow::set_camera_mode(Camera::Mode mode, bool orthographic)
{
    settings_->camera().set_mode(mode);
    settings_->camera().orthographic = orthographic;
    settings_changed();
}

QSlider *MainWindow::alpha_slider() const
{
    return opacity_panel_->alpha_slider();
}

// ----------------------------------------------------------------- parts

void MainWindow::set_part_visible(int index, bool visible)
{
    RenderSettings &s = settings_->render_settings();
    if (index < 0 || size_t(index) >= s.part_visible.size())
        return;
    s.part_visible[size_t(index)] = visible;
    parts_panel_->set_values(s.part_alpha, s.part_visible);
    render_now();
}

void MainWindow::set_part_alpha(int index, float alpha)
{
    RenderSettings &s = settings_->render_settings();
    if (index < 0 || size_t(index) >= s.part_alpha.size())
        return;
    s.part_alpha[size_t(index)] = std::min(1.0f, std::max(0.0f, alpha));
    parts_panel_->set_values(s.part_alpha, s.part_visible);
    render_now();
}

void MainWindow::frame_parts(const std::vector<int> &parts)
{
    if (!model_ || parts.empty())
        return;
    const oit_model &m = *model_;
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}; // relative
    for (int part : parts) {
        if (part < 0 || uint32_t(part) >= m.component_count)
            continue;
        const oit_component &c = m.components[part];
        for (uint32_t t = c.first_triangle; t < c.first_triangle + c.triangle_count; ++t)
            for (int k = 0; k < 3; ++k) {
                const float *p = m.positions + size_t(m.indices[size_t(t) * 3 + size_t(k)]) * 3;
                for (int a = 0; a < 3; ++a) {
                    lo[a] = std::min(lo[a], p[a]);
                    hi[a] = std::max(hi[a], p[a]);
                }
            }
    }
    if (!(lo[0] <= hi[0]))
        return; // parts without triangles
    double box_min[3], box_max[3]; // in file coordinates, as the camera
    for (int a = 0; a < 3; ++a) {
        box_min[a] = m.origin[a] + lo[a];
        box_max[a] = m.origin[a] + hi[a];
    }
    QSize size = view_->pixel_size(); // the whole view: side by side, each half shows as much (make_frame)
    settings_->camera().frame_box(box_min, box_max, size.width(), size.height());
    settings_->camera_edited();
    render_now();
}

void MainWindow::pick_at(const QPoint &pixel, bool next_contributor)
{
    if (!model_)
        return;
    if (sections_panel_->picking_face()) {
        pick_section_face(pixel);
        return;
    }
    std::vector<float> storage;
    oit_frame_settings frame = view_->current_frame(storage);
    const RenderSettings &s = settings_->render_settings();
    // side by side, both halves have the same camera: the pixel within its half
    bool right_half = s.split == SplitMode::SideBySide && pixel.x() >= frame.width;
    QPoint at(right_half ? pixel.x() - frame.width : pixel.x(), pixel.y());
    // a click (or Alt+click) where the last one picked, in the same frame: the
    // contributor behind it (after the last, the front again); elsewhere the
    // front one (Alt: the second)
    std::vector<double> camera(frame.modelview, frame.modelview + 16);
    camera.insert(camera.end(), frame.projection, frame.projection + 16);
    camera.push_back(frame.width);
    camera.push_back(frame.height);
    camera.push_back(frame.alpha);
    camera.insert(camera.end(), storage.begin(), storage.end()); // the parts' opacities
    const bool again = at == last_pick_pixel_ && camera == last_pick_camera_;
    int rank = again ? last_pick_rank_ + 1 : next_contributor ? 2 : 1;
    if (measuring())
        rank = next_contributor ? 2 : 1; // each click a new point, never the one behind the last
    last_pick_camera_ = camera;
    std::string error;
    // the model as drawn: a click picks a part where it was moved to, never where the sections removed it
    std::shared_ptr<const oit_model> drawn = view_->drawn_model_pointer();
    ContributorPick hit = pick_contributor(*drawn, frame, at.x(), at.y(), rank, error);
    last_pick_pixel_ = at;
    last_pick_rank_ = hit.rank;
    if (measuring()) {
        measure_pick(hit, error); // the same pick, a measured point instead of a selection
        return;
    }
    if (!error.empty()) {
        status_label_->setText(QString::fromStdString("pick: " + error));
        return;
    }
    if (hit.component < 0) {
        status_label_->setText("nothing under the pointer");
        return;
    }
    parts_panel_->select_part(hit.component);
    // its path through the assembly tree (its name when the file has none): names repeat across assemblies
    char path[1024];
    oit_model_component_path(model_.get(), uint32_t(hit.component), path, sizeof path);
    status_label_->setText(QString("picked part %1 (%2): %3% of the pixel, contributor %4 of %5%6")
                               .arg(QString::fromUtf8(path))
                               .arg(hit.component)
                               .arg(100.0 * hit.contribution, 0, 'f', 1)
                               .arg(hit.rank)
                               .arg(hit.parts)
                               .arg(hit.parts > 1 ? " (click again: the next)" : ""));
}

// ------------------------------------------------------- sections (issue 28)

void MainWindow::pick_section_face(const QPoint &pixel)
{
    sections_panel_->stop_picking_face();
    std::vector<float> storage;
    oit_frame_settings frame = view_->current_frame(storage);
    const RenderSettings &s = settings_->render_settings();
    bool right_half = s.split == SplitMode::SideBySide && pixel.x() >= frame.width;
    QPoint at(right_half ? pixel.x() - frame.width : pixel.x(), pixel.y());
    std::shared_ptr<const oit_model> drawn = view_->drawn_model_pointer();
    std::string error;
    ContributorPick hit = pick_contributor(*drawn, frame, at.x(), at.y(), 1, error);
    if (!error.empty() || hit.component < 0 || hit.triangle < 0 || uint32_t(hit.triangle) >= drawn->triangle_count) {
        status_label_->setText(error.empty() ? QString("pick face: nothing under the pointer")
                                             : QString::fromStdString("pick face: " + error));
        return;
    }
    // the face's normal (its triangle's), turned towards the eye: the plane removes what is in front of it
    const uint32_t *index = drawn->indices + size_t(hit.triangle) * 3;
    glm::dvec3 v[3];
    for (int k = 0; k < 3; ++k) {
        const float *p = drawn->positions + size_t(index[k]) * 3;
        v[k] = glm::dvec3(p[0], p[1], p[2]);
    }
    glm::dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
    if (!(glm::length(n) > 0.0)) {
        status_label_->setText("pick face: the triangle under the pointer has no area");
        return;
    }
    n = glm::normalize(n);
    glm::dvec3 point(hit.point[0], hit.point[1], hit.point[2]);
    if (glm::dot(n, settings_->camera().eye - point) < 0.0)
        n = -n;
    const double normal[3] = {n.x, n.y, n.z}, where[3] = {point.x, point.y, point.z};
    sections_panel_->set_plane(where, normal);
    char path[1024];
    oit_model_component_path(drawn.get(), uint32_t(hit.component), path, sizeof path);
    status_label_->setText(QString("section plane on a face of %1").arg(QString::fromUtf8(path)));
}

void MainWindow::say_open_cut(const std::vector<uint32_t> &parts)
{
    if (parts.empty() || !model_)
        return;
    QStringList names;
    char path[1024];
    for (uint32_t part : parts) {
        if (part >= model_->component_count)
            continue;
        if (names.size() == 20) {
            names << QString("and %1 more").arg(parts.size() - 20);
            break;
        }
        oit_model_component_path(model_.get(), part, path, sizeof path);
        names << QString::fromUtf8(path);
    }
    log_message("sections", "section cuts open parts (no cap): " + names.join(", "));
}

// ----------------------------------------------- status, progress, messages

void MainWindow::frame_progress(const QString &stage, int stages_done, double elapsed_ms)
{
    // long frames only: a fast one would make the status bar flicker
    bool show = !stage.isEmpty() && elapsed_ms > RenderView::kProgressAfterMs && view_->rendering();
    if (show)
        progress_label_->setText(QString("%1: %2 (%3 stages, %4 s)")
                                     .arg(QString::fromStdString(settings_->render_settings().algorithm), stage)
                                     .arg(stages_done)
                                     .arg(elapsed_ms / 1000.0, 0, 'f', 1));
    bool loading_now = loader_->running();
    progress_label_->setVisible(show || loading_now);
    progress_->setVisible(show || loading_now);
    cancel_button_->setVisible(show);
}

void MainWindow::update_stats()
{
    const RenderSettings &s = settings_->render_settings();
    StatsPanel::Summary summary = StatsPanel::describe(*view_, s, model_.get());
    compare_panel_->set_figures(summary.figures);
    stats_panel_->setPlainText(summary.text);
    const oit_stats &st = view_->last_stats();
    const QSize shown = view_->last_image().size();
    histogram_plot_->set_histogram(st, QString::fromStdString(s.algorithm),
                                   uint64_t(shown.width()) * uint64_t(shown.height()));
    QString truncated;
    if (st.truncated)
        truncated = QString(" — TRUNCATED: the layer cap %1 left fragments out").arg(s.config.max_layers);
    if (st.truncated && !last_truncated_)
        log_message("warning", QString("%1: the layer cap %2 left fragments out (TRUNCATED)")
                                   .arg(QString::fromStdString(s.algorithm))
                                   .arg(s.config.max_layers));
    last_truncated_ = st.truncated;
    frame_progress(QString(), 0, 0.0);
    status_label_->setText(QString("%1: %2 ms CPU, %3 ms GPU stages, %4 MB%5%6")
                               .arg(QString::fromStdString(s.algorithm))
                               .arg(st.cpu_ms, 0, 'f', 1)
                               .arg(summary.gpu_ms, 0, 'f', 1)
                               .arg(double(st.memory_bytes) / (1024.0 * 1024.0), 0, 'f', 1)
                               .arg(truncated, summary.compared));
}

QString MainWindow::status_text() const
{
    return status_label_->text();
}

QStringList MainWindow::messages() const
{
    return message_lines_;
}

void MainWindow::log_message(const QString &kind, const QString &text)
{
    QString line = QString("[%1] %2: %3").arg(QTime::currentTime().toString("HH:mm:ss"), kind, text);
    message_lines_ << line;
    while (message_lines_.size() > 2000)
        message_lines_.removeFirst();
    messages_->appendPlainText(line);
}

void MainWindow::show_notice(QMessageBox *box)
{
    // window-modal but not blocking, so the event loop (and tests) go on
    if (error_box_)
        error_box_->close();
    error_box_ = box;
    error_box_->setAttribute(Qt::WA_DeleteOnClose);
    error_box_->open();
}

void MainWindow::show_error(const QString &title, const QString &message)
{
    last_error_ = message;
    status_label_->setText(message);
    log_message("error", title + ": " + message);
    show_notice(new QMessageBox(QMessageBox::Warning, title, message, QMessageBox::Ok, this));
}

bool MainWindow::show_tab(const QString &name)
{
    for (int i = 0; i < tabs_->count(); ++i)
        if (tabs_->tabText(i).compare(name, Qt::CaseInsensitive) == 0) {
            tabs_->setCurrentIndex(i);
            return true;
        }
    return false;
}

// --------------------------------------------------------------- loading

bool MainWindow::loading() const
{
    return loader_->running();
}

void MainWindow::load_model(const QString &path)
{
    if (loader_->running()) {
        status_label_->setText("still loading " + loading_path_);
        return;
    }
    loading_path_ = QFileInfo(path).absoluteFilePath();
    progress_->show();
    progress_label_->setText("reading " + QFileInfo(loading_path_).fileName() + "…");
    progress_label_->show();
    status_label_->setText("loading " + loading_path_ + "…");
    log_message("load", "reading " + loading_path_);
    loader_->start(loading_path_, settings_->render_settings().import);
}

void MainWindow::load_failed(const QString &message)
{
    progress_->hide();
    progress_label_->hide();
    if (pending_session_) { // the session's parts, camera and views wait for no model
        pending_session_ = false;
        pending_views_.clear();
        pending_preset_.clear();
    }
    show_error("Cannot open model", message);
    emit model_failed(message);
}

void MainWindow::load_finished(ModelPointer model, const QString &path)
{
    progress_->hide();
    progress_label_->hide();
    model_ = std::move(model);
    settings_->set_model(model_.get());
    model_path_ = path;
    RenderSettings &settings = settings_->render_settings();
    Camera &camera = settings_->camera();
    settings.reset_parts(*model_);
    QSize size = view_->pixel_size();
    camera.frame(*model_, size.width(), size.height());
    camera.set_mode(Camera::Mode::Orbit);
    if (!pending_preset_.empty()) {
        bool has_camera;
        Camera preset_camera = camera;
        std::string preset_error;
        RenderSettings s = settings;
        // the rest of the preset was applied when it was loaded (and may have
        // been changed since, by --algorithm for one): only parts and camera
        // needed the model
        if (preset_from_json(pending_preset_name_.toStdString(), pending_preset_, s, preset_camera, has_camera,
                             model_.get(), preset_error)) {
            settings.part_alpha = s.part_alpha;
            settings.part_visible = s.part_visible;
            settings.section_parts = s.section_parts; // names, matched against this model
            // a camera saved with another model would show nothing useful
            if (has_camera && pending_preset_name_ != "saved settings")
                camera = preset_camera;
        } else {
            log_message("warning", QString("the parts of %1 were not applied: %2")
                                       .arg(pending_preset_name_, QString::fromStdString(preset_error)));
        }
        pending_preset_.clear();
    }
    // the views saved with this model (by its file name) come back
    auto views = saved_.views.find(model_path_.toStdString());
    camera_panel_->set_saved_views(views != saved_.views.end() ? views->second : std::vector<SavedView>());
    if (pending_session_) {
        // a session's views: the model's saved views from now on
        camera_panel_->set_saved_views(pending_views_);
        saved_.views[model_path_.toStdString()] = pending_views_;
        pending_views_.clear();
        pending_session_ = false;
    }
    setWindowTitle(QString("%1 — oit-workbench").arg(QFileInfo(model_path_).fileName()));
    add_recent(model_path_);
    // one write of the settings file: each is synced to disk on this thread,
    // up to 25 ms on a busy disk (measured with strace)
    save_state(false);
    parts_panel_->set_model(model_.get(), settings.part_alpha, settings.part_visible);
    sync_panel_from_settings();
    reset_settings_history(); // the parts are another model's now
    // the worker uploads it with the first (coarse) frame
    view_->set_model(model_);
    status_label_->setText(QString("loaded %1: %2 triangles, %3 parts")
                               .arg(model_path_)
                               .arg(model_->triangle_count)
                               .arg(model_->component_count));
    log_message("load", status_label_->text());
    last_error_.clear();
    // what the import skipped or repaired is said once, in a notice that does not block
    model_warnings_.clear();
    for (uint32_t i = 0; i < model_->warning_count; ++i)
        model_warnings_ << QString::fromUtf8(model_->warnings[i]);
    for (const QString &warning : model_warnings_)
        log_message("warning", warning);
    if (!model_warnings_.isEmpty())
        show_notice(new QMessageBox(QMessageBox::Information, "Model loaded with warnings",
                                    model_warnings_.join("\n"), QMessageBox::Ok, this));
    emit model_loaded(model_path_);
}

void MainWindow::dragEnterEvent(QDragEnterEvent *event)
{
    if (event->mimeData()->hasUrls() && event->mimeData()->urls().first().isLocalFile())
        event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent *event)
{
    const QList<QUrl> urls = event->mimeData()->urls();
    if (!urls.isEmpty() && urls.first().isLocalFile()) {
        QString path = urls.first().toLocalFile();
        if (path.endsWith(".oitsession", Qt::CaseInsensitive)) {
            QString error;
            if (!open_session(path, error))
                show_error("Open session", error);
        } else if (path.endsWith(".json", Qt::CaseInsensitive)) {
            QString error;
            if (!load_preset(path, error))
                show_error("Load preset", error);
        } else {
            load_model(path);
        }
        event->acceptProposedAction();
    }
}

// ----------------------------------------------------------------- paths

QString MainWindow::source_root()
{
    // the shader tree's parent: the source tree, or the install's share/oit-workbench
    char dir[4096];
    oit_error err{};
    QByteArray argv0 = QCoreApplication::applicationFilePath().toLocal8Bit();
    if (oit_find_shader_dir(argv0.constData(), dir, sizeof dir, &err) != OIT_OK)
        return QDir::currentPath();
    return QDir(QString::fromLocal8Bit(dir) + "/..").canonicalPath();
}

QString MainWindow::default_model_path()
{
    return source_root() + "/resources/models/gearbox.obj";
}
