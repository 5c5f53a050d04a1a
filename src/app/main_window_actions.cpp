// main_window_actions.cpp: the window's menus and what their entries do
// (main_window.h): open and recent models, presets, Export PNG, Copy as
// command, undo and redo, the camera's views, the view's modes and the
// algorithms. Each entry changes the settings model and asks for a frame as
// the panels do.
#include "main_window.h"
#include "file_io.h"
#include "parts_panel.h"
#include "settings_panel.h"
#include "shortcut_help.h"
#include "algorithm_switcher.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QCheckBox>
#include <QClipboard>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QFontDatabase>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QPlainTextEdit>
#include <QProgressDialog>
#include <QRadioButton>
#include <QSpinBox>
#include <QStandardPaths>
#include <QtConcurrent/QtConcurrentRun>
#include <QFutureWatcher>
#include <QEventLoop>
#include <QUndoStack>
#include <QVBoxLayout>

#include <array>
#include <cstring>
#include <functional>
#include <memory>

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

} // namespace

// ------------------------------------------------------------------ menus

void MainWindow::build_menus()
{
    build_file_menu();

    QMenu *edit = menuBar()->addMenu("&Edit");
    QAction *undo = menu_action(edit, "&Undo settings change", QKeySequence::Undo, this, [this] { undo_settings(); });
    QAction *redo = menu_action(edit, "&Redo settings change", QKeySequence::Redo, this, [this] { redo_settings(); });
    undo->setEnabled(false);
    redo->setEnabled(false);
    connect(settings_->undo_stack(), &QUndoStack::canUndoChanged, undo, &QAction::setEnabled);
    connect(settings_->undo_stack(), &QUndoStack::canRedoChanged, redo, &QAction::setEnabled);

    build_view_menu();
    build_parts_menu();
    build_measure_menu();
    build_help_menu();
}

void MainWindow::build_file_menu()
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
    // sessions (main_window_session.cpp, docs/sessions.md)
    file->addSeparator();
    menu_action(file, "Open s&ession…", QKeySequence("Ctrl+Shift+O"), this, [this] {
        QString path = QFileDialog::getOpenFileName(this, "Open session", QFileInfo(model_path_).absolutePath(),
                                                    "Sessions (*.oitsession);;All files (*)");
        QString error;
        if (!path.isEmpty() && !open_session(path, error))
            show_error("Open session", error);
    });
    recent_sessions_menu_ = file->addMenu("Open recent sess&ion");
    menu_action(file, "Sa&ve session…", QKeySequence("Ctrl+Shift+S"), this, [this] {
        QString suggested = QFileInfo(model_path_).absolutePath() + "/" + QFileInfo(model_path_).completeBaseName() +
                            ".oitsession";
        QString path = QFileDialog::getSaveFileName(this, "Save session", suggested, "Sessions (*.oitsession)");
        if (path.isEmpty())
            return;
        if (!path.endsWith(".oitsession", Qt::CaseInsensitive))
            path += ".oitsession";
        QString error;
        if (!save_session(path, error))
            show_error("Save session", error);
    });
    file->addSeparator();
    file->addAction("&Export PNG…", this, &MainWindow::export_dialog, QKeySequence("Ctrl+E"));
    file->addAction("Export &turntable…", this, &MainWindow::turntable_dialog);
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
}

