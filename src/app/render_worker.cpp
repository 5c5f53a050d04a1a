// render_worker.cpp: see render_worker.h.
#include <GL/glew.h>

#include "render_worker.h"

#include <chrono>
#include <cerrno>
#include <sys/resource.h>
#include <unistd.h>
#include <cstring>
#include <type_traits>

namespace {

double now_ms()
{
    using namespace std::chrono;
    return duration<double, std::milli>(steady_clock::now().time_since_epoch()).count();
}

// What makes an algorithm instance reusable: its name, its configuration and
// whether it serves coarse or full frames (two sizes that would otherwise
// reallocate every buffer on each switch).
std::string algorithm_key(const std::string &name, const FrameJob &job)
{
    return name + "/" + config_key(job.config) + (job.coarse_scale > 1 ? "coarse" : "full");
}

// The GL state of a fresh context, which is what `oit render` starts from:
// the algorithms set what they change, but not always what they merely rely
// on, and this context has served other algorithms before.
void reset_gl_state()
{
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glStencilMask(0xffffffffu);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ZERO);
    glDepthFunc(GL_LESS);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, 0);
    glUseProgram(0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
}

// Everything that decides the reference's image of a frame, as bytes: the
// size, the camera's matrices, every setting and the configuration.
class KeyWriter {
public:
    template <class T>
    KeyWriter &operator<<(const T &value)
    {
        static_assert(std::is_arithmetic<T>::value || std::is_enum<T>::value, "scalars only (no padding)");
        bytes_.append(reinterpret_cast<const char *>(&value), sizeof value);
        return *this;
    }
    template <class T, size_t N>
    KeyWriter &operator<<(const T (&values)[N])
    {
        for (const T &value : values)
            *this << value;
        return *this;
    }
    std::string str() const { return bytes_; }

private:
    std::string bytes_;
};

} // namespace

std::string config_key(const oit_algorithm_config &c)
{
    return std::to_string(int(c.ll_sort)) + "/" + std::to_string(c.max_memory_bytes) + "/" +
           std::to_string(c.max_layers) + "/" + std::to_string(c.initial_fragment_capacity) + "/" +
           std::to_string(c.layers) + "/" + std::to_string(int(c.moments)) + "/" + std::to_string(c.debug) + "/" +
           std::to_string(c.neighbour_quality) + "/";
}

std::string frame_key(const oit_frame_settings &f)
{
    KeyWriter k;
    k << f.width << f.height << f.modelview << f.projection << f.alpha << f.shading << f.background;
    k << f.samples; // anti-aliasing: a different image
    const oit_modulation &m = f.modulation;
    k << m.view << m.view_parameter << m.mode << m.neighbours << m.curvature_neighbours << m.curvature_effect
      << m.focus_region << m.distance << m.distance_skip << m.fields << m.diffusion_iterations
      << m.blur_iterations << m.lambda_alpha << m.lambda_beta << m.lambda_gamma << m.has_halo_colour << m.halo_colour
      << m.last_layer_opaque << m.epsilon_max;
    const oit_local_modulation &l = f.local;
    k << l.component_count;
    for (uint32_t i = 0; l.component_alpha && i < l.component_count; ++i)
        k << l.component_alpha[i];
    k << l.focus_shape << l.focus << l.contrast << l.focus_default_region;
    k << l.component_highlight_count;
    for (uint32_t i = 0; l.component_highlight && i < l.component_highlight_count; ++i)
        k << l.component_highlight[i];
    k << l.has_highlight_colour << l.highlight_colour << l.highlight_strength;
    k << l.section_count << l.no_caps;
    for (uint32_t i = 0; i < l.section_count && i < OIT_SECTION_PLANES_MAX; ++i)
        k << l.sections[i];
    k << l.section_parts_count;
    for (uint32_t i = 0; l.section_parts && i < l.section_parts_count; ++i)
        k << l.section_parts[i];
    return k.str();
}

