// render_view.h: the render view. A plain widget that shows the last frame
// the RenderWorker finished (render_worker.h) and turns mouse and keys into
// camera moves and frame requests; it never renders and never waits. The
// settings and the camera it renders are the window's (settings_model.h).
//
// Progressive frames: while the user interacts (drags, walks, moves a slider,
// types in a spin box) and full frames are slow, the view asks for a preview
// (a fast stand-in algorithm at 1/coarse_scale of the pixels per side, adapted
// to its cost) and, once the input has rested for kRestMs, for the full frame;
// when nothing changed it asks for nothing. The rules are render_worker.h's.
// A frame running longer than kProgressAfterMs shows its stage and peel count
// over the image.
//
// Comparisons (settings.error_view, settings.split): the error view shows the
// full frame's error map against the reference with a legend (error_legend.h;
// coarse frames show the plain image); the split view shows two algorithms of
// the same camera either side of a wipe line dragged with the mouse, or side
// by side (split_view.h). Both together: each side's error map.
#pragma once

#include <QElapsedTimer>
#include <QImage>
#include <QPoint>
#include <QSet>
#include <QWidget>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "camera.h"
#include "oit.h"
#include "render_worker.h"
#include "settings.h"
#include "settings_model.h"

class QPainter;
class QTimer;
class ErrorLegend;
class HeatmapLegend;
class MeasureTool;

class RenderView : public QWidget {
    Q_OBJECT
public:
    static constexpr int kRestMs = 200;           // input at rest: refine to the full frame
    static constexpr double kSlowFrameMs = 60.0;  // full frames slower than this go coarse first
    static constexpr int kProgressAfterMs = 300;  // then the overlay shows the frame's progress
    static constexpr double kPreviewBudgetMs = 60.0; // a preview slower than this goes coarser
    static constexpr int kMaxCoarseScale = 8;        // the coarsest preview: 1/8 per side
    // Auto anti-aliasing (render_worker.h): a still view's full frame is rendered
    // again at 4 samples when it took at most this long (4 samples: about 4x)
    static constexpr double kAutoSamplesMaxMs = 2500.0;

    // Shows frames of the settings model's render settings and camera (the
    // window's); the mouse and keys move that camera and the wipe line.
    explicit RenderView(SettingsModel &settings, QWidget *parent = nullptr);
    ~RenderView() override;

    // The model to show (shared with the worker, which uploads it with the next frame).
    void set_model(std::shared_ptr<const oit_model> model);
    const oit_model *model() const { return model_.get(); }
    // Frame the model again with the default three-quarter view.
    void reset_camera();

    // Ask for a new frame of the current settings: coarse first when frames are
    // slow and the user is interacting, refined when the input rests.
    void request_frame(bool interactive = true);
    // Abandon the running frame (and the refinement); the view keeps its image.
    void cancel_frame();
    // Render at width x height into image off the view (an export); frame
    // returns the matrices. Waits in a local event loop (the GUI stays live).
    // image shares the worker's pixels: no copy is made on the GUI thread
    // (MainWindow::finish_export makes the core's image on a pool thread).
    // with_highlight: the selection highlight as the view shows it (else none).
    // modelview (16 doubles, or null: the camera's) replaces the camera's
    // modelview (a turntable's frame; the projection stays the camera's).
    bool render_offscreen(int width, int height, QImage &image, oit_frame_settings &frame, std::string &error,
                          bool with_highlight = false, const double *modelview = nullptr);
    // The frame the view shows now (its size in pixels and its matrices); side
    // by side, the frame of each half (side A's, which Copy as command copies).
    oit_frame_settings current_frame(std::vector<float> &storage) const;
    QSize pixel_size() const;
    // The selection highlight (oit_local_modulation.component_highlight): these
    // parts tinted in every frame of the view, none when empty; a new frame if it changed.
    void set_highlight(const std::vector<int> &parts);
    // The measurement drawn over the image (measure_tool.h; the window's), null: none.
    void set_measure(const MeasureTool *measure);
    const std::vector<float> &highlight() const { return highlight_; } // per part 0 / 1, or empty
    // The size each side renders at: the view's, or half its width side by side.
    QSize side_pixel_size() const;
    QSize render_size() const; // the size of the last frame shown

