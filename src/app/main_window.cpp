// main_window.cpp: see main_window.h.
#include "main_window.h"
#include "oit_shared.h" // OIT_APPROX_LAYERS_DEFAULT, _MAX
#include "compare_panel.h"
#include "error_legend.h"
#include "file_io.h"
#include "parts_panel.h"
#include "pick.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QButtonGroup>
#include <QCheckBox>
#include <QClipboard>
#include <QCloseEvent>
#include <QColorDialog>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDir>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QFontDatabase>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QPainter>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QRadioButton>
#include <QScrollArea>
#include <QSlider>
#include <QSpinBox>
#include <QStandardItemModel>
#include <QStatusBar>
#include <QTabWidget>
#include <QTextStream>
#include <QTime>
#include <QVBoxLayout>
#include <QtConcurrent/QtConcurrent>

#include <cmath>
#include <cstdio>
#include <cstring>

struct LoadResult {
    oit_model model{};
    bool ok = false;
    QString path, error;
};

void ModelDeleter::operator()(oit_model *model) const
{
    oit_model_free(model);
    delete model;
}

namespace {

// A menu entry with a shortcut that runs a function.
template <class Function>
QAction *menu_action(QMenu *menu, const QString &text, const QKeySequence &key, QObject *context, Function f)
{
    QAction *action = menu->addAction(text);
    action->setShortcut(key);
    QObject::connect(action, &QAction::triggered, context, f);
    return action;
}

QString read_text_file(const QString &path, QString &error)
{
    // a regular file only: a FIFO or /dev/zero would block or never end
    QByteArray bytes;
    if (!read_regular_file(path, nullptr, bytes, error))
        return QString();
    return QString::fromUtf8(bytes);
}

QIcon swatch(const float colour[3])
{
    QPixmap pixmap(14, 14);
    pixmap.fill(QColor::fromRgbF(colour[0], colour[1], colour[2]));
    QPainter painter(&pixmap);
    painter.setPen(Qt::black);
    painter.drawRect(0, 0, 13, 13);
    return QIcon(pixmap);
}

QString colour_text(const float c[3])
{
    return QString("%1,%2,%3").arg(double(c[0])).arg(double(c[1])).arg(double(c[2]));
}

} // namespace

// ------------------------------------------------------------ construction

MainWindow::MainWindow(Start start, QWidget *parent) : QMainWindow(parent), start_(start)
{
    setWindowTitle("oit-workbench");
    setAcceptDrops(true);
    view_ = new RenderView(this);
    setCentralWidget(view_);

    tabs_ = new QTabWidget;
    tabs_->addTab(build_algorithm_tab(), "Algorithm");
    tabs_->addTab(build_opacity_tab(), "Opacity");
    tabs_->addTab(build_parts_tab(), "Parts");
    tabs_->addTab(build_camera_tab(), "Camera");
    tabs_->addTab(build_views_tab(), "Views");
    tabs_->addTab(build_stats_tab(), "Stats");
    tabs_->addTab(build_compare_tab(), "Compare");
    auto *dock = new QDockWidget("Settings", this);
    dock->setObjectName("settings");
    dock->setWidget(tabs_);
    dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable |
                      QDockWidget::DockWidgetClosable);
    addDockWidget(Qt::RightDockWidgetArea, dock);

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

    loader_ = new QFutureWatcher<LoadResult *>(this);
    connect(loader_, &QFutureWatcher<LoadResult *>::finished, this, &MainWindow::load_finished);
    connect(view_, &RenderView::frame_rendered, this, &MainWindow::update_stats);
    connect(view_, &RenderView::frame_progress, this, &MainWindow::frame_progress);
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
                                        .arg(QString::fromStdString(view_->settings.algorithm), text));
        last_left_out_ = text;
    });

    // which algorithm renders which option: the core's capability tables
    capabilities_ = capability_table();
    sync_actions_.push_back([this] { apply_capabilities(); });
    coalesce_timer_ = new QTimer(this);
    coalesce_timer_->setSingleShot(true);
    coalesce_timer_->setInterval(kUndoCoalesceMs);
    build_menus();
    QMenu *view_menu = nullptr;
    for (QAction *a : menuBar()->actions())
        if (a->text() == "&View")
            view_menu = a->menu();
    if (view_menu)
        view_menu->addAction(dock->toggleViewAction());

    resize(1200, 760);
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
    if (start_ == Start::Restore) {
        // the restored state may be slow (a deep model with dp): its first full
        // frame gets a budget, past which the coarse frame stays and the user decides
        view_->set_full_frame_budget(3000.0);
        QByteArray geometry = QByteArray::fromBase64(QByteArray::fromStdString(saved_.geometry));
        QByteArray layout = QByteArray::fromBase64(QByteArray::fromStdString(saved_.window));
        if ((!geometry.isEmpty() && !restoreGeometry(geometry)) || (!layout.isEmpty() && !restoreState(layout)))
            log_message("warning", "the saved window layout was not restored (Qt did not take it)");
        pending_preset_ = saved_.settings;
        pending_preset_name_ = "saved settings";
        if (!pending_preset_.empty()) {
            Camera ignored = view_->camera;
            bool has_camera;
            std::string error;
            RenderSettings restored = view_->settings;
            if (preset_from_json("saved settings", pending_preset_, restored, ignored, has_camera, nullptr, error))
                view_->settings = restored;
        }
    }
    sync_panel_from_settings();
    reset_settings_history();
    give_every_control_a_tooltip();
}

MainWindow::~MainWindow()
{
    if (load_unclaimed_) {
        // a load that load_finished never took (still running, or its signal
        // not delivered yet): its model is freed here
        loader_->waitForFinished();
        std::unique_ptr<LoadResult> result(loader_->result());
        if (result->ok)
            oit_model_free(&result->model);
    }
    delete view_; // its GL resources go before the model they came from
    view_ = nullptr;
}

void MainWindow::closeEvent(QCloseEvent *event)
{
    save_state(true);
    QMainWindow::closeEvent(event);
}