namespace {

std::string reference_key(const oit_algorithm_config &c, const oit_frame_settings &f)
{
    KeyWriter k;
    k << c.ll_sort << c.max_memory_bytes << c.max_layers << c.initial_fragment_capacity
      << c.neighbour_quality << c.layers << int(c.moments);
    return k.str() + frame_key(f);
}

// A QImage (RGBA8888: rows are packed) seen as the core's image, without a copy.
oit_image core_image(const QImage &image)
{
    oit_image out{};
    out.width = image.width();
    out.height = image.height();
    out.rgba = const_cast<uint8_t *>(image.constBits());
    return out;
}

} // namespace

CapabilityTable capability_table()
{
    CapabilityTable table;
    size_t count;
    const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
    for (size_t i = 0; i < count; ++i) {
        const oit_capabilities *can = list[i]->capabilities;
        const QString name = QString::fromUtf8(list[i]->name);
        for (int v = OIT_VIEW_COLOUR + 1; v < OIT_VIEW_COUNT; ++v)
            if (!can->views[v])
                table[QString("view:") + oit_setting_word(OIT_SETTING_VIEW, v)] << name;
        for (int m = OIT_MODULATE_NONE + 1; m < OIT_MODULATION_COUNT; ++m)
            if (!can->modulations[m])
                table[QString("modulation:") + oit_setting_word(OIT_SETTING_MODULATION, m)] << name;
        // a distance is rendered where a modulation that measures it is
        bool measures = !can->modulations[OIT_MODULATE_DISTANCE] || !can->modulations[OIT_MODULATE_DIST_CURV];
        for (int d = OIT_DISTANCE_ADJACENT + 1; measures && d < OIT_DISTANCE_COUNT; ++d)
            if (!can->distances[d])
                table[QString("distance:") + oit_setting_word(OIT_SETTING_DISTANCE, d)] << name;
    }
    return table;
}

void reduce_to_capabilities(const oit_algorithm_ops *ops, oit_frame_settings &frame, std::vector<QString> &left_out)
{
    oit_error err{};
    oit_modulation &m = frame.modulation;
    const oit_capabilities *can = ops->capabilities;
    while (oit_frame_check(ops, &frame, &err) == OIT_E_INPUT) {
        left_out.push_back(QString::fromUtf8(err.message));
        // leave out what the check refused: it looks at the modulation, its distance, the view
        if (unsigned(m.mode) >= OIT_MODULATION_COUNT || can->modulations[m.mode])
            m.mode = OIT_MODULATE_NONE;
        else if ((m.mode == OIT_MODULATE_DISTANCE || m.mode == OIT_MODULATE_DIST_CURV) &&
                 (unsigned(m.distance) >= OIT_DISTANCE_COUNT || can->distances[m.distance]))
            m.distance = OIT_DISTANCE_ADJACENT;
        else {
            m.view = OIT_VIEW_COLOUR;
            m.view_parameter = 0;
        }
    }
}

struct RenderWorker::Running {
    RenderWorker *worker;
    const FrameJob *job;
    double start_ms;
    double last_progress_ms;
    QString phase; // said before the stage: "", "blend: ", "reference: "
};

RenderWorker::RenderWorker(oit_backend backend, const std::string &shader_dir, QObject *parent)
    : QObject(parent), backend_(backend), shader_dir_(shader_dir)
{
    qRegisterMetaType<FrameResultPointer>("FrameResultPointer");
    thread_ = std::thread([this] { run(); });
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait(lock, [this] { return context_attempted_; });
}

RenderWorker::~RenderWorker()
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
        cancel_up_to_ = next_id_;
    }
    wake_.notify_all();
    thread_.join();
}

uint64_t RenderWorker::submit(FrameJob job)
{
    uint64_t id;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        id = job.id = next_id_++;
        if (job.kind == FrameJob::Kind::View)
            pending_view_.reset(new FrameJob(std::move(job)));
        else
            pending_exports_.push_back(std::move(job));
    }
    wake_.notify_all();
    return id;
}

