// render_worker.h: the thread that renders every frame of the workbench.
//
// The GUI thread never waits for a frame. A RenderWorker owns a thread with
// its own headless GL context (the core's EGL or OSMesa context, the one
// `oit render` uses, so an exported PNG is byte for byte the command line's),
// the uploaded scene and a small cache of algorithm instances. The GUI submits
// FrameJobs; results and progress come back as queued signals.
//
// Scheduling, in one place (RenderWorker::keep_going):
// - the newest view job replaces a pending one (latest settings win);
// - a running full view frame is abandoned between stages (between peels for
//   dp and ddp) when a newer view job waits; a running coarse frame (a
//   preview) finishes when the job waiting is the next coarse frame of the
//   drag or a refinement, so that a continuous drag always moves (superseding
//   previews by newer ones used to show nothing until the drag stopped when a
//   preview took longer than the moves' interval); it is abandoned for a full
//   frame the user asked for (an algorithm switch, F5);
// - cancel() abandons whatever runs or waits; export jobs are never superseded.
// - a turntable (MainWindow::export_turntable) is a series of export jobs, one
//   per frame, each submitted when the previous frame's PNG and video frame
//   are written (on a pool thread, not here): no frame waits behind another,
//   view jobs run between them, and Cancel stops after the frame under way.
//
// What the view asks for (RenderView::request_frame; the rules live here):
// - nothing changed since the last request (same algorithm, settings, camera,
//   size, comparisons): no job at all, its frames are shown or on their way;
// - the view did not change, only the algorithm, its configuration or a
//   comparison did: the full frame at once, never a coarse one (the image on
//   screen already shows this view);
// - the view changed (camera, size, opacity, a modulation, a part) while the
//   user interacts, and the chosen algorithm's last full frame on this model
//   took over RenderView::kSlowFrameMs (or is unknown): a preview job, then the full frame
//   once the input rested for RenderView::kRestMs (a refinement: it waits for the preview);
//   otherwise the full frame at once ("fast enough, no stand-in");
// - the preview renders with the stand-in of "Preview algorithm while
//   moving" (RenderSettings::preview_algorithm) at 1/coarse_scale per side:
//   "auto" is ll, or wboit once an ll preview at the coarsest scale still took
//   over RenderView::kPreviewBudgetMs (ll's fill grows with the fragments; wboit's does
//   not sort: on the 512-sphere scene at 150x95 ll takes 100 ms, wboit 61 ms;
//   on the engine both about 35 ms: docs/workbench.md); "same" is the chosen
//   algorithm itself (the view's behaviour before stand-ins); a split view
//   previews with its own two algorithms;
// - the scale adapts to the preview's own time: coarser (up to
//   RenderView::kMaxCoarseScale) above kPreviewBudgetMs, finer below a quarter of it.
// - anti-aliasing (RenderSettings::samples, --samples): previews always render at
//   1 sample; a chosen count (4, 8, 16) renders every full frame at it; Auto (the
//   default; the colour view only: the diagnostic views and the error map show
//   each pixel centre's figures, at 1) renders full frames at 1 sample while the view changes and, once the
//   full frame of the latest request is shown, the input rests (no button or walk
//   key held, no rest timer running) and that frame took at most
//   RenderView::kAutoSamplesMaxMs, asks for the same frame again at
//   RenderSettings::kAutoSamples (4) samples, an ordinary view job that any newer
//   one supersedes; 4 samples cost about 4 times the frame (docs/benchmarks.md,
//   "Anti-aliasing"), so a still view gets edges without slowing a drag. Exports
//   render at export_samples (at least 4; the chosen count if higher), and their
//   command says --samples.
// The status line names what is on screen and what renders
// (RenderView::frame_status: "dp refining…, showing ll preview (1/4 scale)").
// Options an algorithm cannot express (the core refuses them with
// OIT_E_INPUT before doing any work) are dropped one by one and named in
// FrameResult::left_out instead of failing the frame.
//
// Comparisons, in the same job and with the same frame (camera, size, settings):
// - split view: a second algorithm (FrameJob::algorithm_b) renders the frame
//   after the first, from its own cached instance;
// - error view: full frames also take the CPU reference's image of the frame
//   each side rendered (rendered here, on this thread, cancellable between its
//   passes like any frame, or taken from a small cache keyed by the frame's
//   camera, size and settings) and the error map and figures against it.
//   Coarse frames skip the reference (docs/workbench.md says why).
//
// The model as drawn (issue 28, docs/sections.md): a job names the loaded
// model, the explode factor (FrameJob::explode) and the sections in its
// frame; this thread turns them into the model every algorithm draws
// (oit_explode_offsets, then oit_model_derive when oit_model_derive_needed:
// the parts moved, the caps appended), kept while the factor, and with caps
// the sections, stay the same, and uploads it like a new model. Previews and
// full frames draw the same model, so an explode slider or a section drag
// previews with the stand-in like any other setting and the GUI thread never
// derives. FrameResult::drawn_model hands it back for the pick and the
// plane's outline; FrameResult::open_cut names the open parts a section cuts.
#pragma once