    // The last full frame (and what the widget shows when no coarse frame is up).
    const QImage &last_image() const { return last_image_; }
    const oit_stats &last_stats() const { return last_stats_; }
    // The last result of any kind (coarse or full) that reached the view.
    FrameResultPointer last_result() const { return last_result_; }
    double measured_fps() const { return fps_; }
    long total_overflow_retries() const { return overflow_total_; }
    const std::string &renderer() const { return renderer_; }
    const std::string &shader_dir() const { return shader_dir_; }
    bool gl_ready() const { return gl_ready_; }
    const std::string &gl_error() const { return gl_error_; }
    // Why the view cannot render at all (no usable shader folder: the core's
    // one line); empty when the render worker runs. worker() is null then.
    const std::string &startup_error() const { return startup_error_; }
    RenderWorker *worker() const { return worker_.get(); }
    // Nothing waits or runs and the full frame of the current settings is shown.
    bool settled() const;
    // A frame is running or waiting.
    bool rendering() const;
    int coarse_scale() const { return coarse_scale_; }
    // What the view shows of the last result (before the overlays): side A's
    // image, or its error map; side B's in a split view (null otherwise).
    QImage shown_a() const;
    // What the view paints when it is not split: shown_a() at the view's pixel
    // size with the orientation aids the settings ask for (issue 29), drawn by
    // the core's overlay (oit_overlay_draw, as `oit render --axes --scale-bar`)
    // with the current camera on a copy; shown_a() itself when there are none.
    QImage displayed() const;
    QImage shown_b() const;
    // The error view's legend (hidden when the view shows no error map).
    ErrorLegend *legend() const { return legend_; }
    // The heatmap view's legend, the shown frame's scale (hidden in other views).
    HeatmapLegend *heatmap_legend() const { return heatmap_legend_; }
    // What is on screen when it is not the full frame of the latest request
    // ("dp refining…, showing ll preview (1/4 scale)"); empty when it is.
    QString frame_status() const;
    // The algorithm previews render with now (the stand-in, render_worker.h).
    std::string preview_algorithm() const;
    // View jobs submitted since the view was made (tests count them).
    int jobs_submitted() const { return jobs_submitted_; }
    // Full frames slower than this go coarse first while interacting (tests set 0).
    void set_slow_frame_ms(double ms) { slow_frame_ms_ = ms; }

    // --- sections and the exploded view (issue 28; section_overlay.h) ---
    // The model the shown frame drew (exploded, capped: render_worker.h), or
    // model() before one came back: what a click picks and the outline frames.
    const oit_model *drawn_model() const { return drawn_model_ ? drawn_model_.get() : model_.get(); }
    std::shared_ptr<const oit_model> drawn_model_pointer() const { return drawn_model_ ? drawn_model_ : model_; }
    // The section plane whose outline and drag handle the view draws (-1: none).
    void set_active_section(int index);
    int active_section() const { return active_section_; }
    // The handle's centre in widget coordinates; false when not drawn.
    bool section_handle(QPointF &centre) const;
    // The open parts the shown frame's sections cut (no cap), as the worker found them.
    const std::vector<uint32_t> &open_cut() const { return open_cut_; }

    void set_continuous(bool on);
    void set_progressive(bool on);
    bool progressive() const { return progressive_; }
    // The next full frame is cancelled if it runs longer than budget_ms (start-up).
    void set_full_frame_budget(double budget_ms) { full_frame_budget_ms_ = budget_ms; }

signals:
    void frame_rendered();        // a full frame is shown (stats follow it)
    void coarse_frame_rendered(); // a coarse frame is shown
    void render_failed(const QString &message);
    void frame_cancelled(const QString &why);
    void frame_progress(const QString &stage, int stages_done, double elapsed_ms);
    void options_left_out(const QStringList &messages); // empty: everything applied
    // a click without a drag (pixel coordinates); next_contributor: with Alt held
    void clicked(const QPoint &pixel, bool next_contributor);
    void wipe_moved(float wipe);       // the user dragged the wipe line
    // frame_status() changed while the full frame is not on screen (after
    // frame_rendered when a newer frame is on its way)
    void status_changed(const QString &text);
    // the active section's handle was dragged (the plane moved; the panel follows)
    void section_dragged();
    // the open parts the sections cut changed (component indices)
    void open_cut_changed(const std::vector<uint32_t> &parts);

protected:
    void paintEvent(QPaintEvent *event) override;
    void resizeEvent(QResizeEvent *event) override;
    void mousePressEvent(QMouseEvent *event) override;
    void mouseMoveEvent(QMouseEvent *event) override;
    void mouseReleaseEvent(QMouseEvent *event) override;
    void wheelEvent(QWheelEvent *event) override;
    void keyPressEvent(QKeyEvent *event) override;
    void keyReleaseEvent(QKeyEvent *event) override;
    void focusOutEvent(QFocusEvent *event) override;

private:
    const RenderSettings &settings() const { return settings_.render_settings(); }
    const Camera &camera() const { return settings_.camera(); }
    // The camera moved by the mouse or keys: its controls follow, and a frame.
    void camera_moved();
    FrameJob make_job(int width, int height, int coarse_scale) const;
    // algorithm: the job's (empty: the chosen one)
    // Auto anti-aliasing: the still view's latest full frame again at 4 samples
    // (render_worker.h); called when a frame arrives and when the input rests
    void antialias_when_still();
    // samples: 0 the rule of render_worker.h (previews 1; Auto's first full frame 1)
    void submit(int coarse_scale, bool refinement = false, const std::string &algorithm = std::string(),
                int samples = 0);
    void frame_done(FrameResultPointer result);
    void walk_tick();
    bool interacting() const;
    void update_overlays();
    void paint_measure(QPainter &painter) const; // the measurement over the image