void RenderWorker::cancel()
{
    std::lock_guard<std::mutex> lock(mutex_);
    cancel_up_to_ = next_id_ - 1;
    pending_view_.reset();
    pending_exports_.clear();
}

bool RenderWorker::busy() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    return running_ || pending_view_ || !pending_exports_.empty();
}

void RenderWorker::run()
{
    // A little less CPU weight than the GUI thread, so that on a machine whose
    // cores llvmpipe fills the window still answers at once. llvmpipe's own
    // rasterizer threads are created from this thread and inherit its nice
    // value. Raising one's own nice value needs no privilege; failing is harmless.
    errno = 0;
    int nice_now = getpriority(PRIO_PROCESS, id_t(gettid()));
    if (errno == 0)
        setpriority(PRIO_PROCESS, id_t(gettid()), std::min(19, nice_now + kNiceIncrement));
    oit_error err{};
    QString renderer, error;
    if (oit_gl_context_create(backend_, false, &context_, &err) == OIT_OK)
        renderer = QString::fromUtf8(oit_gl_renderer_string());
    else
        error = QString::fromUtf8(err.message);
    {
        std::lock_guard<std::mutex> lock(mutex_);
        renderer_ = renderer;
        context_error_ = error;
        context_attempted_ = true;
    }
    wake_.notify_all();

    for (;;) {
        FrameJob job;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [this] {
                return stopping_ || pending_view_ || !pending_exports_.empty();
            });
            if (stopping_)
                break;
            // exports first: the user asked for them explicitly and waits on them
            if (!pending_exports_.empty()) {
                job = std::move(pending_exports_.front());
                pending_exports_.pop_front();
            } else {
                job = std::move(*pending_view_);
                pending_view_.reset();
            }
            running_ = true;
            running_id_ = job.id;
        }
        render_job(job);
        std::lock_guard<std::mutex> lock(mutex_);
        running_ = false;
        running_id_ = 0;
    }
    release_gl();
    if (context_)
        oit_gl_context_destroy(context_);
    context_ = nullptr;
}

bool RenderWorker::progress_callback(void *user, const char *stage, int stages_done)
{
    auto *running = static_cast<Running *>(user);
    return running->worker->keep_going(*running, stage, stages_done);
}

bool RenderWorker::keep_going(Running &running, const char *stage, int stages_done)
{
    double now = now_ms(), elapsed = now - running.start_ms;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (stopping_ || running.job->id <= cancel_up_to_)
            return false;
        if (running.job->kind == FrameJob::Kind::View && pending_view_) {
            // a coarse frame gives way to a full frame the user asked for,
            // never to the next coarse frame of a drag nor to its refinement
            bool coarse = running.job->coarse_scale > 1;
            bool waits_for_it = pending_view_->coarse_scale > 1 || pending_view_->refinement;
            if (!coarse || !waits_for_it)
                return false; // superseded
        }
    }
    if (now - running.last_progress_ms >= kProgressIntervalMs) {
        running.last_progress_ms = now;
        emit progress(running.job->id, running.phase + QString::fromUtf8(stage), stages_done, elapsed);
    }
    return true;
}

RenderWorker::CachedAlgorithm *RenderWorker::algorithm_for(const std::string &name, const FrameJob &job,
                                                           const oit_algorithm_ops *ops, oit_error *err)
{
    std::string key = algorithm_key(name, job);
    for (CachedAlgorithm &cached : cache_)
        if (cached.key == key) {
            cached.last_used = ++use_counter_;
            return &cached;
        }
    // at most a few instances: each holds buffers the size of its frames
    while (cache_.size() >= kAlgorithmCacheSize) {
        auto oldest = cache_.begin();
        for (auto it = cache_.begin(); it != cache_.end(); ++it)
            if (it->last_used < oldest->last_used)
                oldest = it;
        oldest->ops->destroy(oldest->algorithm);
        cache_.erase(oldest);
    }
    oit_algorithm_config config = job.config;
    config.shader_dir = shader_dir_.c_str();
    oit_algorithm *algorithm = nullptr;
    if (oit_algorithm_create(ops, &config, &algorithm, err) != OIT_OK)
        return nullptr;
    cache_.push_back({key, ops, algorithm, ++use_counter_, 0, 0});
    return &cache_.back();
}

