// main_window.h: the workbench window: the render view, the settings panel's
// tabs (one class each: algorithm_panel.h, opacity_panel.h, parts_panel.h,
// camera_panel.h, views_panel.h, stats_panel.h, compare_panel.h) over the
// settings model (settings_model.h), the menus and their actions, the
// Messages, progress and Cancel, model loading off the GUI thread
// (model_loader.h), Export PNG, "Copy as command", presets and the saved
// state (saved_state.h).
#pragma once

#include <QMainWindow>
#include <QPointer>
#include <QStringList>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "model_loader.h"
#include "oit.h"
#include "render_view.h"
#include "saved_state.h"
#include "settings.h"
#include "settings_model.h"

class QDockWidget;
class QLabel;
class QMenu;
class QMessageBox;
class QPlainTextEdit;
class QProgressBar;
class QPushButton;
class QSlider;
class QTabWidget;
class AlgorithmPanel;
class AlgorithmSwitcher;
class CameraPanel;
class MeasureTool;
struct ContributorPick;
class ComparePanel;
class OpacityPanel;
class PartsPanel;
class SectionsPanel;
class SettingsPanel;
class StatsPanel;
class HistogramPlot;
class ViewsPanel;

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    // What the window does with the saved state (saved_state.h).
    enum class Start {
        Restore,  // the last settings, window layout and recent models; saved again
        Fresh,    // --fresh: the defaults, with the recent models; saved again
        Untouched // --screenshot: the saved state is neither read nor written
    };
    explicit MainWindow(Start start = Start::Restore, QWidget *parent = nullptr);
    ~MainWindow() override;

    // Why the workbench cannot run (no usable shader folder: the core's one
    // line, as `oit` says it); empty when it can. The window then renders
    // nothing and must not be shown: main() says it and exits with status 3.
    QString startup_error() const { return QString::fromStdString(view_->startup_error()); }
    // Say startup_error() in a modal dialog; returns the exit status, 3.
    static int refuse_to_start(const QString &problem);
    // The last model of the saved state ("" if none, or not restored).
    QString saved_last_model() const;
    const SettingsFile &settings_file() const { return settings_file_; }

    RenderView *view() const { return view_; }
    // The render settings and the camera, with their undo history.
    SettingsModel *settings_model() const { return settings_; }
    const oit_model *model() const { return model_.get(); }
    QString model_path() const { return model_path_; }
    bool loading() const;
    QString last_error() const { return last_error_; }
    // which algorithms express which option (the core's capability tables)
    const CapabilityTable &capabilities() const { return capabilities_; }
    // the loaded model's import warnings (oit_model.warnings), shown in a notice
    QStringList model_warnings() const { return model_warnings_; }
    QString status_text() const;
    // File > Open recent, newest first (a model that failed to open is dropped).
    const QStringList &recent_models() const { return recent_; }
    // Why the current algorithm cannot show this oit_view, in the core's words
    // (oit_frame_check: "mboit: buffer views are ll's and ib's ..."); empty if it can.
    QString view_refusal(int view) const;
    // The message area: loads, exports, copies, warnings, cancels and errors
    // stay readable there (newest last), each line "[hh:mm:ss] kind: text".
    QStringList messages() const;
    void log_message(const QString &kind, const QString &text);

    // Start loading a model off the GUI thread (the previous one stays until it succeeds).
    void load_model(const QString &path);
    // Apply a preset file now (and its parts again when the next model arrives).
    bool load_preset(const QString &path, QString &error);
    bool save_preset(const QString &path, QString &error);
    // File > Save session… and Open session… (session.h, docs/sessions.md): the
    // model (relative to the session file), the settings, the camera, the saved
    // views and Export PNG's frame. Opening checks the whole file first (false
    // with a one-line error, nothing changed), applies the settings, then loads
    // the model off the GUI thread; its parts, camera and views follow when it
    // is in (model_loaded). Unknown fields are said in the Messages.
    bool save_session(const QString &path, QString &error);
    bool open_session(const QString &path, QString &error);
    // File > Open recent session, newest first.
    const QStringList &recent_sessions() const { return recent_sessions_; }
    // The Camera tab (its saved views).
    CameraPanel *camera_panel() const { return camera_panel_; }
    // Renders off the view, then encodes the PNG off the GUI thread (a local
    // event loop waits, so the window keeps answering); clears the progress.
    // with_highlight: the selection highlight as the view shows it (Export PNG's
    // "Include selection highlight"); without, none.
    bool export_png(const QString &path, int width, int height, QString &error, bool with_highlight = false);
    // Where Export PNG's save dialog opens: the last export's folder, else the
    // user's Pictures folder (never the source tree).
    QString export_folder() const;
    // The size Export PNG last used when chosen (invalid: the view's size).
    QSize export_size() const { return export_size_; }
    // File > Export turntable… (docs/workbench.md): frames frames of the camera's
    // orbit about the up axis (View's Y or Z up) through the model's centre
    // (oit.h, "turntables"), frame 0 the view, each rendered as Export PNG
    // renders (the render worker, a fresh algorithm: `oit render`'s bytes),
    // written with the video (fps > 0; 0: none) off the GUI thread into
    // folder, replaced whole. A progress dialog ("turntable_progress") with
    // Cancel: the frame under way ends, then nothing is left behind.
    bool export_turntable(const QString &folder, int frames, int width, int height, int fps, QString &error);
    // The `oit render --turntable` command that writes the same folder.
    QString turntable_command(const QString &folder, int frames, int width, int height, int fps) const;
    // The `oit render` command for the current view (what "Copy as command" copies).
    QString render_command_for_view(const QString &out_path) const;
    QString oit_program() const;

    // Settings changed by code (tests, presets): refresh the panel and render.
    void settings_changed();
    // Refresh every control from the settings (no frame).
    void sync_panel_from_settings();
    // Copy the `oit render` command for the view and show it (File > Copy as command).
    void copy_command();
    void set_algorithm(const QString &name);
    // View > Algorithm > Switch algorithm… (Ctrl+K): every algorithm, filtered as you type.
    AlgorithmSwitcher *open_algorithm_switcher();
    void set_part_visible(int index, bool visible);
    void set_part_alpha(int index, float alpha);
    PartsPanel *parts_panel() const { return parts_panel_; }
    // The Sections tab (issue 28): planes, caps, the parts cut, the explode factor.
    SectionsPanel *sections_panel() const { return sections_panel_; }
    // Turn the camera's target to these parts' bounds and fit them in the view.
    void frame_parts(const std::vector<int> &parts);
    // Select the part that adds most to a view pixel's colour (a click in the
    // view); a click again at the same pixel of the same frame (or Alt+click):
    // the one behind it, stepping further back each time (after the last, the
    // front again); a click elsewhere starts at the front.
    void pick_at(const QPoint &pixel, bool next_contributor = false);
    // Selection (main_window_selection.cpp): Parts > Highlight selection (on by
    // default) tints the selected parts in the view; Parts > Fade others
    // (ghosting) sets every part not selected to the fade opacity in one undo step.
    void set_highlight_selection(bool on);
    bool highlight_selection() const;
    bool fade_others();
    // Select the parts these names or assembly paths match (as `oit render --highlight`
    // and --component-alpha match them: oit_model_match_parts); false, with the
    // name that matches nothing in error, when one does not match.
    bool select_parts_named(const QStringList &names, QString &error);
    // Measure ▸ Measure distance (main_window_measure.cpp, measure_tool.h): in
    // measure mode a click picks a point as a click picks a part (pick_at: the
    // part adding most to the pixel, its point), A, then B, then A again; the
    // distance is drawn in the view, said in the status bar and the Messages.
    // Esc (View ▸ Cancel frame) leaves the mode and drops the markers; Ctrl+C
    // copies the line while A and B are set.
    void set_measuring(bool on);
    bool measuring() const;
    const MeasureTool &measure_tool() const { return *measure_; }
    // Measure ▸ Copy measurement: the line on the clipboard (empty without B).
    QString copy_measurement();
    QSlider *alpha_slider() const;
    ComparePanel *compare_panel() const { return compare_panel_; }
    // View ▸ Error against reference, Split view, Side by side (and the Compare tab)
    void set_error_view(bool on);
    void set_split(SplitMode mode, const QString &algorithm_b = QString());
    void set_camera_mode(Camera::Mode mode, bool orthographic);
    // Undo / redo of settings changes (Edit menu); false when there is none.
    bool undo_settings();
    bool redo_settings();
    // Forget the history: the current settings are where undo stops.
    void reset_settings_history();
    // Bring a settings tab to the front by its name (case-insensitive).
    bool show_tab(const QString &name);
    // The settings panel's dock (View > Settings panel, F4 shows or hides it).
    QDockWidget *settings_dock() const { return settings_dock_; }
    // The settings panel's width at the first start (and in a fresh layout).
    static constexpr int kSettingsPanelWidth = 300;
    static constexpr int kSettingsPanelMaxWidth = 480; // 40% of a 1200 px window
    // Move (and shrink) the window onto the screens' available area when it is
    // partly off them (a geometry saved on another monitor layout).
    void keep_on_screen();

    // The path of the bundled default model (resources/models/gearbox.obj).
    static QString default_model_path();
    static QString source_root();