    SettingsModel &settings_; // the window's
    std::shared_ptr<const oit_model> model_;
    std::unique_ptr<RenderWorker> worker_;
    bool gl_ready_ = false;
    std::string gl_error_, renderer_, shader_dir_, startup_error_;

    uint64_t latest_id_ = 0;      // the newest view job submitted
    uint64_t latest_coarse_id_ = 0;
    uint64_t running_job_id_ = 0; // from the worker's progress
    bool latest_is_full_ = false;
    uint64_t shown_full_id_ = 0;  // the full frame on screen
    uint64_t export_id_ = 0;
    FrameResultPointer export_result_;
    QImage shown_;                // what paintEvent draws (coarse or full)
    FrameResultPointer shown_result_; // the result shown_ came from
    ErrorLegend *legend_ = nullptr;
    HeatmapLegend *heatmap_legend_ = nullptr;
    bool dragging_wipe_ = false;
    QImage last_image_;
    FrameResultPointer last_result_;
    oit_stats last_stats_{};
    long overflow_total_ = 0;
    double last_full_ms_ = -1.0;  // unknown until a full frame finished
    std::map<std::string, double> full_ms_; // each algorithm's last full frame on this model
    std::string requested_key_;      // everything the latest request decides (empty: none)
    std::string requested_view_key_; // what it shows (frame_key: camera, size, settings)
    std::string coarse_algorithm_;   // the latest coarse job's
    bool wboit_preview_ = false;     // "auto": ll previews were too slow at the coarsest scale
    int jobs_submitted_ = 0;
    double slow_frame_ms_ = kSlowFrameMs;
    int coarse_scale_ = 2;
    bool progressive_ = true;
    bool continuous_ = false;
    double full_frame_budget_ms_ = 0.0;
    QElapsedTimer fps_clock_;
    double fps_ = 0.0;
    QString progress_text_;
    QElapsedTimer running_clock_;
    QTimer *rest_timer_ = nullptr;
    QTimer *progress_timer_ = nullptr;

    QPoint last_mouse_, press_position_;
    bool dragged_ = false;
    Qt::MouseButtons buttons_ = Qt::NoButton;
    QSet<int> walk_keys_;
    QTimer *walk_timer_ = nullptr;
    std::vector<float> highlight_; // per part: 1 highlighted; empty: no highlight
    // sections (issue 28)
    std::shared_ptr<const oit_model> drawn_model_; // the shown frame's
    // displayed()'s last image and what it was drawn from (a repaint without a
    // new frame, camera or aids reuses it)
    mutable QImage aids_image_;
    mutable qint64 aids_source_ = 0;
    mutable std::vector<double> aids_key_;
    std::vector<uint32_t> open_cut_;
    int active_section_ = -1;
    bool dragging_section_ = false;
    QPoint section_press_;
    double section_press_d_ = 0.0;
    void paint_section(QPainter &painter) const;
    // the view's matrices at its pixel size (the outline's projection); false side by side
    bool view_matrices(double modelview[16], double projection[16], QSize &size) const;
    const MeasureTool *measure_ = nullptr; // drawn over the image, reprojected each paint
};