void RenderWorker::release_gl()
{
    for (CachedAlgorithm &cached : cache_)
        cached.ops->destroy(cached.algorithm);
    cache_.clear();
    references_.clear();
    if (scene_uploaded_)
        oit_scene_release(&gpu_scene_);
    scene_uploaded_ = false;
    uploaded_model_.reset();
}

namespace {

// Open parts (not closed) that a section cuts: vertices on both sides of a
// plane, in the parts the sections cut. For a model oit_model_derive did not
// run on (it says them itself when it does).
std::vector<uint32_t> open_parts_cut(const oit_model &model, const oit_local_modulation &local)
{
    std::vector<uint32_t> out;
    if (local.section_count == 0 || local.no_caps)
        return out;
    for (uint32_t c = 0; c < model.component_count; ++c) {
        const oit_component &part = model.components[c];
        if (part.closed || part.triangle_count == 0 ||
            (local.section_parts && (c >= local.section_parts_count || !local.section_parts[c])))
            continue;
        bool cut = false;
        for (uint32_t i = 0; i < local.section_count && i < OIT_SECTION_PLANES_MAX && !cut; ++i) {
            const double *s = local.sections[i];
            bool kept = false, removed = false;
            for (uint64_t t = part.first_triangle; t < uint64_t(part.first_triangle) + part.triangle_count && !cut;
                 ++t)
                for (int k = 0; k < 3; ++k) {
                    const float *p = model.positions + size_t(model.indices[t * 3 + size_t(k)]) * 3;
                    double side = s[0] * (model.origin[0] + p[0]) + s[1] * (model.origin[1] + p[1]) +
                                  s[2] * (model.origin[2] + p[2]) - s[3];
                    (side > 0.0 ? removed : kept) = true;
                }
            cut = kept && removed;
        }
        if (cut)
            out.push_back(c);
    }
    return out;
}

} // namespace

oit_status RenderWorker::drawn_model(const FrameJob &job, const oit_local_modulation &local,
                                     std::shared_ptr<const oit_model> &out, std::vector<uint32_t> &open_cut,
                                     double &ms, oit_error &err)
{
    const oit_model &base = *job.model;
    double start = now_ms();
    ms = 0.0;
    if (job.model != offsets_model_ || job.explode != offsets_factor_) {
        offsets_.assign(size_t(base.component_count) * 3, 0.0f);
        offsets_model_.reset();
        if (job.explode != 0.0 && oit_explode_offsets(&base, job.explode, offsets_.data(), &err) != OIT_OK)
            return OIT_E_INPUT;
        offsets_model_ = job.model;
        offsets_factor_ = job.explode;
    }
    const float *offsets = job.explode != 0.0 ? offsets_.data() : nullptr;
    const uint32_t offset_count = offsets ? base.component_count : 0;
    // what the drawn model depends on: the factor, and the sections when they make caps
    KeyWriter k;
    k << job.explode;
    if (local.section_count > 0 && !local.no_caps) {
        for (uint32_t i = 0; i < local.section_count && i < OIT_SECTION_PLANES_MAX; ++i)
            k << local.sections[i];
        k << local.section_parts_count;
        for (uint32_t i = 0; local.section_parts && i < local.section_parts_count; ++i)
            k << local.section_parts[i];
    }
    std::string key = k.str();
    if (derived_base_ == job.model && derived_key_ == key && derived_) {
        out = derived_;
        open_cut = derived_open_cut_;
        return OIT_OK;
    }
    derived_.reset(); // the old one goes before a new one is made (memory)
    derived_base_.reset();
    if (!oit_model_derive_needed(&base, offsets, offset_count, &local)) {
        out = job.model;
        open_cut = open_parts_cut(base, local);
    } else {
        std::unique_ptr<oit_model> made(new oit_model());
        std::vector<uint8_t> cut(base.component_count, 0);
        if (oit_model_derive(&base, offsets, offset_count, &local, made.get(), cut.data(), &err) != OIT_OK)
            return OIT_E_INPUT;
        out = std::shared_ptr<const oit_model>(made.release(), [](const oit_model *m) {
            oit_model_free(const_cast<oit_model *>(m));
            delete m;
        });
        open_cut.clear();
        for (uint32_t c = 0; c < base.component_count; ++c)
            if (cut[c])
                open_cut.push_back(c);
    }
    derived_base_ = job.model;
    derived_key_ = key;
    derived_ = out;
    derived_open_cut_ = open_cut;
    ms = now_ms() - start;
    return OIT_OK;
}