signals:
    void model_loaded(const QString &path);
    void model_failed(const QString &message);
    // Export turntable: frames written so far of total.
    void turntable_progress(int done, int total);

protected:
    void dragEnterEvent(QDragEnterEvent *event) override;
    void dropEvent(QDropEvent *event) override;
    void closeEvent(QCloseEvent *event) override;

private:
    void build_menus();
    void turntable_dialog(); // File > Export turntable…
    void build_file_menu();
    void build_view_menu();
    void build_aids_menu(QMenu *view); // View > Orientation aids (issue 29)
    void build_help_menu();
    void build_parts_menu(); // main_window_selection.cpp
    void update_highlight(); // the view's highlight from the selection and the action
    void build_measure_menu(); // main_window_measure.cpp
    void measuring_toggled(bool on); // the cursor, the status; off: the markers go
    // A click's pick in measure mode: a point, or why not (the status bar).
    void measure_pick(const ContributorPick &hit, const std::string &error);
    // The settings panel's tabs, wired to the settings model.
    QTabWidget *build_tabs();
    // The tabs whose controls are bound to the settings (settings_panel.h).
    std::array<SettingsPanel *, 5> settings_panels() const;
    // Sections (issue 28): a click in the view while the Sections tab's "Pick
    // face" is on puts the active plane on the face under it, facing the eye.
    void pick_section_face(const QPoint &pixel);
    // The Messages name the open parts the sections cut (they get no cap).
    void say_open_cut(const std::vector<uint32_t> &parts);
    void update_stats();
    void load_finished(ModelPointer model, const QString &path);
    void load_failed(const QString &message);
    void add_recent(const QString &path);
    // A model that failed to open leaves Open recent; false if it was not there.
    bool forget_recent(const QString &path);
    // Write the saved state (the recent models and the last model; closing,
    // also the settings and the window's layout); a failure goes to the
    // Messages once (and to stderr when closing, the Messages going with the window).
    void save_state(bool closing);
    void restore_saved_settings();
    void rebuild_recent_menu();
    void add_recent_session(const QString &path);
    void rebuild_recent_sessions_menu();
    void show_error(const QString &title, const QString &message);
    // A notice that does not block (window-modal, the event loop goes on).
    void show_notice(QMessageBox *box);
    void open_model_dialog();
    void export_dialog();
    // A control changed the settings: one undo step (coalesced), and a frame.
    void render_now();
    // Undo or redo replaced the settings: the panel follows, and a full frame.
    void settings_restored();
    void frame_progress(const QString &stage, int stages_done, double elapsed_ms);

    SettingsModel *settings_ = nullptr;
    RenderView *view_ = nullptr;
    ModelLoader *loader_ = nullptr;
    // An exported frame made the core's image, aids drawn, then written by
    // write, on a pool thread (main_window_actions.cpp); "" or the message.
    QString finish_export(QImage shown, const oit_frame_settings &frame,
                          std::function<QString(const oit_image &)> write) const;
    ModelPointer model_;
    QPoint last_pick_pixel_{-1, -1}; // where the last click picked, and the rank it showed
    int last_pick_rank_ = 0;
    std::vector<double> last_pick_camera_; // the frame's matrices and opacities then: a repeated click steps deeper only in it
    QAction *highlight_action_ = nullptr;
    QAction *fade_action_ = nullptr;
    std::unique_ptr<MeasureTool> measure_; // main_window_measure.cpp
    QAction *measure_action_ = nullptr;
    QAction *copy_measure_action_ = nullptr;
    QString model_path_;
    QString loading_path_;
    QString last_error_;
    QStringList model_warnings_;
    std::string pending_preset_; // applied again once the next model is loaded
    QString pending_preset_name_;
    const CapabilityTable capabilities_;

    QTabWidget *tabs_ = nullptr;
    QDockWidget *settings_dock_ = nullptr;
    AlgorithmPanel *algorithm_panel_ = nullptr;
    OpacityPanel *opacity_panel_ = nullptr;
    PartsPanel *parts_panel_ = nullptr;
    CameraPanel *camera_panel_ = nullptr;
    ViewsPanel *views_panel_ = nullptr;
    StatsPanel *stats_panel_ = nullptr;
    HistogramPlot *histogram_plot_ = nullptr; // under the Stats tab's text: the frame's list lengths
    ComparePanel *compare_panel_ = nullptr;
    SectionsPanel *sections_panel_ = nullptr;

    QProgressBar *progress_ = nullptr;
    QLabel *progress_label_ = nullptr;
    QPushButton *cancel_button_ = nullptr;
    QLabel *status_label_ = nullptr;
    QPlainTextEdit *messages_ = nullptr;
    QStringList message_lines_;
    QString last_left_out_; // said once per change, not once per frame
    bool last_truncated_ = false;
    QMenu *recent_menu_ = nullptr;
    QStringList recent_;
    QMenu *recent_sessions_menu_ = nullptr;
    QStringList recent_sessions_;
    // a session's saved views, given to the Camera tab once its model is in
    std::vector<SavedView> pending_views_;
    bool pending_session_ = false;
    SettingsFile settings_file_;
    SavedStateText saved_; // as read, updated by each save
    Start start_ = Start::Restore;
    QString last_save_error_; // said once
    std::vector<std::function<void()>> sync_actions_; // the menus' checks follow the settings
    QPointer<QMessageBox> error_box_;
    QString export_folder_; // the last export's, kept in the saved state
    QSize export_size_;     // the last chosen export size; invalid: the view's
    bool exporting_ = false; // one export at a time (its waits run the event loop)
};