#include <QImage>
#include <QMetaType>
#include <QObject>
#include <QString>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "oit.h"

struct FrameJob {
    enum class Kind { View, Export };
    Kind kind = Kind::View;
    uint64_t id = 0; // set by submit()
    std::shared_ptr<const oit_model> model;
    std::string algorithm;
    oit_algorithm_config config{};  // shader_dir is the worker's
    oit_frame_settings frame{};     // at the size to render; progress is the worker's
    std::vector<float> component_alpha; // frame.local.component_alpha points here
    std::vector<float> component_highlight; // frame.local.component_highlight points here (empty: none)
    int coarse_scale = 1;           // 1: full resolution; N: 1/N of the view per side
    bool refinement = false;        // the full frame of the coarse one before it: waits for it
    std::string algorithm_b;        // split view: the second algorithm, same frame (empty: none)
    bool error_view = false;        // full frames: the error map against the reference too
    double explode = 0.0;           // --explode: the model as drawn (the rule above)
    std::vector<uint8_t> section_parts; // frame.local.section_parts points here (empty: every part)
};

// One side's image against the CPU reference's image of the same frame.
struct ErrorResult {
    bool present = false;     // figures and map were computed
    oit_image_error figures{};
    QImage map;               // oit_image_error_map without legend, RGBA8888
    bool reference_cached = false; // the reference image came from the cache
    double reference_ms = 0.0;     // rendering the reference (0 when cached)
    double error_ms = 0.0;         // the figures and the map
    QString problem;               // why there is no error map (the reference failed)
};

// The second algorithm of a split view.
struct SideResult {
    std::string algorithm;
    oit_status status = OIT_OK;
    QString error;
    QImage image;
    oit_stats stats{};
    double render_ms = 0.0;
    std::vector<QString> left_out;
    ErrorResult error_map;
};

struct FrameResult {
    uint64_t id = 0;
    FrameJob::Kind kind = FrameJob::Kind::View;
    int coarse_scale = 1;
    int samples = 1;         // the frame's anti-aliasing samples (job.frame.samples)
    std::string algorithm;
    oit_status status = OIT_OK;
    QString error;           // status != OIT_OK: the core's message
    QImage image;            // RGBA8888, top row first
    oit_stats stats{};
    double wall_ms = 0.0;    // from the job's start to its end, upload included
    bool uploaded = false;   // this job uploaded a new model first
    // what the algorithm could not express and was left out (the core's words)
    std::vector<QString> left_out;
    oit_modulation modulation{};        // the settings actually rendered
    oit_focus_shape focus_shape = OIT_FOCUS_NONE;
    double render_ms = 0.0;  // the algorithm's frame alone (wall_ms adds upload, side B, reference)
    ErrorResult error_map;   // the error view (job.error_view, full frames)
    bool split = false;      // job.algorithm_b was set: b is the second side
    SideResult b;
    // the model the frame drew: job.model, or it exploded and capped (null when none was made)
    std::shared_ptr<const oit_model> drawn_model;
    std::vector<uint32_t> open_cut; // parts a section cuts that are open (no cap), with caps on
    double derive_ms = 0.0;         // making the drawn model (0: kept from before)
};
using FrameResultPointer = std::shared_ptr<const FrameResult>;
Q_DECLARE_METATYPE(FrameResultPointer)

// Everything that decides what a frame shows besides the algorithm and its
// configuration, as bytes: the size, the camera's matrices, every setting
// and the per-part opacity. Equal keys: the same view.
std::string frame_key(const oit_frame_settings &frame);
// What makes two configurations render differently, as text (the shader folder aside).
std::string config_key(const oit_algorithm_config &config);

// Which algorithms render each option: feature key ("view:heatmap",
// "modulation:fields", "distance:skip", ...) -> their names, from the core's
// capability tables (oit_capabilities); no frame is rendered to find out.
using CapabilityTable = std::map<QString, QStringList>;
CapabilityTable capability_table();

// The frame with what ops does not render left out (the view, the
// modulation, its distance), each refusal's one line in left_out.
void reduce_to_capabilities(const oit_algorithm_ops *ops, oit_frame_settings &frame, std::vector<QString> &left_out);