void RenderWorker::render_job(FrameJob &job)
{
    auto result = std::make_shared<FrameResult>();
    result->id = job.id;
    result->kind = job.kind;
    result->coarse_scale = job.coarse_scale;
    result->samples = job.frame.samples < 1 ? 1 : job.frame.samples;
    result->algorithm = job.algorithm;
    oit_stats_reset(&result->stats);
    Running running{this, &job, now_ms(), 0.0, QString()};
    running_job_ = &running;
    auto finish = [&](oit_status status, const QString &error) {
        result->status = status;
        result->error = error;
        result->wall_ms = now_ms() - running.start_ms;
        running_job_ = nullptr;
        emit frame_done(result);
    };
    if (!context_)
        return finish(OIT_E_RUNTIME, "no OpenGL context: " + context_error_);
    if (!job.model)
        return finish(OIT_E_INPUT, "no model is loaded");
    if (!keep_going(running, "start", 0))
        return finish(OIT_CANCELLED, "the frame was cancelled before it started");

    oit_error err{};
    oit_frame_settings frame = job.frame;
    frame.local.component_alpha = job.component_alpha.empty() ? nullptr : job.component_alpha.data();
    frame.local.component_count = uint32_t(job.component_alpha.size());
    frame.local.component_highlight = job.component_highlight.empty() ? nullptr : job.component_highlight.data();
    frame.local.component_highlight_count = uint32_t(job.component_highlight.size());
    frame.local.section_parts = job.section_parts.empty() ? nullptr : job.section_parts.data();
    frame.local.section_parts_count = uint32_t(job.section_parts.size());

    // the model as drawn: exploded, with caps (kept while they stay the same)
    std::shared_ptr<const oit_model> drawn;
    if (drawn_model(job, frame.local, drawn, result->open_cut, result->derive_ms, err) != OIT_OK)
        return finish(OIT_E_INPUT, QString::fromUtf8(err.message));
    result->drawn_model = drawn;
    if (drawn != uploaded_model_) {
        // algorithms may keep buffers sized for the last scene
        release_gl();
        emit progress(job.id, "upload", 0, 0.0);
        if (oit_scene_upload(&gpu_scene_, drawn.get(), &err) != OIT_OK)
            return finish(OIT_E_RUNTIME, QString("cannot upload the model: ") + err.message);
        scene_uploaded_ = true;
        oit_scene_cpu(&cpu_scene_, drawn.get());
        uploaded_model_ = drawn;
        result->uploaded = true;
    }

    frame.progress.report = &RenderWorker::progress_callback;
    frame.progress.user = &running;
    const oit_frame_settings requested = frame;

    double side_start = now_ms();
    oit_status status =
        render_side(job, job.algorithm, frame, result->image, result->stats, result->left_out, err);
    result->render_ms = now_ms() - side_start;
    result->modulation = frame.modulation;
    result->focus_shape = frame.local.focus_shape;
    if (status != OIT_OK) {
        result->left_out.clear();
        return finish(status, QString::fromUtf8(err.message));
    }
    bool compare = job.kind == FrameJob::Kind::View && job.error_view && job.coarse_scale == 1;

    // split view: the second algorithm, the same frame as requested
    oit_frame_settings frame_b = requested;
    if (job.kind == FrameJob::Kind::View && !job.algorithm_b.empty()) {
        SideResult &b = result->b;
        result->split = true;
        b.algorithm = job.algorithm_b;
        oit_stats_reset(&b.stats);
        running.phase = QString::fromStdString(job.algorithm_b) + ": ";
        oit_error err_b{};
        side_start = now_ms();
        b.status = render_side(job, job.algorithm_b, frame_b, b.image, b.stats, b.left_out, err_b);
        b.render_ms = now_ms() - side_start;
        if (b.status == OIT_CANCELLED)
            return finish(OIT_CANCELLED, QString::fromUtf8(err_b.message));
        if (b.status != OIT_OK) {
            b.error = QString::fromUtf8(err_b.message);
            b.left_out.clear();
        }
    }

    // error view: each side against the reference's image of the frame it rendered
    if (compare) {
        running.phase.clear();
        compare_with_reference(job, frame, result->image, result->error_map, result->left_out);
        if (result->split && result->b.status == OIT_OK)
            compare_with_reference(job, frame_b, result->b.image, result->b.error_map, result->b.left_out);
        if (!keep_going(running, "error map", 0))
            return finish(OIT_CANCELLED, "the frame was superseded");
    }
    finish(OIT_OK, QString());
}