void MainWindow::save_state(bool closing)
{
    if (start_ == Start::Untouched)
        return;
    saved_.recent.clear();
    for (const QString &path : recent_)
        saved_.recent.push_back(path.toStdString());
    if (!model_path_.isEmpty())
        saved_.last_model = model_path_.toStdString();
    if (closing) {
        saved_.geometry = saveGeometry().toBase64().toStdString();
        saved_.window = saveState().toBase64().toStdString();
        saved_.settings = preset_to_json(view_->settings, view_->camera, model_.get());
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

void MainWindow::render_now()
{
    record_settings_change();
    if (view_)
        view_->request_frame(true);
}

// ------------------------------------------------------------ undo / redo

// Settings compared as their preset text (the camera is not a setting here:
// the same placeholder camera goes into both).
std::string MainWindow::settings_key(const RenderSettings &settings) const
{
    // the wipe line is where one looks, like the camera: not a step of its own
    RenderSettings s = settings;
    s.wipe = 0.5f;
    return preset_to_json(s, Camera(), model_.get());
}

// Changes within kUndoCoalesceMs of each other (a slider drag, typing a
// number) are one step.
void MainWindow::record_settings_change()
{
    if (restoring_settings_ || !view_)
        return;
    std::string key = settings_key(view_->settings);
    if (key == committed_key_)
        return;
    if (!coalesce_timer_->isActive()) {
        undo_stack_.push_back(committed_settings_);
        if (undo_stack_.size() > 200)
            undo_stack_.erase(undo_stack_.begin());
        redo_stack_.clear();
    }
    committed_settings_ = view_->settings;
    committed_key_ = key;
    coalesce_timer_->start();
    undo_action_->setEnabled(!undo_stack_.empty());
    redo_action_->setEnabled(false);
}

void MainWindow::reset_settings_history()
{
    undo_stack_.clear();
    redo_stack_.clear();
    committed_settings_ = view_->settings;
    committed_key_ = settings_key(view_->settings);
    coalesce_timer_->stop();
    if (undo_action_) {
        undo_action_->setEnabled(false);
        redo_action_->setEnabled(false);
    }
}

void MainWindow::restore_settings(const RenderSettings &settings)
{
    restoring_settings_ = true;
    float wipe = view_->settings.wipe; // not a setting (settings_key)
    view_->settings = settings;
    view_->settings.wipe = wipe;
    committed_settings_ = settings;
    committed_key_ = settings_key(settings);
    coalesce_timer_->stop();
    sync_panel_from_settings();
    if (model_)
        parts_panel_->set_values(settings.part_alpha, settings.part_visible);
    view_->request_frame(false);
    restoring_settings_ = false;
    undo_action_->setEnabled(!undo_stack_.empty());
    redo_action_->setEnabled(!redo_stack_.empty());
}

bool MainWindow::undo_settings()
{
    record_settings_change(); // a change still coalescing is a step of its own
    if (undo_stack_.empty())
        return false;
    redo_stack_.push_back(view_->settings);
    RenderSettings previous = undo_stack_.back();
    undo_stack_.pop_back();
    restore_settings(previous);
    log_message("undo", "settings as before the last change");
    return true;
}

bool MainWindow::redo_settings()
{
    if (redo_stack_.empty())
        return false;
    undo_stack_.push_back(view_->settings);
    RenderSettings next = redo_stack_.back();
    redo_stack_.pop_back();
    restore_settings(next);
    log_message("redo", "the undone change again");
    return true;
}

void MainWindow::frame_progress(const QString &stage, int stages_done, double elapsed_ms)
{
    // long frames only: a fast one would make the status bar flicker
    bool show = !stage.isEmpty() && elapsed_ms > RenderView::kProgressAfterMs && view_->rendering();
    if (show)
        progress_label_->setText(QString("%1: %2 (%3 stages, %4 s)")
                                     .arg(QString::fromStdString(view_->settings.algorithm), stage)
                                     .arg(stages_done)
                                     .arg(elapsed_ms / 1000.0, 0, 'f', 1));
    bool loading_now = loader_->isRunning();
    progress_label_->setVisible(show || loading_now);
    progress_->setVisible(show || loading_now);
    cancel_button_->setVisible(show);
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

// ------------------------------------------------------------------ menus

void MainWindow::build_menus()
{
    QMenu *file = menuBar()->addMenu("&File");
    file->addAction("&Open model…", this, &MainWindow::open_model_dialog, QKeySequence::Open);
    recent_menu_ = file->addMenu("Open &recent");
    QMenu *models = file->addMenu("&Models");
    QString list_path = source_root() + "/config/models.json";
    QString error;
    QString text = read_text_file(list_path, error);
    std::vector<ModelEntry> entries;
    std::string list_error;
    if (text.isEmpty() || !read_model_list(list_path.toStdString(), text.toStdString(), source_root().toStdString(),
                                           entries, list_error)) {
        models->addAction(error.isEmpty() ? QString::fromStdString(list_error) : error)->setEnabled(false);
    }
    for (const ModelEntry &entry : entries) {
        QString path = QString::fromStdString(entry.path);
        QAction *action = models->addAction(QString::fromStdString(entry.name), this, [this, path] { load_model(path); });
        action->setToolTip(path);
        action->setEnabled(QFileInfo::exists(path));
    }
    file->addSeparator();
    file->addAction("&Export PNG…", this, &MainWindow::export_dialog, QKeySequence("Ctrl+E"));
    file->addAction("&Copy as command", this, &MainWindow::copy_command, QKeySequence("Ctrl+Shift+C"));
    file->addSeparator();
    menu_action(file, "&Save settings preset…", QKeySequence::Save, this, [this] {
        QString path = QFileDialog::getSaveFileName(this, "Save settings preset", QString(), "Presets (*.json)");
        QString error;
        if (!path.isEmpty() && !save_preset(path, error))
            show_error("Save preset", error);
    });
    menu_action(file, "&Load settings preset…", QKeySequence("Ctrl+L"), this, [this] {
        QString path = QFileDialog::getOpenFileName(this, "Load settings preset", QString(), "Presets (*.json)");
        QString error;
        if (!path.isEmpty() && !load_preset(path, error))
            show_error("Load preset", error);
    });
    file->addSeparator();
    file->addAction("&Quit", this, &QWidget::close, QKeySequence::Quit);

    QMenu *edit = menuBar()->addMenu("&Edit");
    undo_action_ = menu_action(edit, "&Undo settings change", QKeySequence::Undo, this, [this] { undo_settings(); });
    redo_action_ = menu_action(edit, "&Redo settings change", QKeySequence::Redo, this, [this] { redo_settings(); });
    undo_action_->setEnabled(false);
    redo_action_->setEnabled(false);

    QMenu *view = menuBar()->addMenu("&View");
    menu_action(view, "&Reset camera", QKeySequence("Home"), this, [this] { view_->reset_camera(); });
    menu_action(view, "&Frame selected parts", QKeySequence("Ctrl+F"), this,
                [this] { frame_parts(parts_panel_->selected_parts()); });
    QMenu *standard = view->addMenu("&Standard view");
    struct StandardView {
        const char *name;
        float azimuth, elevation;
    };
    // isometric: the cube's diagonal towards the eye, elevation atan(1 / sqrt 2)
    static const StandardView standard_views[] = {{"&Front", 0, 0},   {"&Back", 180, 0},  {"&Left", -90, 0},
                                                  {"&Right", 90, 0},  {"&Top", 0, 90},    {"Botto&m", 0, -90},
                                                  {"&Isometric", 45, 35.26439f}};
    int number = 1;
    for (const StandardView &v : standard_views) {
        float azimuth = v.azimuth, elevation = v.elevation;
        menu_action(standard, v.name, QKeySequence(QString("Alt+%1").arg(number++)), this, [this, azimuth, elevation] {
            view_->camera.set_view_direction(azimuth, elevation);
            emit view_->camera_changed();
            view_->request_frame(true);
        });
    }
    QAction *ortho = view->addAction("&Orthographic");
    ortho->setShortcut(QKeySequence("O"));
    ortho->setCheckable(true);
    connect(ortho, &QAction::triggered, this, [this](bool on) { set_camera_mode(view_->camera.mode(), on); });
    QAction *walk = view->addAction("&Walk mode (W/A/S/D, Q/E)");
    walk->setShortcut(QKeySequence("V"));
    walk->setCheckable(true);
    connect(walk, &QAction::triggered, this, [this](bool on) {
        set_camera_mode(on ? Camera::Mode::Walk : Camera::Mode::Orbit, view_->camera.orthographic);
    });
    // the camera's state can change from the Camera tab, presets and saved views
    auto sync_camera_actions = [this, ortho, walk] {
        ortho->setChecked(view_->camera.orthographic);
        walk->setChecked(view_->camera.mode() == Camera::Mode::Walk);
    };
    sync_actions_.push_back(sync_camera_actions);
    connect(view_, &RenderView::camera_changed, this, sync_camera_actions);
    QAction *heatmap = heatmap_action_ = view->addAction("&Heatmap");
    heatmap->setShortcut(QKeySequence("H"));
    heatmap->setCheckable(true);
    connect(heatmap, &QAction::triggered, this, [this](bool on) {
        view_->settings.modulation.view = on ? OIT_VIEW_HEATMAP : OIT_VIEW_COLOUR;
        settings_changed();
    });
    sync_actions_.push_back([this, heatmap] { heatmap->setChecked(view_->settings.modulation.view == OIT_VIEW_HEATMAP); });
    QAction *error_view = view->addAction("&Error against reference");
    error_view->setShortcut(QKeySequence("R"));
    error_view->setCheckable(true);
    error_view->setToolTip("the error map of the frame against the CPU reference, with rmse, psnr, ssim, max "
                           "and the share over 2 (--error-vs-reference)");
    connect(error_view, &QAction::triggered, this, [this](bool on) { set_error_view(on); });
    sync_actions_.push_back([this, error_view] { error_view->setChecked(view_->settings.error_view); });
    QAction *split = view->addAction("&Split view (wipe line)");
    split->setShortcut(QKeySequence("X"));
    split->setCheckable(true);
    split->setToolTip("two algorithms of the same camera either side of a wipe line you drag");
    connect(split, &QAction::triggered, this,
            [this](bool on) { set_split(on ? SplitMode::Wipe : SplitMode::Off); });
    QAction *side_by_side = view->addAction("Side &by side");
    side_by_side->setCheckable(true);
    side_by_side->setToolTip("two algorithms of the same camera, each at half the view's width");
    connect(side_by_side, &QAction::triggered, this,
            [this](bool on) { set_split(on ? SplitMode::SideBySide : SplitMode::Off); });
    sync_actions_.push_back([this, split, side_by_side] {
        split->setChecked(view_->settings.split == SplitMode::Wipe);
        side_by_side->setChecked(view_->settings.split == SplitMode::SideBySide);
    });
    QMenu *algorithm_b_menu = view->addMenu("Split view's algorithm &B");
    auto *algorithm_b_group = new QActionGroup(this);
    {
        size_t count = 0;
        const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
        for (size_t i = 0; i < count; ++i) {
            QString name = list[i]->name;
            QAction *action = algorithm_b_menu->addAction(name, this, [this, name] {
                SplitMode mode = view_->settings.split;
                set_split(mode == SplitMode::Off ? SplitMode::Wipe : mode, name);
            });
            action->setCheckable(true);
            action->setToolTip(list[i]->summary);
            algorithm_b_group->addAction(action);
            sync_actions_.push_back([this, action, name] {
                action->setChecked(QString::fromStdString(view_->settings.split_algorithm) == name);
            });
        }
        algorithm_b_menu->setToolTipsVisible(true);
    }
    QAction *continuous = view->addAction("&Continuous rendering (measure FPS)");
    continuous->setShortcut(QKeySequence("F"));
    continuous->setCheckable(true);
    connect(continuous, &QAction::toggled, view_, &RenderView::set_continuous);
    QAction *progressive = view->addAction("&Progressive frames (coarse while interacting)");
    progressive->setCheckable(true);
    progressive->setChecked(view_->progressive());
    progressive->setToolTip("when full frames are slow, show a coarse frame during drags and slider moves "
                            "and refine it when the input rests");
    connect(progressive, &QAction::toggled, view_, &RenderView::set_progressive);
    menu_action(view, "&Render full frame", QKeySequence("F5"), this, [this] { view_->request_frame(false); });
    menu_action(view, "&Cancel frame", QKeySequence("Esc"), this, [this] { view_->cancel_frame(); });
    view->addSeparator();
    QMenu *algorithms = view->addMenu("&Algorithm");
    auto *algorithm_group = new QActionGroup(this);
    size_t count;
    const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
    for (size_t i = 0; i < count; ++i) {
        QString name = list[i]->name;
        QAction *action = algorithms->addAction(name, this, [this, name] { set_algorithm(name); },
                                                QKeySequence(QString("Ctrl+%1").arg(i + 1)));
        action->setCheckable(true);
        action->setToolTip(list[i]->summary);
        algorithm_group->addAction(action);
        sync_actions_.push_back([this, action, name] {
            action->setChecked(QString::fromStdString(view_->settings.algorithm) == name);
        });
    }
    algorithms->setToolTipsVisible(true);
    view->addSeparator();

    QMenu *help = menuBar()->addMenu("&Help");
    help->addAction("&Keyboard and mouse", this, [this] {
        QMessageBox::information(this, "Keyboard and mouse",
                                 "Orbit: left drag turns (virtual trackball), right or middle drag (or Shift) pans,\n"
                                 "wheel zooms. Walk (V): W/A/S/D move, Q/E down/up, left drag looks around.\n"
                                 "Home resets the camera, O toggles orthographic, H the heatmap,\n"
                                 "Ctrl+1..7 choose the algorithm, Ctrl+E exports a PNG,\n"
                                 "Ctrl+Shift+C copies the equivalent `oit render` command.");
    });
    help->addAction("&About", this, [this] {
        QMessageBox::about(this, "About oit-workbench",
                           QString("<b>oit-workbench</b> %1<br>Order-independent transparency for multi-part "
                                   "models: compare the algorithms live on the same scene.<br>Renderer: %2")
                               .arg(QApplication::applicationVersion(),
                                    QString::fromStdString(view_->renderer()).toHtmlEscaped()));
    });
}

void MainWindow::rebuild_recent_menu()
{
    recent_menu_->clear();
    for (const QString &path : recent_)
        recent_menu_->addAction(path, this, [this, path] { load_model(path); });
    recent_menu_->setEnabled(!recent_.isEmpty());
}

void MainWindow::add_recent(const QString &path)
{
    recent_.removeAll(path);
    recent_.prepend(path);
    while (recent_.size() > 8)
        recent_.removeLast();
    rebuild_recent_menu();
}

void MainWindow::show_error(const QString &title, const QString &message)
{
    last_error_ = message;
    status_label_->setText(message);
    // window-modal but not blocking, so the event loop (and tests) go on
    if (error_box_)
        error_box_->close();
    log_message("error", title + ": " + message);
    error_box_ = new QMessageBox(QMessageBox::Warning, title, message, QMessageBox::Ok, this);
    error_box_->setAttribute(Qt::WA_DeleteOnClose);
    error_box_->open();
}

// ----------------------------------------------------------- small controls

namespace {

// A slider with a numeric field, both bound to one float.
QWidget *slider_row(double low, double high, int decimals, std::function<float()> get,
                    std::function<void(float)> set, std::vector<std::function<void()>> &sync, bool &syncing,
                    QSlider **slider_out = nullptr)
{
    auto *row = new QWidget;
    auto *layout = new QHBoxLayout(row);
    layout->setContentsMargins(0, 0, 0, 0);
    auto *slider = new QSlider(Qt::Horizontal);
    slider->setRange(0, 1000);
    auto *spin = new QDoubleSpinBox;
    spin->setRange(low, high);
    spin->setDecimals(decimals);
    spin->setSingleStep(std::pow(10.0, -decimals) * 5);
    layout->addWidget(slider, 1);
    layout->addWidget(spin);
    auto to_slider = [=](double v) { return int(std::lround((v - low) / (high - low) * 1000.0)); };
    QObject::connect(slider, &QSlider::valueChanged, spin, [=, &syncing](int v) {
        if (syncing)
            return;
        double value = low + (high - low) * v / 1000.0;
        spin->blockSignals(true);
        spin->setValue(value);
        spin->blockSignals(false);
        set(float(spin->value()));
    });
    QObject::connect(spin, QOverload<double>::of(&QDoubleSpinBox::valueChanged), slider, [=, &syncing](double v) {
        if (syncing)
            return;
        slider->blockSignals(true);
        slider->setValue(to_slider(v));
        slider->blockSignals(false);
        set(float(v));
    });
    sync.push_back([=] {
        spin->setValue(double(get()));
        slider->setValue(to_slider(double(get())));
    });
    if (slider_out)
        *slider_out = slider;
    return row;
}

// A length from 0 ("auto") over many orders of magnitude: the slider is
// logarithmic between range()'s ends, which follow the model (a fall-off of
// 1e-3 to 4 bounding radii), and its left end is 0.
QWidget *log_length_row(std::function<std::pair<double, double>()> range, std::function<float()> get,
                        std::function<void(float)> set, std::vector<std::function<void()>> &sync, bool &syncing)
{
    auto *row = new QWidget;
    auto *layout = new QHBoxLayout(row);
    layout->setContentsMargins(0, 0, 0, 0);
    auto *slider = new QSlider(Qt::Horizontal);
    slider->setRange(0, 1000);
    auto *spin = new QDoubleSpinBox;
    spin->setDecimals(6);
    spin->setSpecialValueText("auto");
    layout->addWidget(slider, 1);
    layout->addWidget(spin);
    auto to_slider = [range](double v) {
        auto [low, high] = range();
        if (!(v > 0.0))
            return 0;
        double t = std::log(std::max(v, low) / low) / std::log(high / low);
        return std::max(1, int(std::lround(std::min(1.0, t) * 1000.0)));
    };
    QObject::connect(slider, &QSlider::valueChanged, spin, [=, &syncing](int position) {
        if (syncing)
            return;
        auto [low, high] = range();
        double value = position == 0 ? 0.0 : low * std::pow(high / low, position / 1000.0);
        spin->blockSignals(true);
        spin->setValue(value);
        spin->blockSignals(false);
        set(float(value));
    });
    QObject::connect(spin, QOverload<double>::of(&QDoubleSpinBox::valueChanged), slider, [=, &syncing](double v) {
        if (syncing)
            return;
        slider->blockSignals(true);
        slider->setValue(to_slider(v));
        slider->blockSignals(false);
        set(float(v));
    });
    sync.push_back([=] {
        auto [low, high] = range();
        spin->setRange(0.0, high * 1000.0);
        spin->setSingleStep(low * 10.0);
        spin->setValue(double(get()));
        slider->setValue(to_slider(double(get())));
    });
    return row;
}

QComboBox *combo(const QStringList &items, std::function<int()> get, std::function<void(int)> set,
                 std::vector<std::function<void()>> &sync, bool &syncing)
{
    auto *box = new QComboBox;
    box->addItems(items);
    QObject::connect(box, QOverload<int>::of(&QComboBox::currentIndexChanged), box, [=, &syncing](int i) {
        if (!syncing && i >= 0)
            set(i);
    });
    sync.push_back([=] { box->setCurrentIndex(get()); });
    return box;
}

QSpinBox *spin_box(int low, int high, std::function<int()> get, std::function<void(int)> set,
                   std::vector<std::function<void()>> &sync, bool &syncing)
{
    auto *box = new QSpinBox;
    box->setRange(low, high);
    QObject::connect(box, QOverload<int>::of(&QSpinBox::valueChanged), box, [=, &syncing](int v) {
        if (!syncing)
            set(v);
    });
    sync.push_back([=] { box->setValue(get()); });
    return box;
}

QCheckBox *check_box(const QString &text, std::function<bool()> get, std::function<void(bool)> set,
                     std::vector<std::function<void()>> &sync, bool &syncing)
{
    auto *box = new QCheckBox(text);
    QObject::connect(box, &QCheckBox::toggled, box, [=, &syncing](bool on) {
        if (!syncing)
            set(on);
    });
    sync.push_back([=] { box->setChecked(get()); });
    return box;
}

QWidget *scrolled(QWidget *content)
{
    auto *area = new QScrollArea;
    area->setWidget(content);
    area->setWidgetResizable(true);
    area->setFrameShape(QFrame::NoFrame);
    return area;
}

} // namespace

// Options the current algorithm cannot express are disabled, with a tooltip
// naming the algorithms that can (from the core's capability tables); the
// settings keep them, and a frame leaves them out and says so.
void MainWindow::apply_capabilities()
{
    if (capabilities_.empty() || !modulation_combo_)
        return;
    QString algorithm = QString::fromStdString(view_->settings.algorithm);
    auto describe = [&](const QString &key, const QString &what) {
        auto found = capabilities_.find(key);
        QStringList can = found == capabilities_.end() ? QStringList() : found->second;
        bool ok = can.contains(algorithm);
        QString tip = can.isEmpty() ? QString("%1: no algorithm can").arg(what)
                                    : QString("%1: %2 can").arg(what, can.join(", "));
        if (!ok)
            tip += QString(" — not %1, which renders without it (the Messages say so)").arg(algorithm);
        return std::make_pair(ok, tip);
    };
    auto items = [&](QComboBox *box, const std::vector<std::pair<int, QString>> &keys) {
        auto *model = qobject_cast<QStandardItemModel *>(box->model());
        if (!model)
            return;
        for (const auto &[index, key] : keys) {
            auto [ok, tip] = describe(key, box->itemText(index));
            QStandardItem *item = model->item(index);
            item->setEnabled(ok);
            item->setToolTip(tip);
        }
    };
    items(modulation_combo_, {{1, "modulation:curvature"},
                              {2, "modulation:distance"},
                              {3, "modulation:dist-curv"},
                              {4, "modulation:fields"},
                              {5, "modulation:edges"}});
    items(view_combo_, {{1, "view:heatmap"},
                        {2, "view:peel-limit"},
                        {3, "view:layer"},
                        {4, "view:neighbours"},
                        {5, "view:curvature"},
                        {6, "view:distance"},
                        {7, "view:fields"}});
    items(distance_combo_, {{1, "distance:skip"}, {2, "distance:far"}});
    if (!heatmap_action_)
        return;
    auto [heatmap_ok, heatmap_tip] = describe("view:heatmap", "heatmap view");
    heatmap_action_->setEnabled(heatmap_ok || view_->settings.modulation.view == OIT_VIEW_HEATMAP);
    heatmap_action_->setToolTip(heatmap_tip);
}

// What each row of the settings panel does, by its label (the flag in
// brackets is `oit render`'s, which Copy as command writes).
static const std::pair<const char *, const char *> kRowTips[] = {
    {"algorithm", "how transparency is composited: the exact ones (dp, ddp, ll, ib, reference) agree; "
                  "blend and wboit approximate"},
    {"sort", "ll's per-pixel sort: insertion sort in the lists, or a copy into a local array"},
    {"neighbours", "ib: how a fragment finds its neighbours on the surface (shared vertex index, welded "
                   "position, or the epsilon depth/normal search)"},
    {"memory budget", "the most the fragment pools of ll and ib may grow to"},
    {"layer cap", "dp/ddp: stop after this many layers (none: peel until nothing is left); a frame cut short "
                  "is marked TRUNCATED"},
    {"shading", "flat: the material colour; headlight: lit from the eye"},
    {"background", "the colour behind the model"},
    {"alpha", "opacity of every surface, times the part's own opacity"},
    {"contrast", "stretch the composited colour about mid-grey (1: unchanged)"},
    {"focus shape", "fade surfaces by their distance to a point, plane or box (every algorithm)"},
    {"focus (model units)", "the focus shape's point, plane (a b c d) or box (min, max), model coordinates"},
    {"focus region", "fall-off length of the focus shape and of ib's distance modulation; logarithmic slider, "
                     "left end 0 = automatic"},
    {"modulation", "ib's opacity modulation from the surface around each fragment; other algorithms do "
                   "what they can and the Messages say what they left out"},
    {"curvature effect", "how strongly curvature raises opacity (delta_c)"},
    {"curvature neighbours", "curvature from 4 or 8 neighbours"},
    {"distance", "ib: distance to the next fragment, to the one K places on, or to the last"},
    {"skip K", "ib: the fragment K places on for the skip distance"},
    {"fields", "ib: which transparency fields (alpha, beta, gamma) modulate"},
    {"diffusion iterations", "ib: diffusion steps of the fields over the surface (0 = none)"},
    {"blur iterations", "ib: blur passes of the beta field (0 = none)"},
    {"lambda", "ib: weight of the field (0 = automatic)"},
    {"epsilon max", "ib: the largest epsilon the epsilon neighbour search accepts"},
    {"halo colour", "ib: the colour of the halos the fields draw"},
    {"view", "what the view shows: the colour, the list-length heatmap, one layer, or ib's buffers"},
    {"N / layer L", "the peel limit or layer the view shows"},
    {"mode", "orbit turns about the target; walk moves with W/A/S/D, Q/E"},
    {"projection", "perspective or orthographic"},
    {"field of view", "vertical field of view of the perspective camera"},
    {"saved views", "camera poses kept for this model: double-click one to return to it"},
};

// Every control of the panel gets a tooltip: the row's own description, with
// its label (which names the command-line flag) in front.
void MainWindow::give_every_control_a_tooltip()
{
    for (QFormLayout *form : tabs_->findChildren<QFormLayout *>()) {
        for (int row = 0; row < form->rowCount(); ++row) {
            QLayoutItem *label_item = form->itemAt(row, QFormLayout::LabelRole);
            QLayoutItem *field_item = form->itemAt(row, QFormLayout::FieldRole);
            if (!field_item)
                field_item = form->itemAt(row, QFormLayout::SpanningRole);
            auto *label = label_item ? qobject_cast<QLabel *>(label_item->widget()) : nullptr;
            // the field: a widget, or a row of them in a layout
            QList<QWidget *> controls;
            std::function<void(QLayoutItem *)> collect = [&](QLayoutItem *item) {
                if (!item)
                    return;
                if (QWidget *w = item->widget()) {
                    controls << w << w->findChildren<QWidget *>();
                } else if (QLayout *layout = item->layout()) {
                    for (int i = 0; i < layout->count(); ++i)
                        collect(layout->itemAt(i));
                }
            };
            collect(field_item);
            if (controls.isEmpty())
                continue;
            QWidget *field = controls.first();
            QString name = label ? label->text() : QString();
            if (name.isEmpty())
                if (auto *button = qobject_cast<QAbstractButton *>(field))
                    name = button->text().remove('&');
            QString tip;
            for (const auto &entry : kRowTips)
                if (!name.isEmpty() && name.startsWith(entry.first))
                    tip = QString("%1: %2").arg(name, entry.second);
            if (tip.isEmpty())
                tip = name;
            if (tip.isEmpty())
                continue;
            for (QWidget *control : controls)
                if (control->toolTip().isEmpty())
                    control->setToolTip(tip);
            if (label && label->toolTip().isEmpty())
                label->setToolTip(tip);
        }
    }
}

void MainWindow::settings_changed()
{
    sync_panel_from_settings();
    render_now();
}

void MainWindow::sync_panel_from_settings()
{
    syncing_ = true;
    for (auto &action : sync_actions_)
        action();
    if (parts_panel_ && model_)
        parts_panel_->set_values(view_->settings.part_alpha, view_->settings.part_visible);
    syncing_ = false;
}

// ------------------------------------------------------------------- tabs

QWidget *MainWindow::build_algorithm_tab()
{
    RenderSettings &s = view_->settings;
    auto *page = new QWidget;
    auto *form = new QFormLayout(page);
    form->setRowWrapPolicy(QFormLayout::WrapLongRows); // narrow panels put fields under labels
    size_t count;
    const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
    QStringList names;
    for (size_t i = 0; i < count; ++i)
        names << list[i]->name;
    auto *summary = new QLabel;
    summary->setWordWrap(true);
    algorithm_combo_ = combo(
        names,
        [&s, names] { return std::max(0, int(names.indexOf(QString::fromStdString(s.algorithm)))); },
        [this, names](int i) { set_algorithm(names[i]); }, sync_actions_, syncing_);
    for (size_t i = 0; i < count; ++i)
        algorithm_combo_->setItemData(int(i), QString(list[i]->summary), Qt::ToolTipRole);
    sync_actions_.push_back([&s, summary] {
        const oit_algorithm_ops *ops = oit_algorithm_find(s.algorithm.c_str());
        summary->setText(ops ? QString("%1%2").arg(ops->summary, ops->exact ? " (exact)" : " (approximate)") : "");
    });
    form->addRow("algorithm (--algorithm)", algorithm_combo_);
    form->addRow(summary);
    form->addRow("sort (--sort, ll)", combo({"insertion", "array"}, [&s] { return int(s.config.ll_sort); },
                                            [this, &s](int i) {
                                                s.config.ll_sort = oit_ll_sort(i);
                                                render_now();
                                            },
                                            sync_actions_, syncing_));
    form->addRow("neighbours (--neighbours, ib)",
                 combo({"default (welded)", "index", "welded", "epsilon"}, [&s] { return int(s.modulation.neighbours); },
                       [this, &s](int i) {
                           s.modulation.neighbours = oit_neighbour_search(i);
                           render_now();
                       },
                       sync_actions_, syncing_));
    auto *memory = spin_box(1, 1 << 22, [&s] { return int(s.config.max_memory_bytes / (1024 * 1024)); },
                            [this, &s](int mb) {
                                s.config.max_memory_bytes = uint64_t(mb) * 1024 * 1024;
                                render_now();
                            },
                            sync_actions_, syncing_);
    memory->setSuffix(" MB");
    form->addRow("memory budget (--max-memory)", memory);
    // 0 is "no cap" (peel until nothing is left), shown as "none"
    auto *layer_cap = spin_box(0, OIT_PEEL_LAYER_CAP_MAX, [&s] { return s.config.max_layers; },
                               [this, &s](int n) {
                                   s.config.max_layers = n;
                                   render_now();
                               },
                               sync_actions_, syncing_);
    layer_cap->setSpecialValueText("none");
    form->addRow("layer cap (--max-layers, dp/ddp)", layer_cap);
    // the approximations' parameters (OIT_OPTION_LAYERS / OIT_OPTION_MOMENTS in their capabilities)
    auto *approx_layers = spin_box(1, OIT_APPROX_LAYERS_MAX,
                                   [&s] { return s.config.layers == 0 ? OIT_APPROX_LAYERS_DEFAULT : s.config.layers; },
                                   [this, &s](int n) {
                                       s.config.layers = n;
                                       render_now();
                                   },
                                   sync_actions_, syncing_);
    approx_layers->setToolTip("Layers kept per pixel by kbuffer, hybrid and mlab (k): exact where no pixel has "
                              "more fragments; memory grows with k");
    form->addRow("layers (--layers, kbuffer/hybrid/mlab)", approx_layers);
    auto *moments = combo({"power4", "power6", "trig3"},
                          [&s] { return s.config.moments == OIT_MOMENTS_DEFAULT ? 0 : int(s.config.moments) - 1; },
                          [this, &s](int i) {
                              s.config.moments = oit_moments(i + 1);
                              render_now();
                          },
                          sync_actions_, syncing_);
    moments->setToolTip("The moments mboit keeps per pixel: 4 or 6 power moments, or 3 trigonometric ones");
    form->addRow("moments (--moments, mboit)", moments);
    form->addRow("shading (--shading)", combo({"flat", "headlight"}, [&s] { return int(s.shading); },
                                              [this, &s](int i) {
                                                  s.shading = oit_shading_mode(i);
                                                  render_now();
                                              },
                                              sync_actions_, syncing_));
    auto *background = new QPushButton;
    connect(background, &QPushButton::clicked, this, [this, &s] {
        QColor c = QColorDialog::getColor(QColor::fromRgbF(s.background[0], s.background[1], s.background[2]), this,
                                          "Background (--background)");
        if (!c.isValid())
            return;
        s.background[0] = float(c.redF());
        s.background[1] = float(c.greenF());
        s.background[2] = float(c.blueF());
        settings_changed();
    });
    sync_actions_.push_back([&s, background] {
        background->setIcon(swatch(s.background));
        background->setText(colour_text(s.background));
    });
    form->addRow("background (--background)", background);
    return scrolled(page);
}

QWidget *MainWindow::build_opacity_tab()
{
    RenderSettings &s = view_->settings;
    oit_modulation &m = s.modulation;
    auto *page = new QWidget;
    auto *layout = new QVBoxLayout(page);
    auto changed = [this] { render_now(); };
    auto *global = new QGroupBox("Every algorithm");
    auto *gform = new QFormLayout(global);
    gform->setRowWrapPolicy(QFormLayout::WrapLongRows); // narrow panels put fields under labels
    gform->addRow("alpha (--alpha)", slider_row(0, 1, 3, [&s] { return s.alpha; },
                                                [&s, changed](float v) {
                                                    s.alpha = v;
                                                    changed();
                                                },
                                                sync_actions_, syncing_, &alpha_slider_));
    gform->addRow("contrast (--contrast)", slider_row(0.1, 10, 2, [&s] { return s.contrast == 0.0f ? 1.0f : s.contrast; },
                                                      [&s, changed](float v) {
                                                          s.contrast = v;
                                                          changed();
                                                      },
                                                      sync_actions_, syncing_));
    gform->addRow("focus shape", combo({"none", "point (--focus-point)", "plane (--focus-plane)", "box (--focus-box)"},
                                       [&s] { return int(s.focus_shape); },
                                       [this, &s](int i) {
                                           s.focus_shape = oit_focus_shape(i);
                                           if (model_ && i != OIT_FOCUS_NONE) {
                                               // start from something visible: the model's centre / bounds
                                               // (in file coordinates: origin + relative bounds)
                                               const oit_model &mo = *model_;
                                               const double *o = mo.origin;
                                               double defaults[4][6] = {
                                                   {0, 0, 0, 0, 0, 0},
                                                   {o[0], o[1], o[2], 0, 0, 0},
                                                   {0, 0, 1, -o[2], 0, 0},
                                                   {o[0] + mo.bounds_min[0], o[1] + mo.bounds_min[1],
                                                    o[2] + mo.bounds_min[2], o[0], o[1], o[2]}};
                                               std::copy(defaults[i], defaults[i] + 6, s.focus);
                                           }
                                           settings_changed();
                                       },
                                       sync_actions_, syncing_));
    auto *focus_row = new QWidget;
    auto *focus_layout = new QGridLayout(focus_row); // three per row: x y z (a b c d, min max)
    focus_layout->setContentsMargins(0, 0, 0, 0);
    for (int i = 0; i < 6; ++i) {
        auto *value = new QDoubleSpinBox;
        value->setRange(-1e6, 1e6);
        value->setDecimals(3);
        value->setSingleStep(0.05);
        value->setMaximumWidth(110);
        connect(value, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, [this, &s, i](double v) {
            if (!syncing_) {
                s.focus[i] = v;
                render_now();
            }
        });
        sync_actions_.push_back([&s, value, i] {
            int used = s.focus_shape == OIT_FOCUS_POINT ? 3 : s.focus_shape == OIT_FOCUS_PLANE ? 4
                       : s.focus_shape == OIT_FOCUS_BOX ? 6 : 0;
            value->setValue(s.focus[i]);
            value->setVisible(i < used);
        });
        focus_layout->addWidget(value, i / 3, i % 3);
    }
    gform->addRow("focus (model units)", focus_row);
    // shared: the focus shapes' fall-off (model units) and ib's distance modulation (eye space)
    gform->addRow("focus region (--focus-region, 0 = auto)",
                  log_length_row(
                      [this] {
                          double radius = model_ && model_->radius > 0.0f ? double(model_->radius) : 1.0;
                          return std::make_pair(radius * 1e-3, radius * 4.0);
                      },
                      [&m] { return m.focus_region; },
                      [&m, changed](float v) {
                          m.focus_region = v;
                          changed();
                      },
                      sync_actions_, syncing_));
    layout->addWidget(global);

    auto *ib = new QGroupBox("Illustration Buffer (--algorithm ib)");
    auto *form = new QFormLayout(ib);
    form->setRowWrapPolicy(QFormLayout::WrapLongRows); // narrow panels put fields under labels
    form->addRow("modulation (--modulation)",
                 modulation_combo_ = combo({"none", "curvature", "distance", "dist-curv", "fields", "edges"}, [&m] { return int(m.mode); },
                       [&m, changed](int i) {
                           m.mode = oit_modulation_mode(i);
                           changed();
                       },
                       sync_actions_, syncing_));
    form->addRow("curvature effect (--curvature-effect)",
                 slider_row(0.1, 64, 2, [&m] { return m.curvature_effect > 0 ? m.curvature_effect : 8.0f; },
                            [&m, changed](float v) {
                                m.curvature_effect = v;
                                changed();
                            },
                            sync_actions_, syncing_));
    form->addRow("curvature neighbours", combo({"4", "8"}, [&m] { return m.curvature_neighbours == 8 ? 1 : 0; },
                                               [&m, changed](int i) {
                                                   m.curvature_neighbours = i ? 8 : 4;
                                                   changed();
                                               },
                                               sync_actions_, syncing_));
    form->addRow("distance (--distance)", distance_combo_ = combo({"adjacent", "skip:K", "far"}, [&m] { return int(m.distance); },
                                                [&m, changed](int i) {
                                                    m.distance = oit_distance_mode(i);
                                                    changed();
                                                },
                                                sync_actions_, syncing_));
    form->addRow("skip K", spin_box(1, 64, [&m] { return m.distance_skip > 0 ? m.distance_skip : 2; },
                                    [&m, changed](int k) {
                                        m.distance_skip = k;
                                        changed();
                                    },
                                    sync_actions_, syncing_));
    auto *fields = new QWidget;
    auto *fields_layout = new QHBoxLayout(fields);
    fields_layout->setContentsMargins(0, 0, 0, 0);
    const char *field_names[] = {"alpha", "beta", "gamma"};
    for (int f = 0; f < 3; ++f)
        fields_layout->addWidget(check_box(field_names[f], [&m, f] { return ((m.fields ? m.fields : 7) >> f) & 1; },
                                           [&m, f, changed](bool on) {
                                               int mask = m.fields ? m.fields : 7;
                                               mask = on ? mask | (1 << f) : mask & ~(1 << f);
                                               m.fields = mask == 7 || mask == 0 ? 0 : mask;
                                               changed();
                                           },
                                           sync_actions_, syncing_));
    form->addRow("fields (--fields)", fields);
    form->addRow("diffusion iterations", spin_box(0, 1000, [&m] { return m.diffusion_iterations == 0 ? 15 : std::max(0, m.diffusion_iterations); },
                                                  [&m, changed](int n) {
                                                      m.diffusion_iterations = n == 0 ? -1 : n;
                                                      changed();
                                                  },
                                                  sync_actions_, syncing_));
    form->addRow("blur iterations", spin_box(0, 1000, [&m] { return m.blur_iterations == 0 ? 1 : std::max(0, m.blur_iterations); },
                                             [&m, changed](int n) {
                                                 m.blur_iterations = n == 0 ? -1 : n;
                                                 changed();
                                             },
                                             sync_actions_, syncing_));
    float *lambdas[] = {&m.lambda_alpha, &m.lambda_beta, &m.lambda_gamma};
    const char *lambda_names[] = {"lambda alpha (0 = auto)", "lambda beta (0 = auto)", "lambda gamma (0 = auto)"};
    for (int l = 0; l < 3; ++l) {
        float *lambda = lambdas[l];
        form->addRow(lambda_names[l], slider_row(0, 2, 3, [lambda] { return *lambda; },
                                                 [lambda, changed](float v) {
                                                     *lambda = v;
                                                     changed();
                                                 },
                                                 sync_actions_, syncing_));
    }
    form->addRow("epsilon max (--epsilon-max)",
                 slider_row(0.001, 1, 3, [&m] { return m.epsilon_max > 0 ? m.epsilon_max : 0.05f; },
                            [&m, changed](float v) {
                                m.epsilon_max = v;
                                changed();
                            },
                            sync_actions_, syncing_));
    auto *halo = new QPushButton;
    connect(halo, &QPushButton::clicked, this, [this, &m] {
        QColor start = m.has_halo_colour ? QColor::fromRgbF(m.halo_colour[0], m.halo_colour[1], m.halo_colour[2])
                                         : QColor(Qt::white);
        QColor c = QColorDialog::getColor(start, this, "Halo colour (--halo-colour)");
        if (!c.isValid())
            return;
        m.has_halo_colour = true;
        m.halo_colour[0] = float(c.redF());
        m.halo_colour[1] = float(c.greenF());
        m.halo_colour[2] = float(c.blueF());
        settings_changed();
    });
    sync_actions_.push_back([&m, halo] {
        float white[3] = {1, 1, 1};
        const float *c = m.has_halo_colour ? m.halo_colour : white;
        halo->setIcon(swatch(c));
        halo->setText(colour_text(c));
    });
    form->addRow("halo colour (--halo-colour)", halo);
    form->addRow(check_box("last layer opaque (--last-layer-opaque)", [&m] { return m.last_layer_opaque; },
                           [&m, changed](bool on) {
                               m.last_layer_opaque = on;
                               changed();
                           },
                           sync_actions_, syncing_));
    layout->addWidget(ib);
    layout->addStretch(1);
    return scrolled(page);
}

QWidget *MainWindow::build_parts_tab()
{
    // a model/view list: fluid at 10,000 parts (parts_panel.h)
    parts_panel_ = new PartsPanel;
    connect(parts_panel_, &PartsPanel::parts_changed, this, [this] {
        view_->settings.part_alpha = parts_panel_->alpha();
        view_->settings.part_visible = parts_panel_->visible();
        render_now();
    });
    connect(parts_panel_, &PartsPanel::frame_selected_requested, this,
            [this](std::vector<int> parts) { frame_parts(parts); });
    return parts_panel_;
}

void MainWindow::rebuild_parts()
{
    parts_panel_->set_model(model_.get(), view_->settings.part_alpha, view_->settings.part_visible);
}

void MainWindow::set_part_visible(int index, bool visible)
{
    RenderSettings &s = view_->settings;
    if (index < 0 || size_t(index) >= s.part_visible.size())
        return;
    s.part_visible[size_t(index)] = visible;
    parts_panel_->set_values(s.part_alpha, s.part_visible);
    render_now();
}

void MainWindow::set_part_alpha(int index, float alpha)
{
    RenderSettings &s = view_->settings;
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
    QSize size = view_->side_pixel_size();
    view_->camera.frame_box(box_min, box_max, size.width(), size.height());
    emit view_->camera_changed();
    render_now();
}

void MainWindow::pick_at(const QPoint &pixel)
{
    if (!model_)
        return;
    std::vector<float> storage;
    oit_frame_settings frame = view_->current_frame(storage);
    // side by side, both halves have the same camera: the pixel within its half
    bool right_half = view_->settings.split == SplitMode::SideBySide && pixel.x() >= frame.width;
    int x = right_half ? pixel.x() - frame.width : pixel.x();
    PickResult hit = pick(*model_, frame.modelview, frame.projection, frame.width, frame.height, x + 0.5,
                          pixel.y() + 0.5, view_->settings.part_alpha, view_->settings.part_visible);
    if (hit.component < 0) {
        status_label_->setText("nothing under the pointer");
        return;
    }
    parts_panel_->select_part(hit.component);
    status_label_->setText(QString("picked part %1 (%2), triangle %3")
                               .arg(QString::fromUtf8(model_->components[hit.component].name))
                               .arg(hit.component)
                               .arg(hit.triangle));
}

QWidget *MainWindow::build_camera_tab()
{
    Camera &camera = view_->camera;
    auto *page = new QWidget;
    auto *form = new QFormLayout(page);
    form->setRowWrapPolicy(QFormLayout::WrapLongRows); // narrow panels put fields under labels
    form->addRow("mode", combo({"orbit (trackball, wheel zoom, right-drag pan)", "walk (W/A/S/D, Q/E, mouse look)"},
                               [&camera] { return camera.mode() == Camera::Mode::Walk ? 1 : 0; },
                               [this, &camera](int i) {
                                   set_camera_mode(i ? Camera::Mode::Walk : Camera::Mode::Orbit, camera.orthographic);
                               },
                               sync_actions_, syncing_));
    form->addRow("projection", combo({"perspective", "orthographic"}, [&camera] { return camera.orthographic ? 1 : 0; },
                                     [this, &camera](int i) { set_camera_mode(camera.mode(), i == 1); },
                                     sync_actions_, syncing_));
    form->addRow("field of view (degrees)", slider_row(5, 120, 1, [&camera] { return camera.fov_degrees; },
                                                       [this, &camera](float v) {
                                                           camera.fov_degrees = v;
                                                           render_now();
                                                       },
                                                       sync_actions_, syncing_));
    auto *reset = new QPushButton("Reset camera (Home)");
    reset->setToolTip("frame the whole model again from the default three-quarter view");
    connect(reset, &QPushButton::clicked, this, [this] { view_->reset_camera(); });
    form->addRow(reset);
    saved_views_ = new QListWidget;
    auto *save = new QPushButton("Save view");
    save->setToolTip("keep the camera's pose in the list below");
    auto *restore = new QPushButton("Go to view");
    restore->setToolTip("return to the pose selected in the list");
    connect(save, &QPushButton::clicked, this, [this] {
        saved_cameras_.push_back(view_->camera);
        saved_views_->addItem(QString("view %1").arg(saved_cameras_.size()));
    });
    auto go = [this] {
        int row = saved_views_->currentRow();
        if (row >= 0 && size_t(row) < saved_cameras_.size()) {
            view_->camera = saved_cameras_[size_t(row)];
            settings_changed();
        }
    };
    connect(restore, &QPushButton::clicked, this, go);
    connect(saved_views_, &QListWidget::itemDoubleClicked, this, go);
    auto *row = new QHBoxLayout;
    row->addWidget(save);
    row->addWidget(restore);
    form->addRow("saved views", row);
    form->addRow(saved_views_);
    connect(view_, &RenderView::camera_changed, this, [this] { sync_panel_from_settings(); });
    return scrolled(page);
}

void MainWindow::set_camera_mode(Camera::Mode mode, bool orthographic)
{
    view_->camera.set_mode(mode);
    view_->camera.orthographic = orthographic;
    settings_changed();
}

QWidget *MainWindow::build_views_tab()
{
    oit_modulation &m = view_->settings.modulation;
    auto *page = new QWidget;
    auto *form = new QFormLayout(page);
    form->setRowWrapPolicy(QFormLayout::WrapLongRows); // narrow panels put fields under labels
    QStringList views = {"colour", "heatmap", "peel-limit:N", "layer:L", "neighbours (ib)",
                         "curvature:L (ib)", "distance:L (ib)", "fields:L (ib)"};
    form->addRow("view (--view)", view_combo_ = combo(views, [&m] { return int(m.view); },
                                        [this, &m](int i) {
                                            m.view = oit_view(i);
                                            if ((m.view == OIT_VIEW_PEEL_LIMIT) && m.view_parameter < 1)
                                                m.view_parameter = 1;
                                            settings_changed();
                                        },
                                        sync_actions_, syncing_));
    auto *parameter = spin_box(0, 1000, [&m] { return m.view_parameter; },
                               [this, &m](int n) {
                                   m.view_parameter = n;
                                   render_now();
                               },
                               sync_actions_, syncing_);
    auto *previous = new QPushButton("◀ nearer");
    previous->setToolTip("the layer (or peel limit) one nearer the eye");
    auto *next = new QPushButton("farther ▶");
    next->setToolTip("the layer (or peel limit) one farther from the eye");
    connect(previous, &QPushButton::clicked, parameter, [parameter] { parameter->setValue(parameter->value() - 1); });
    connect(next, &QPushButton::clicked, parameter, [parameter] { parameter->setValue(parameter->value() + 1); });
    auto *row = new QHBoxLayout;
    row->addWidget(parameter);
    row->addWidget(previous);
    row->addWidget(next);
    form->addRow("N / layer L", row);
    form->addRow(new QLabel("Layer by layer: choose layer:L and step with the buttons.\n"
                            "heatmap and peel-limit: ll and ib; the others: ib."));
    form->addRow(check_box("edge view (ib: --modulation edges)", [&m] { return m.mode == OIT_MODULATE_EDGES; },
                           [this, &m](bool on) {
                               m.mode = on ? OIT_MODULATE_EDGES : OIT_MODULATE_NONE;
                               if (on && view_->settings.algorithm != "ib")
                                   set_algorithm("ib");
                               settings_changed();
                           },
                           sync_actions_, syncing_));
    return scrolled(page);
}

QWidget *MainWindow::build_stats_tab()
{
    stats_text_ = new QPlainTextEdit;
    stats_text_->setReadOnly(true);
    stats_text_->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
    return stats_text_;
}

QWidget *MainWindow::build_compare_tab()
{
    compare_panel_ = new ComparePanel(view_->settings);
    connect(compare_panel_, &ComparePanel::changed, this, [this] { settings_changed(); });
    connect(compare_panel_, &ComparePanel::wipe_changed, view_, QOverload<>::of(&QWidget::update));
    connect(view_, &RenderView::wipe_moved, compare_panel_, [this] { compare_panel_->sync(); });
    sync_actions_.push_back([this] { compare_panel_->sync(); });
    return scrolled(compare_panel_);
}

void MainWindow::set_error_view(bool on)
{
    view_->settings.error_view = on;
    settings_changed();
}

void MainWindow::set_split(SplitMode mode, const QString &algorithm_b)
{
    view_->settings.split = mode;
    if (!algorithm_b.isEmpty() && oit_algorithm_find(algorithm_b.toUtf8().constData()))
        view_->settings.split_algorithm = algorithm_b.toStdString();
    settings_changed();
}

void MainWindow::update_stats()
{
    const oit_stats &st = view_->last_stats();
    QString text;
    QTextStream out(&text);
    double gpu_total = 0.0;
    for (int i = 0; i < st.stage_count; ++i)
        gpu_total += st.stages[i].gpu_ms;
    QSize size = view_->last_image().size();
    out << QString("%1, %2x%3\n").arg(QString::fromStdString(view_->settings.algorithm)).arg(size.width()).arg(size.height());
    out << QString("%1 frame time (CPU)   %2 ms\n").arg("", 0).arg(st.cpu_ms, 0, 'f', 2);
    out << QString("frames per second   %1%2\n")
               .arg(view_->measured_fps(), 0, 'f', 1)
               .arg(QString("")); // continuous rendering (F) measures it; otherwise 1 / frame time
    out << QString("stages (GPU)        %1 ms\n").arg(gpu_total, 0, 'f', 2);
    for (int i = 0; i < st.stage_count && i < 40; ++i)
        out << QString("  %1 %2 ms\n").arg(QString(st.stages[i].name), -18).arg(st.stages[i].gpu_ms, 8, 'f', 3);
    if (st.stage_count > 40)
        out << QString("  ... %1 stages in all\n").arg(st.stage_count);
    out << QString("memory              %1 MB\n").arg(double(st.memory_bytes) / (1024.0 * 1024.0), 0, 'f', 2);
    auto optional = [&out](const char *name, int64_t value) {
        if (value >= 0)
            out << QString("%1 %2\n").arg(name, -19).arg(qlonglong(value));
    };
    optional("fragments", st.fragments);
    optional("longest list", st.max_list);
    optional("layers", st.layers);
    if (st.truncated)
        out << QString("TRUNCATED           the layer cap %1 left fragments out\n").arg(view_->settings.config.max_layers);
    if (st.mean_list >= 0)
        out << QString("mean list           %1\n").arg(st.mean_list, 0, 'f', 2);
    if (st.psi >= 0)
        out << QString("psi (lists > 2/3 max) %1\n").arg(st.psi, 0, 'f', 4);
    if (st.overflow_retries >= 0)
        out << QString("overflow events     %1 this frame, %2 in all\n")
                   .arg(qlonglong(st.overflow_retries))
                   .arg(view_->total_overflow_retries());
    if (st.bands > 1)
        out << QString("bands of rows       %1 (more fragments than one pool holds)\n").arg(qlonglong(st.bands));
    if (st.bytes_per_fragment > 0)
        out << QString("bytes / fragment    %1\n").arg(st.bytes_per_fragment, 0, 'f', 1);
    if (st.neighbours_four_share >= 0)
        out << QString("four neighbours     %1\n").arg(st.neighbours_four_share, 0, 'f', 3);
    if (model_)
        out << QString("model               %1 triangles, %2 parts\n").arg(model_->triangle_count).arg(model_->component_count);
    out << QString("renderer            %1\n").arg(QString::fromStdString(view_->renderer()));
    // the comparisons: side B and the error against the reference
    FrameResultPointer last = view_->last_result();
    QString compared, figures;
    if (last && last->coarse_scale == 1 && view_->settings.error_view) {
        auto describe = [](const std::string &name, const ErrorResult &e) {
            if (!e.present)
                return QString("%1 vs reference: %2").arg(QString::fromStdString(name), e.problem);
            return QString("%1 vs reference: %2 (reference %3, error %4 ms)")
                .arg(QString::fromStdString(name), error_figures_text(e.figures),
                     e.reference_cached ? QString("cached") : QString("%1 ms").arg(e.reference_ms, 0, 'f', 1))
                .arg(e.error_ms, 0, 'f', 1);
        };
        figures = describe(last->algorithm, last->error_map);
        if (last->split && last->b.status == OIT_OK)
            figures += "\n" + describe(last->b.algorithm, last->b.error_map);
        out << figures << "\n";
        if (last->error_map.present)
            compared += " — vs reference: " + error_figures_text(last->error_map.figures);
    }
    if (last && last->split) {
        const SideResult &b = last->b;
        if (b.status == OIT_OK)
            out << QString("split side B        %1: %2 ms CPU, %3 MB\n")
                       .arg(QString::fromStdString(b.algorithm))
                       .arg(b.stats.cpu_ms, 0, 'f', 2)
                       .arg(double(b.stats.memory_bytes) / (1024.0 * 1024.0), 0, 'f', 2);
        else
            out << QString("split side B        %1 failed: %2\n")
                       .arg(QString::fromStdString(b.algorithm), b.error);
        compared +=
            QString(" | B %1: %2 ms").arg(QString::fromStdString(b.algorithm)).arg(b.stats.cpu_ms, 0, 'f', 1);
        if (view_->settings.error_view && b.error_map.present)
            compared += QString(", rmse %1").arg(b.error_map.figures.rmse, 0, 'f', 3);
    }
    compare_panel_->set_figures(figures);
    stats_text_->setPlainText(text);
    QString truncated;
    if (st.truncated)
        truncated = QString(" — TRUNCATED: the layer cap %1 left fragments out").arg(view_->settings.config.max_layers);
    if (st.truncated && !last_truncated_)
        log_message("warning", QString("%1: the layer cap %2 left fragments out (TRUNCATED)")
                                   .arg(QString::fromStdString(view_->settings.algorithm))
                                   .arg(view_->settings.config.max_layers));
    last_truncated_ = st.truncated;
    frame_progress(QString(), 0, 0.0);
    status_label_->setText(QString("%1: %2 ms CPU, %3 ms GPU stages, %4 MB%5%6")
                               .arg(QString::fromStdString(view_->settings.algorithm))
                               .arg(st.cpu_ms, 0, 'f', 1)
                               .arg(gpu_total, 0, 'f', 1)
                               .arg(double(st.memory_bytes) / (1024.0 * 1024.0), 0, 'f', 1)
                               .arg(truncated, compared));
}

QString MainWindow::status_text() const
{
    return status_label_->text();
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

void MainWindow::set_algorithm(const QString &name)
{
    if (!oit_algorithm_find(name.toUtf8().constData()))
        return;
    view_->settings.algorithm = name.toStdString();
    settings_changed();
}

// --------------------------------------------------------------- loading

bool MainWindow::loading() const
{
    return loader_->isRunning();
}

void MainWindow::load_model(const QString &path)
{
    if (loader_->isRunning()) {
        status_label_->setText("still loading " + loading_path_);
        return;
    }
    loading_path_ = QFileInfo(path).absoluteFilePath();
    progress_->show();
    progress_label_->setText("reading " + QFileInfo(loading_path_).fileName() + "…");
    progress_label_->show();
    status_label_->setText("loading " + loading_path_ + "…");
    log_message("load", "reading " + loading_path_);
    QString target = loading_path_;
    load_unclaimed_ = true;
    loader_->setFuture(QtConcurrent::run([target] {
        auto *result = new LoadResult;
        result->path = target;
        oit_error err{};
        QByteArray bytes = QFile::encodeName(target);
        // in a contained worker process: a parser crash or hang is an error, not our crash
        result->ok = oit_model_load_contained(bytes.constData(), nullptr, &result->model, &err) == OIT_OK;
        result->error = QString::fromUtf8(err.message);
        return result;
    }));
}

void MainWindow::load_finished()
{
    progress_->hide();
    progress_label_->hide();
    std::unique_ptr<LoadResult> result(loader_->result());
    load_unclaimed_ = false;
    if (!result->ok) {
        show_error("Cannot open model", result->error);
        emit model_failed(result->error);
        return;
    }
    model_ = ModelPointer(new oit_model(result->model), ModelDeleter());
    model_path_ = result->path;
    view_->settings.reset_parts(*model_);
    QSize size = view_->pixel_size();
    view_->camera.frame(*model_, size.width(), size.height());
    view_->camera.set_mode(Camera::Mode::Orbit);
    if (!pending_preset_.empty()) {
        bool has_camera;
        Camera camera = view_->camera;
        std::string preset_error;
        RenderSettings s = view_->settings;
        // the rest of the preset was applied when it was loaded (and may have
        // been changed since, by --algorithm for one): only parts and camera
        // needed the model
        if (preset_from_json(pending_preset_name_.toStdString(), pending_preset_, s, camera, has_camera, model_.get(),
                             preset_error)) {
            view_->settings.part_alpha = s.part_alpha;
            view_->settings.part_visible = s.part_visible;
            // a camera saved with another model would show nothing useful
            if (has_camera && pending_preset_name_ != "saved settings")
                view_->camera = camera;
        } else {
            log_message("warning", QString("the parts of %1 were not applied: %2")
                                       .arg(pending_preset_name_, QString::fromStdString(preset_error)));
        }
        pending_preset_.clear();
    }
    saved_cameras_.clear();
    saved_views_->clear();
    setWindowTitle(QString("%1 — oit-workbench").arg(QFileInfo(model_path_).fileName()));
    add_recent(model_path_);
    // one write of the settings file: each is synced to disk on this thread,
    // up to 25 ms on a busy disk (measured with strace)
    save_state(false);
    rebuild_parts();
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
    if (!model_warnings_.isEmpty()) {
        if (error_box_)
            error_box_->close();
        error_box_ = new QMessageBox(QMessageBox::Information, "Model loaded with warnings",
                                     model_warnings_.join("\n"), QMessageBox::Ok, this);
        error_box_->setAttribute(Qt::WA_DeleteOnClose);
        error_box_->open();
    }
    emit model_loaded(model_path_);
}

void MainWindow::open_model_dialog()
{
    QString path = QFileDialog::getOpenFileName(this, "Open model", QFileInfo(model_path_).absolutePath(),
                                                "Models (*.obj *.gltf *.glb *.stl *.ply *.fbx *.dae *.3ds *.off);;All files (*)");
    if (!path.isEmpty())
        load_model(path);
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
        if (path.endsWith(".json", Qt::CaseInsensitive)) {
            QString error;
            if (!load_preset(path, error))
                show_error("Load preset", error);
        } else {
            load_model(path);
        }
        event->acceptProposedAction();
    }
}

// ------------------------------------------------- presets, export, command

bool MainWindow::load_preset(const QString &path, QString &error)
{
    // a regular file only: a FIFO or /dev/zero would block or never end
    QByteArray bytes;
    if (!read_regular_file(path, nullptr, bytes, error))
        return false;
    QString text = QString::fromUtf8(bytes);
    RenderSettings s = view_->settings;
    Camera camera = view_->camera;
    bool has_camera = false;
    std::string message;
    if (!preset_from_json(path.toStdString(), text.toStdString(), s, camera, has_camera, model_.get(), message)) {
        error = QString::fromStdString(message);
        return false;
    }
    view_->settings = s;
    if (has_camera)
        view_->camera = camera;
    // a model still loading gets the preset's parts and camera when it arrives
    pending_preset_ = loading() || !model_ ? text.toStdString() : std::string();
    pending_preset_name_ = path;
    if (model_)
        rebuild_parts();
    settings_changed();
    return true;
}

bool MainWindow::save_preset(const QString &path, QString &error)
{
    // written beside the file and renamed over it once whole: a failed write
    // (a full disk) leaves the previous preset as it was; only a regular file
    // is replaced (a link to a device or a FIFO is refused)
    QByteArray bytes = QByteArray::fromStdString(preset_to_json(view_->settings, view_->camera, model_.get()));
    return write_output_file(path, nullptr, bytes, error);
}

bool MainWindow::export_png(const QString &path, int width, int height, QString &error)
{
    // checked before the frame: the core's writer would write into a FIFO (and
    // wait for a reader, on the GUI thread) or a device rather than replace it
    if (!check_output_path(path, nullptr, error))
        return false;
    oit_image image{};
    oit_frame_settings frame;
    std::string message;
    if (!view_->render_offscreen(width, height, image, frame, message)) {
        error = QString::fromStdString(message);
        return false;
    }
    oit_error err{};
    QByteArray bytes = QFile::encodeName(path);
    QString refused;
    bool ok = check_output_path(path, nullptr, refused) && // again: the frame took a while
              oit_png_write(bytes.constData(), &image, &err) == OIT_OK;
    oit_image_free(&image);
    if (!ok)
        error = refused.isEmpty() ? QString::fromUtf8(err.message) : refused;
    else
        log_message("export", QString("wrote %1 (%2x%3)").arg(path).arg(width).arg(height));
    return ok;
}

QString MainWindow::oit_program() const
{
    QString dir = QCoreApplication::applicationDirPath();
    for (const QString &candidate : {dir + "/oit", dir + "/../cli/oit", dir + "/../../src/cli/oit"})
        if (QFileInfo(candidate).isExecutable())
            return QFileInfo(candidate).canonicalFilePath();
    return "oit";
}

QString MainWindow::render_command_for_view(const QString &out_path) const
{
    if (!model_)
        return QString();
    std::vector<float> storage;
    oit_frame_settings frame = view_->current_frame(storage);
    // what the view rendered: options the algorithm left out are left out here too
    RenderSettings settings = view_->settings;
    FrameResultPointer last = view_->last_result();
    if (last && last->status == OIT_OK && last->algorithm == settings.algorithm && !last->left_out.empty()) {
        settings.modulation = last->modulation;
        settings.focus_shape = last->focus_shape;
    }
    return QString::fromStdString(render_command(oit_program().toStdString(), model_path_.toStdString(),
                                                 settings, frame, out_path.toStdString()));
}

void MainWindow::copy_command()
{
    QString command = render_command_for_view("view.png");
    if (command.isEmpty())
        return;
    QApplication::clipboard()->setText(command);
    // the whole command, wrapped and selectable (a message box cuts it off)
    auto *dialog = new QDialog(this);
    dialog->setObjectName("copied_command");
    dialog->setWindowTitle("Copied as command");
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    auto *layout = new QVBoxLayout(dialog);
    layout->addWidget(new QLabel("This `oit render` command (now on the clipboard) renders the current view:"));
    auto *text = new QPlainTextEdit(command);
    text->setObjectName("command_text");
    text->setReadOnly(true);
    text->setLineWrapMode(QPlainTextEdit::WidgetWidth);
    text->setWordWrapMode(QTextOption::WrapAnywhere);
    text->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
    text->setMinimumSize(560, 160);
    layout->addWidget(text);
    auto *buttons = new QDialogButtonBox(QDialogButtonBox::Close);
    connect(buttons, &QDialogButtonBox::rejected, dialog, &QDialog::close);
    layout->addWidget(buttons);
    dialog->open();
    status_label_->setText("copied the oit render command to the clipboard");
    log_message("copied", command);
    if (view_->settings.split != SplitMode::Off)
        log_message("split view", QString("the command line has no split view: the command renders side A "
                                          "(%1)%2, not side B (%3)")
                                      .arg(QString::fromStdString(view_->settings.algorithm),
                                           view_->settings.split == SplitMode::SideBySide
                                               ? " at half the view's width, as it is shown"
                                               : "",
                                           QString::fromStdString(view_->settings.split_algorithm)));
}

void MainWindow::export_dialog()
{
    if (!model_)
        return;
    QDialog dialog(this);
    dialog.setWindowTitle("Export PNG");
    auto *form = new QFormLayout(&dialog);
    form->setRowWrapPolicy(QFormLayout::WrapLongRows); // narrow panels put fields under labels
    QSize size = view_->side_pixel_size(); // side A's, side by side
    auto *view_size = new QRadioButton(QString("view size (%1x%2)").arg(size.width()).arg(size.height()));
    auto *custom = new QRadioButton("chosen size");
    view_size->setChecked(true);
    auto *w = new QSpinBox, *h = new QSpinBox;
    w->setRange(1, 16384);
    h->setRange(1, 16384);
    w->setValue(size.width());
    h->setValue(size.height());
    auto *size_row = new QHBoxLayout;
    size_row->addWidget(w);
    size_row->addWidget(new QLabel("x"));
    size_row->addWidget(h);
    form->addRow(view_size);
    form->addRow(custom, size_row);
    auto *buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
    form->addRow(buttons);
    if (dialog.exec() != QDialog::Accepted)
        return;
    QString path = QFileDialog::getSaveFileName(this, "Export PNG", QFileInfo(model_path_).completeBaseName() + ".png",
                                                "PNG images (*.png)");
    if (path.isEmpty())
        return;
    int width = custom->isChecked() ? w->value() : size.width();
    int height = custom->isChecked() ? h->value() : size.height();
    QString error;
    if (!export_png(path, width, height, error))
        show_error("Export PNG", error);
    else
        status_label_->setText(QString("wrote %1 (%2x%3)").arg(path).arg(width).arg(height));
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