class RenderWorker : public QObject {
    Q_OBJECT
public:
    // The worker (and llvmpipe's threads it starts) runs this much nicer than the GUI.
    static constexpr int kNiceIncrement = 5;
    // Progress signals at most this often.
    static constexpr double kProgressIntervalMs = 40.0;
    // Algorithm instances kept (each holds buffers the size of its frames):
    // full and coarse of two split sides and the reference, and one spare.
    static constexpr size_t kAlgorithmCacheSize = 6;
    // Reference images kept: the last few frames' (a split view whose sides
    // left out different options needs two).
    static constexpr size_t kReferenceCacheSize = 4;

    // Returns once the context exists or failed (renderer(), context_error()):
    // the core folds what the driver prints during creation into its message
    // by borrowing stderr for that moment, so nothing else may print meanwhile.
    RenderWorker(oit_backend backend, const std::string &shader_dir, QObject *parent = nullptr);
    ~RenderWorker() override; // abandons any frame, releases GL, joins the thread

    // Queue a job; returns its id (increasing). Thread-safe.
    uint64_t submit(FrameJob job);
    // Abandon the running frame and every waiting one.
    void cancel();
    // A frame is running or waiting.
    bool busy() const;
    // GL_RENDERER, or empty with context_error() saying why there is no context.
    QString renderer() const { return renderer_; }
    QString context_error() const { return context_error_; }
    // The job running now (0: none).
    uint64_t running_id() const { return running_id_.load(); }

signals:
    void progress(quint64 id, const QString &stage, int stages_done, double elapsed_ms);
    void frame_done(FrameResultPointer result);

private:
    struct Running;
    void run();
    void render_job(FrameJob &job);
    // One algorithm's image of frame (reduced in place to what it rendered).
    oit_status render_side(const FrameJob &job, const std::string &name, oit_frame_settings &frame,
                           QImage &image, oit_stats &stats, std::vector<QString> &left_out, oit_error &err);
    // side's image against the reference's image of frame (rendered or cached).
    void compare_with_reference(const FrameJob &job, const oit_frame_settings &frame, const QImage &side,
                                ErrorResult &out, std::vector<QString> &left_out);
    bool keep_going(Running &running, const char *stage, int stages_done);
    static bool progress_callback(void *user, const char *stage, int stages_done);
    struct CachedAlgorithm;
    CachedAlgorithm *algorithm_for(const std::string &name, const FrameJob &job, const oit_algorithm_ops *ops,
                                   oit_error *err);
    void release_gl();
    // The model job draws (the rule above), made or kept; open_cut as FrameResult's.
    oit_status drawn_model(const FrameJob &job, const oit_local_modulation &local,
                           std::shared_ptr<const oit_model> &out, std::vector<uint32_t> &open_cut, double &ms,
                           oit_error &err);

    oit_backend backend_;
    std::string shader_dir_;
    std::thread thread_;

    mutable std::mutex mutex_;
    std::condition_variable wake_;
    bool stopping_ = false;
    std::unique_ptr<FrameJob> pending_view_;
    std::deque<FrameJob> pending_exports_;
    uint64_t next_id_ = 1;
    uint64_t cancel_up_to_ = 0; // jobs with ids <= this are abandoned
    std::atomic<uint64_t> running_id_{0};
    bool running_ = false;
    bool context_attempted_ = false;
    QString renderer_, context_error_;

    // worker thread only
    oit_gl_context *context_ = nullptr;
    std::shared_ptr<const oit_model> uploaded_model_;
    oit_scene gpu_scene_{}, cpu_scene_{};
    bool scene_uploaded_ = false;
    struct CachedAlgorithm {
        std::string key;
        const oit_algorithm_ops *ops = nullptr;
        oit_algorithm *algorithm = nullptr;
        uint64_t last_used = 0;
        int width = 0, height = 0; // the size it was last resized to
    };
    std::vector<CachedAlgorithm> cache_;
    uint64_t use_counter_ = 0;
    // the reference's images by frame (camera, size, settings): switching the
    // algorithm, or the split view's second side, does not render it again
    struct CachedReference {
        std::string key;
        QImage image;
    };
    std::deque<CachedReference> references_;
    Running *running_job_ = nullptr; // the job render_job is working on
    // the model as drawn, kept while its key (factor, sections with caps) stays
    std::shared_ptr<const oit_model> derived_base_, derived_;
    std::string derived_key_;
    std::vector<uint32_t> derived_open_cut_;
    std::shared_ptr<const oit_model> offsets_model_; // the explode offsets' model and factor
    double offsets_factor_ = -1.0;
    std::vector<float> offsets_;
};