oit_status RenderWorker::render_side(const FrameJob &job, const std::string &name, oit_frame_settings &frame,
                                     QImage &image, oit_stats &stats, std::vector<QString> &left_out,
                                     oit_error &err)
{
    const oit_algorithm_ops *ops = oit_algorithm_find(name.c_str());
    if (!ops)
        return oit_fail(&err, OIT_E_INPUT, "unknown algorithm '%s'", name.c_str());
    bool fresh = job.kind == FrameJob::Kind::Export; // an export starts as `oit render` does
    oit_algorithm *algorithm = nullptr;
    bool needs_resize = true;
    if (fresh) {
        oit_algorithm_config config = job.config;
        config.shader_dir = shader_dir_.c_str();
        if (oit_algorithm_create(ops, &config, &algorithm, &err) != OIT_OK)
            algorithm = nullptr;
    } else if (CachedAlgorithm *cached = algorithm_for(name, job, ops, &err)) {
        algorithm = cached->algorithm;
        needs_resize = cached->width != frame.width || cached->height != frame.height;
        cached->width = frame.width;
        cached->height = frame.height;
    }
    if (!algorithm)
        return err.message[0] ? OIT_E_RUNTIME
                              : oit_fail(&err, OIT_E_RUNTIME, "%s: cannot be created", name.c_str());
    const oit_scene *scene = ops->uses_gl ? &gpu_scene_ : &cpu_scene_;

    // the options this algorithm does not render are left out, and said (its capabilities)
    reduce_to_capabilities(ops, frame, left_out);
    // an algorithm that reads the samples as its own per-pixel count (stochastic,
    // OIT_OPTION_SAMPLES): the view's 1 (no anti-aliasing) takes its default
    if (oit_algorithm_reads(ops, OIT_OPTION_SAMPLES) && frame.samples <= 1)
        frame.samples = 0;
    oit_status status = needs_resize ? oit_algorithm_resize(ops, algorithm, frame.width, frame.height, &err) : OIT_OK;
    if (status == OIT_OK) {
        reset_gl_state();
        status = oit_algorithm_render(ops, algorithm, scene, &frame, &err);
    }
    // its samples sit at the pixel centre: the frame as rendered, which the
    // error view's reference renders too, has no anti-aliasing
    if (oit_algorithm_reads(ops, OIT_OPTION_SAMPLES))
        frame.samples = 0;
    if (status == OIT_OK) {
        oit_image out{};
        status = ops->read_image(algorithm, &out, &err);
        if (status == OIT_OK) {
            image = QImage(out.rgba, out.width, out.height, QImage::Format_RGBA8888).copy();
            oit_image_free(&out);
            ops->stats(algorithm, &stats);
        }
    }
    if (fresh) {
        ops->destroy(algorithm);
    } else if (status != OIT_OK && status != OIT_CANCELLED && status != OIT_E_INPUT) {
        // a failed frame (an exhausted memory budget...) leaves the instance unusable
        for (auto it = cache_.begin(); it != cache_.end(); ++it)
            if (it->algorithm == algorithm) {
                it->ops->destroy(it->algorithm);
                cache_.erase(it);
                break;
            }
    }
    // the reference's own frames serve the error view too
    if (status == OIT_OK && !fresh && job.coarse_scale == 1 && ops == &oit_algorithm_reference) {
        references_.push_front({reference_key(job.config, frame), image});
        while (references_.size() > kReferenceCacheSize)
            references_.pop_back();
    }
    return status;
}