void MainWindow::build_view_menu()
{
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
            QSize size = view_->pixel_size(); // the whole model in the whole view
            settings_->camera().set_view_direction(azimuth, elevation, size.width(), size.height());
            settings_->camera_edited();
            view_->request_frame(true);
        });
    }
    QAction *ortho = view->addAction("&Orthographic");
    ortho->setShortcut(QKeySequence("O"));
    ortho->setCheckable(true);
    connect(ortho, &QAction::triggered, this, [this](bool on) { set_camera_mode(settings_->camera().mode(), on); });
    QAction *walk = view->addAction("&Walk mode (W/A/S/D, Q/E)");
    walk->setShortcut(QKeySequence("V"));
    walk->setCheckable(true);
    connect(walk, &QAction::triggered, this, [this](bool on) {
        set_camera_mode(on ? Camera::Mode::Walk : Camera::Mode::Orbit, settings_->camera().orthographic);
    });
    // the camera's state can change from the Camera tab, presets and saved views
    auto sync_camera_actions = [this, ortho, walk] {
        ortho->setChecked(settings_->camera().orthographic);
        walk->setChecked(settings_->camera().mode() == Camera::Mode::Walk);
    };
    sync_actions_.push_back(sync_camera_actions);
    QAction *heatmap = view->addAction("&Heatmap");
    heatmap->setShortcut(QKeySequence("H"));
    heatmap->setCheckable(true);
    connect(heatmap, &QAction::triggered, this, [this, heatmap](bool on) {
        // H where the algorithm has no heatmap: say why in the core's words, not nothing
        QString refused = on ? view_refusal(OIT_VIEW_HEATMAP) : QString();
        if (!refused.isEmpty()) {
            heatmap->setChecked(false);
            status_label_->setText("no heatmap: " + refused);
            log_message("heatmap", "not shown: " + refused);
            return;
        }
        settings_->render_settings().modulation.view = on ? OIT_VIEW_HEATMAP : OIT_VIEW_COLOUR;
        settings_changed();
    });
    sync_actions_.push_back([this, heatmap] {
        const RenderSettings &s = settings_->render_settings();
        heatmap->setChecked(s.modulation.view == OIT_VIEW_HEATMAP);
        // not greyed out where the algorithm cannot show it: a disabled action's
        // key does nothing, silently; the trigger says why (view_refusal)
        if (capabilities_.empty())
            return;
        heatmap->setToolTip(
            capability(capabilities_, "view:heatmap", "heatmap view", QString::fromStdString(s.algorithm)).second);
    });
    QAction *error_view = view->addAction("&Error against reference");
    error_view->setShortcut(QKeySequence("R"));
    error_view->setCheckable(true);
    error_view->setToolTip("the error map of the frame against the CPU reference, with rmse, psnr, ssim, max, "
                           "the share over 2 and the mean FLIP (--error-vs-reference)");
    connect(error_view, &QAction::triggered, this, [this](bool on) { set_error_view(on); });
    sync_actions_.push_back([this, error_view] { error_view->setChecked(settings_->render_settings().error_view); });
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
        split->setChecked(settings_->render_settings().split == SplitMode::Wipe);
        side_by_side->setChecked(settings_->render_settings().split == SplitMode::SideBySide);
    });
    QMenu *algorithm_b_menu = view->addMenu("Split view's algorithm &B");
    auto *algorithm_b_group = new QActionGroup(this);
    {
        size_t count = 0;
        const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
        for (size_t i = 0; i < count; ++i) {
            QString name = list[i]->name;
            QAction *action = algorithm_b_menu->addAction(name, this, [this, name] {
                SplitMode mode = settings_->render_settings().split;
                set_split(mode == SplitMode::Off ? SplitMode::Wipe : mode, name);
            });
            action->setCheckable(true);
            action->setToolTip(list[i]->summary);
            algorithm_b_group->addAction(action);
            sync_actions_.push_back([this, action, name] {
                action->setChecked(QString::fromStdString(settings_->render_settings().split_algorithm) == name);
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
    menu_action(view, "&Cancel frame", QKeySequence("Esc"), this, [this] {
        set_measuring(false); // Esc also leaves measure mode
        view_->cancel_frame();
    });
    view->addSeparator();
    QMenu *algorithms = view->addMenu("&Algorithm");
    // every algorithm of the core's list, filtered as you type (the ten first also have Ctrl+1..9, Ctrl+0)
    algorithms->addAction("&Switch algorithm…", this, [this] { open_algorithm_switcher(); }, QKeySequence("Ctrl+K"));
    algorithms->addSeparator();
    auto *algorithm_group = new QActionGroup(this);
    size_t count;
    const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
    for (size_t i = 0; i < count; ++i) {
        QString name = list[i]->name;
        QKeySequence key = i < 10 ? QKeySequence(QString("Ctrl+%1").arg((i + 1) % 10)) : QKeySequence();
        QAction *action = algorithms->addAction(name, this, [this, name] { set_algorithm(name); }, key);
        action->setCheckable(true);
        action->setToolTip(list[i]->summary);
        algorithm_group->addAction(action);
        sync_actions_.push_back([this, action, name] {
            action->setChecked(QString::fromStdString(settings_->render_settings().algorithm) == name);
        });
    }
    algorithms->setToolTipsVisible(true);
    view->addSeparator();
    build_aids_menu(view);
}

// issue 29: the axes triad (on by default) and the scale bar over the view,
// drawn by the core's overlay; exports and Copy as command carry them when
// "Include in exports" is on (`oit render --axes=CORNER --scale-bar`).
void MainWindow::build_aids_menu(QMenu *view)
{
    QMenu *aids = view->addMenu("Orientation &aids");
    aids->setObjectName("aids_menu");
    auto changed = [this] {
        settings_changed();
        view_->update();
    };
    // a checkable action bound to one of the settings' flags
    auto toggle = [this, aids, changed](const char *text, const char *name, const char *tip,
                                        bool RenderSettings::*flag) {
        QAction *action = aids->addAction(text);
        action->setObjectName(name);
        action->setCheckable(true);
        action->setToolTip(tip);
        connect(action, &QAction::triggered, this, [this, changed, flag](bool on) {
            settings_->render_settings().*flag = on;
            changed();
        });
        sync_actions_.push_back([this, action, flag] { action->setChecked(settings_->render_settings().*flag); });
    };
    toggle("&Axes triad", "aids_axes", "X red, Y green, Z blue, as the camera turns the model's axes (--axes)",
           &RenderSettings::axes);
    QMenu *corner = aids->addMenu("Axes &corner");
    auto *corner_group = new QActionGroup(this);
    for (int c = 0; c < 4; ++c) {
        QAction *action = corner->addAction(oit_corner_name(oit_corner(c)));
        action->setCheckable(true);
        corner_group->addAction(action);
        connect(action, &QAction::triggered, this, [this, changed, c] {
            settings_->render_settings().axes_corner = oit_corner(c);
            changed();
        });
        sync_actions_.push_back(
            [this, action, c] { action->setChecked(settings_->render_settings().axes_corner == oit_corner(c)); });
    }
    toggle("&Scale bar", "aids_scale_bar",
           "1, 2 or 5 x 10^k model units (mm for STEP and IGES), exact at the depth of the model's "
           "centre (everywhere when orthographic) (--scale-bar)",
           &RenderSettings::scale_bar);
    toggle("&Include in exports", "aids_in_export",
           "Export PNG and Copy as command carry the axes and the scale bar shown", &RenderSettings::aids_in_export);
}

QString MainWindow::view_refusal(int view) const
{
    const oit_algorithm_ops *ops = oit_algorithm_find(settings_->render_settings().algorithm.c_str());
    if (!ops)
        return QString();
    // only the view asked: the frame's other settings would be refused first
    oit_frame_settings probe;
    std::memset(&probe, 0, sizeof probe);
    probe.modulation.view = oit_view(view);
    oit_error err{};
    return oit_frame_check(ops, &probe, &err) == OIT_OK ? QString() : QString::fromUtf8(err.message);
}

void MainWindow::build_help_menu()
{
    QMenu *help = menuBar()->addMenu("&Help");
    // generated from the menus' actions and the view's gestures (shortcut_help.h)
    help->addAction("&Keyboard and mouse", this, [this] { show_keyboard_and_mouse_help(this, menuBar()); });
    help->addAction("&About", this, [this] {
        QMessageBox::about(this, "About oit-workbench",
                           QString("<b>oit-workbench</b> %1<br>Order-independent transparency for multi-part "
                                   "models: compare the algorithms live on the same scene.<br>Renderer: %2")
                               .arg(QApplication::applicationVersion(),
                                    QString::fromStdString(view_->renderer()).toHtmlEscaped()));
    });
}

AlgorithmSwitcher *MainWindow::open_algorithm_switcher()
{
    auto *switcher = new AlgorithmSwitcher(QString::fromStdString(settings_->render_settings().algorithm), this);
    connect(switcher, &AlgorithmSwitcher::chosen, this, &MainWindow::set_algorithm);
    switcher->open();
    return switcher;
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

bool MainWindow::forget_recent(const QString &path)
{
    if (recent_.removeAll(QFileInfo(path).absoluteFilePath()) + recent_.removeAll(path) == 0)
        return false;
    rebuild_recent_menu();
    return true;
}

void MainWindow::open_model_dialog()
{
    QString path = QFileDialog::getOpenFileName(this, "Open model", QFileInfo(model_path_).absolutePath(),
                                                "Models (*.obj *.gltf *.glb *.stl *.ply *.fbx *.dae *.3ds *.off);;All files (*)");
    if (!path.isEmpty())
        load_model(path);
}

// ------------------------------------------------- presets, export, command

bool MainWindow::load_preset(const QString &path, QString &error)
{
    // a regular file only: a FIFO or /dev/zero would block or never end
    QByteArray bytes;
    if (!read_regular_file(path, nullptr, bytes, error))
        return false;
    QString text = QString::fromUtf8(bytes);
    RenderSettings s = settings_->render_settings();
    Camera camera = settings_->camera();
    bool has_camera = false;
    std::string message;
    if (!preset_from_json(path.toStdString(), text.toStdString(), s, camera, has_camera, model_.get(), message)) {
        error = QString::fromStdString(message);
        return false;
    }
    settings_->render_settings() = s;
    if (has_camera)
        settings_->camera() = camera;
    // a model still loading gets the preset's parts and camera when it arrives
    pending_preset_ = loading() || !model_ ? text.toStdString() : std::string();
    pending_preset_name_ = path;
    if (model_)
        parts_panel_->set_model(model_.get(), s.part_alpha, s.part_visible);
    settings_changed();
    return true;
}

bool MainWindow::save_preset(const QString &path, QString &error)
{
    // written beside the file and renamed over it once whole: a failed write
    // (a full disk) leaves the previous preset as it was; only a regular file
    // is replaced (a link to a device or a FIFO is refused)
    QByteArray bytes =
        QByteArray::fromStdString(preset_to_json(settings_->render_settings(), settings_->camera(), model_.get()));
    return write_output_file(path, nullptr, bytes, error);
}
namespace {
// Runs work on a pool thread while a local event loop keeps the window answering.
QString off_gui_thread(const std::function<QString()> &work)
{
    QFutureWatcher<QString> watcher;
    QEventLoop loop;
    QObject::connect(&watcher, &QFutureWatcher<QString>::finished, &loop, &QEventLoop::quit);
    watcher.setFuture(QtConcurrent::run(work));
    if (!watcher.isFinished())
        loop.exec();
    return watcher.result();
}
} // namespace

// The end of an export, on a pool thread while the GUI thread runs its event
// loop: the frame's pixels (shared with the worker's result) copied into the
// core's image, the orientation aids drawn on it as `oit render --axes
// --scale-bar` draws them (the same core function on the same matrices and
// model), then written. At 3840x2160 the copy alone held the event loop for
// 0.3-0.4 s on a loaded machine (app_workbench's UHD export). Export PNG and
// every turntable frame.
QString MainWindow::finish_export(QImage shown, const oit_frame_settings &frame,
                                  std::function<QString(const oit_image &)> write) const
{
    const oit_overlay_options aids = export_aids(settings_->render_settings());
    ModelPointer model = aids.axes || aids.scale_bar ? model_ : nullptr;
    std::array<double, 16> modelview, projection;
    std::copy(frame.modelview, frame.modelview + 16, modelview.begin());
    std::copy(frame.projection, frame.projection + 16, projection.begin());
    // held through a pointer so that the last reference, and the 33 MB, go on the pool thread
    auto pixels = std::make_shared<QImage>(std::move(shown));
    return off_gui_thread([pixels, aids, model, modelview, projection, write]() -> QString {
        oit_image image{};
        oit_error err{};
        oit_status status = oit_image_alloc(&image, pixels->width(), pixels->height(), &err);
        for (int row = 0; status == OIT_OK && row < image.height; ++row)
            std::memcpy(image.rgba + size_t(row) * size_t(image.width) * 4, pixels->constScanLine(row),
                        size_t(image.width) * 4);
        *pixels = QImage();
        if (status == OIT_OK && model)
            status = oit_overlay_draw(&image, &aids, modelview.data(), projection.data(), model.get(), nullptr, &err);
        QString problem = status == OIT_OK ? write(image) : QString::fromUtf8(err.message);
        oit_image_free(&image);
        return problem;
    });
}

bool MainWindow::export_png(const QString &path, int width, int height, QString &error, bool with_highlight)
{
    if (exporting_) {
        error = "an export is already running";
        return false;
    }
    // checked before the frame: the core's writer would write into a FIFO (and
    // wait for a reader, on the GUI thread) or a device rather than replace it
    if (!check_output_path(path, nullptr, error))
        return false;
    exporting_ = true;
    QImage shown;
    oit_frame_settings frame;
    std::string message;
    if (!view_->render_offscreen(width, height, shown, frame, message, with_highlight)) {
        exporting_ = false;
        error = QString::fromStdString(message);
        return false;
    }
    // The core's writer (the bytes `oit render` writes, atomically) with the
    // aids, off the GUI thread: 0.6-0.7 s at 3840x2160 it would otherwise freeze
    QString refused;
    bool ok = check_output_path(path, nullptr, refused); // again: the frame took a while
    if (ok) {
        QByteArray name = QFile::encodeName(path);
        refused = finish_export(std::move(shown), frame, [name](const oit_image &image) -> QString {
            oit_error err{};
            return oit_png_write(name.constData(), &image, &err) == OIT_OK ? QString() : QString::fromUtf8(err.message);
        });
        ok = refused.isEmpty();
    }
    exporting_ = false;
    if (!ok) {
        error = refused;
        return false;
    }
    export_folder_ = QFileInfo(path).absolutePath();
    log_message("export", QString("wrote %1 (%2x%3)").arg(path).arg(width).arg(height));
    return true;
}

QString MainWindow::export_folder() const
{
    if (!export_folder_.isEmpty() && QFileInfo(export_folder_).isDir())
        return export_folder_;
    QString pictures = QStandardPaths::writableLocation(QStandardPaths::PicturesLocation);
    return pictures.isEmpty() ? QDir::homePath() : pictures;
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
    RenderSettings settings = settings_->render_settings();
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
    const RenderSettings &s = settings_->render_settings();
    if (s.split != SplitMode::Off)
        log_message("split view", QString("the command line has no split view: the command renders side A "
                                          "(%1)%2, not side B (%3)")
                                      .arg(QString::fromStdString(s.algorithm),
                                           s.split == SplitMode::SideBySide ? " at half the view's width, as it is shown"
                                                                            : "",
                                           QString::fromStdString(s.split_algorithm)));
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
    // the size chosen last time is offered again
    (export_size_.isValid() ? custom : view_size)->setChecked(true);
    auto *w = new QSpinBox, *h = new QSpinBox;
    w->setRange(1, 16384);
    h->setRange(1, 16384);
    w->setValue(export_size_.isValid() ? export_size_.width() : size.width());
    h->setValue(export_size_.isValid() ? export_size_.height() : size.height());
    auto *size_row = new QHBoxLayout;
    size_row->addWidget(w);
    size_row->addWidget(new QLabel("x"));
    size_row->addWidget(h);
    form->addRow(view_size);
    form->addRow(custom, size_row);
    auto *with_highlight = new QCheckBox("Include selection highlight");
    with_highlight->setObjectName("export_highlight");
    with_highlight->setToolTip("the selected parts tinted as in the view; without, the image has no highlight");
    with_highlight->setEnabled(!view_->highlight().empty());
    form->addRow(with_highlight);
    auto *with_aids = new QCheckBox("Include axes triad and scale bar (as shown)");
    with_aids->setObjectName("export_aids");
    with_aids->setToolTip("the orientation aids the view shows (View > Orientation aids); Copy as command "
                          "then carries them too (--axes, --scale-bar)");
    with_aids->setChecked(settings_->render_settings().aids_in_export);
    with_aids->setEnabled(settings_->render_settings().axes || settings_->render_settings().scale_bar);
    form->addRow(with_aids);
    auto *buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
    form->addRow(buttons);
    if (dialog.exec() != QDialog::Accepted)
        return;
    export_size_ = custom->isChecked() ? QSize(w->value(), h->value()) : QSize();
    if (with_aids->isEnabled() && with_aids->isChecked() != settings_->render_settings().aids_in_export) {
        settings_->render_settings().aids_in_export = with_aids->isChecked();
        settings_changed();
    }
    QString path = QFileDialog::getSaveFileName(
        this, "Export PNG", export_folder() + "/" + QFileInfo(model_path_).completeBaseName() + ".png",
        "PNG images (*.png)");
    if (path.isEmpty())
        return;
    int width = custom->isChecked() ? w->value() : size.width();
    int height = custom->isChecked() ? h->value() : size.height();
    QString error;
    if (!export_png(path, width, height, error, with_highlight->isChecked()))
        show_error("Export PNG", error);
    else
        status_label_->setText(QString("wrote %1 (%2x%3)").arg(path).arg(width).arg(height));
}

// ------------------------------------------------------------- turntable

QString MainWindow::turntable_command(const QString &folder, int frames, int width, int height, int fps) const
{
    if (!model_)
        return QString();
    // Copy as command's, with the frame at the export's size (its projection's aspect), then the turntable's flags
    std::vector<float> storage;
    RenderSettings settings = settings_->render_settings();
    oit_frame_settings frame = make_frame(settings, *model_, settings_->camera(), width, height, storage);
    FrameResultPointer last = view_->last_result();
    if (last && last->status == OIT_OK && last->algorithm == settings.algorithm && !last->left_out.empty()) {
        settings.modulation = last->modulation;
        settings.focus_shape = last->focus_shape;
    }
    QString command = QString::fromStdString(render_command(oit_program().toStdString(), model_path_.toStdString(),
                                                            settings, frame, folder.toStdString()));
    command += QString(" --turntable %1 --turntable-up %2")
                   .arg(frames)
                   .arg(settings_->camera().up == Camera::Up::Z ? "z" : "y");
    command += fps > 0 ? QString(" --fps %1").arg(fps) : QString(" --no-video");
    return command;
}

bool MainWindow::export_turntable(const QString &folder, int frames, int width, int height, int fps, QString &error)
{
    if (!model_) {
        error = "no model is loaded";
        return false;
    }
    if (exporting_) {
        error = "an export is already running";
        return false;
    }
    oit_error err{};
    QByteArray name = QFile::encodeName(folder);
    oit_turntable_output *output = nullptr;
    if (oit_turntable_output_open(name.constData(), "turntable", width, height, frames, fps, &output, &err) !=
        OIT_OK) {
        error = QString::fromUtf8(err.message);
        return false;
    }
    exporting_ = true;
    QProgressDialog progress("Rendering the turntable…", "Cancel", 0, frames, this);
    progress.setObjectName("turntable_progress");
    progress.setWindowTitle("Export turntable");
    progress.setWindowModality(Qt::WindowModal);
    progress.setMinimumDuration(0);
    progress.setValue(0);
    // the orbit (oit.h): about the camera's up axis through the model's centre
    double axis[3], centre[3], base[16];
    oit_turntable_axis(nullptr, settings_->camera().up == Camera::Up::Z ? OIT_TURNTABLE_UP_Z : OIT_TURNTABLE_UP_Y,
                       axis, nullptr);
    std::memcpy(centre, model_->origin, sizeof centre);
    QString problem;
    for (int i = 0; i < frames && problem.isEmpty() && !progress.wasCanceled(); ++i) {
        double modelview[16];
        if (i > 0)
            oit_turntable_modelview(base, centre, axis, i, frames, modelview);
        QImage shown;
        oit_frame_settings frame;
        std::string message;
        // frame 0 is Export PNG's frame of the view at this size; the others turn its modelview
        if (!view_->render_offscreen(width, height, shown, frame, message, false, i > 0 ? modelview : nullptr)) {
            problem = QString::fromStdString(message);
            break;
        }
        if (i == 0)
            std::memcpy(base, frame.modelview, sizeof base);
        problem = finish_export(std::move(shown), frame, [output](const oit_image &image) -> QString {
            oit_error e{};
            return oit_turntable_output_add(output, &image, &e) == OIT_OK ? QString() : QString::fromUtf8(e.message);
        });
        if (problem.isEmpty()) {
            progress.setValue(i + 1);
            emit turntable_progress(i + 1, frames);
        }
    }
    bool cancelled = problem.isEmpty() && progress.wasCanceled();
    if (problem.isEmpty() && !cancelled) {
        progress.setLabelText("Finishing the video…");
        problem = off_gui_thread([output]() -> QString {
            oit_error e{};
            return oit_turntable_output_commit(output, &e) == OIT_OK ? QString() : QString::fromUtf8(e.message);
        });
    } else {
        oit_turntable_output_abort(output); // nothing is left behind
    }
    progress.reset();
    exporting_ = false;
    if (cancelled) {
        error = "cancelled: nothing was written";
        log_message("turntable", QString("cancelled: %1 is as it was").arg(folder));
        return false;
    }
    if (!problem.isEmpty()) {
        error = problem;
        return false;
    }
    log_message("turntable", QString("wrote %1 frames of %2x%3 in %4; the same with: %5")
                                 .arg(frames)
                                 .arg(width)
                                 .arg(height)
                                 .arg(folder, turntable_command(folder, frames, width, height, fps)));
    return true;
}

void MainWindow::turntable_dialog()
{
    if (!model_)
        return;
    QDialog dialog(this);
    dialog.setWindowTitle("Export turntable");
    auto *form = new QFormLayout(&dialog);
    form->setRowWrapPolicy(QFormLayout::WrapLongRows);
    QSize size = view_->side_pixel_size();
    auto *frames = new QSpinBox, *w = new QSpinBox, *h = new QSpinBox, *fps = new QSpinBox;
    frames->setRange(1, OIT_TURNTABLE_FRAMES_MAX);
    frames->setValue(120);
    w->setRange(2, 16384);
    h->setRange(2, 16384);
    w->setValue(size.width() & ~1); // the video needs even sides
    h->setValue(size.height() & ~1);
    fps->setRange(1, OIT_VIDEO_FPS_MAX);
    fps->setValue(30);
    auto *video = new QCheckBox("MP4 video (H.264; even width and height)");
    video->setChecked(true);
    auto *size_row = new QHBoxLayout;
    size_row->addWidget(w);
    size_row->addWidget(new QLabel("x"));
    size_row->addWidget(h);
    form->addRow("Frames (a full turn)", frames);
    form->addRow("Size", size_row);
    form->addRow(video);
    form->addRow("Frames per second", fps);
    connect(video, &QCheckBox::toggled, fps, &QWidget::setEnabled);
    form->addRow(new QLabel("The folder gets frame_0000.png … and turntable.mp4; the camera turns about the\n"
                            "up axis (View ▸ Up) through the model's centre, starting from this view."));
    auto *buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
    form->addRow(buttons);
    if (dialog.exec() != QDialog::Accepted)
        return;
    QString folder = QFileDialog::getSaveFileName(
        this, "Export turntable (a folder)", export_folder() + "/" + QFileInfo(model_path_).completeBaseName() +
                                                 "-turntable",
        QString(), nullptr, QFileDialog::ShowDirsOnly);
    if (folder.isEmpty())
        return;
    QString error;
    if (!export_turntable(folder, frames->value(), w->value(), h->value(), video->isChecked() ? fps->value() : 0,
                          error)) {
        if (!error.startsWith("cancelled"))
            show_error("Export turntable", error);
        status_label_->setText("turntable: " + error);
    } else {
        export_folder_ = QFileInfo(folder).absolutePath();
        status_label_->setText(QString("wrote the turntable in %1").arg(folder));
    }
}

// ----------------------------------------------------------------- paths