void RenderWorker::compare_with_reference(const FrameJob &job, const oit_frame_settings &frame,
                                          const QImage &side, ErrorResult &out, std::vector<QString> &left_out)
{
    std::string key = reference_key(job.config, frame);
    QImage reference;
    for (auto it = references_.begin(); it != references_.end(); ++it)
        if (it->key == key) {
            reference = it->image;
            out.reference_cached = true;
            CachedReference used = *it; // the most recent first
            references_.erase(it);
            references_.push_front(std::move(used));
            break;
        }
    if (reference.isNull()) {
        QString phase = running_job_ ? running_job_->phase : QString();
        if (running_job_) {
            running_job_->phase = "reference: ";
            // said at once (not held back by kProgressIntervalMs): the slow part starts
            emit progress(job.id, "reference: start", 0, now_ms() - running_job_->start_ms);
        }
        oit_frame_settings reference_frame = frame;
        oit_stats stats;
        oit_stats_reset(&stats);
        std::vector<QString> reference_left_out;
        oit_error err{};
        double start = now_ms();
        // cached by render_side under the key of the frame it rendered, which
        // is this one unless the reference left an option out
        oit_status status = render_side(job, oit_algorithm_reference.name, reference_frame, reference, stats,
                                        reference_left_out, err);
        out.reference_ms = now_ms() - start;
        if (running_job_)
            running_job_->phase = phase;
        if (status != OIT_OK) {
            out.problem = status == OIT_CANCELLED ? QString("the reference was superseded")
                                                  : "the reference could not render the frame: " +
                                                        QString::fromUtf8(err.message);
            return;
        }
        for (const QString &message : reference_left_out)
            left_out.push_back("the reference left out (the error map compares different settings): " +
                               message);
        if (references_.empty() || references_.front().key != key) {
            references_.push_front({key, reference});
            while (references_.size() > kReferenceCacheSize)
                references_.pop_back();
        }
    }
    double start = now_ms();
    oit_image image = core_image(side), ref = core_image(reference);
    oit_image map{};
    oit_error err{};
    if (oit_image_error_compute(&image, &ref, &out.figures, &err) != OIT_OK ||
        oit_image_error_map(&image, &ref, false, &map, &err) != OIT_OK) {
        out.problem = QString::fromUtf8(err.message);
        return;
    }
    out.map = QImage(map.rgba, map.width, map.height, QImage::Format_RGBA8888).copy();
    oit_image_free(&map);
    out.error_ms = now_ms() - start;
    out.present = true;
}
