// render_view.cpp: see render_view.h.
#include "render_view.h"
#include "error_legend.h"
#include "heatmap_legend.h"
#include "section_overlay.h"
#include "measure_tool.h"
#include "split_view.h"

#include <QCoreApplication>
#include <QEventLoop>
#include <QKeyEvent>
#include <QLineF>
#include <QMouseEvent>
#include <QPainter>
#include <QTimer>
#include <QWheelEvent>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace {

// OIT_BACKEND picks the context as `oit --backend` does: egl (also unset or
// empty) or osmesa; any other value is refused (it used to mean EGL silently).
bool backend_from_environment(oit_backend &backend, std::string &error)
{
    QString value = qEnvironmentVariable("OIT_BACKEND");
    backend = value == "osmesa" ? OIT_BACKEND_OSMESA : OIT_BACKEND_EGL;
    if (value.isEmpty() || value == "egl" || value == "osmesa")
        return true;
    error = "OIT_BACKEND=" + value.left(40).toStdString() + ": must be egl or osmesa";
    return false;
}

QString seconds_text(double ms)
{
    return ms < 1000.0 ? QString("%1 ms").arg(ms, 0, 'f', 0) : QString("%1 s").arg(ms / 1000.0, 0, 'f', 1);
}

} // namespace

RenderView::RenderView(SettingsModel &settings_model, QWidget *parent) : QWidget(parent), settings_(settings_model)
{
    setFocusPolicy(Qt::StrongFocus);
    setMinimumSize(64, 64);
    setAttribute(Qt::WA_OpaquePaintEvent);
    setMouseTracking(true); // the cursor shows where the wipe line can be grabbed
    legend_ = new ErrorLegend(this);
    legend_->hide();
    heatmap_legend_ = new HeatmapLegend(this);
    heatmap_legend_->hide();
    oit_stats_reset(&last_stats_);
    walk_timer_ = new QTimer(this);
    walk_timer_->setInterval(33);
    connect(walk_timer_, &QTimer::timeout, this, &RenderView::walk_tick);
    rest_timer_ = new QTimer(this);
    rest_timer_->setSingleShot(true);
    rest_timer_->setInterval(kRestMs);
    connect(rest_timer_, &QTimer::timeout, this, [this] {
        if (interacting())
            rest_timer_->start(); // still dragging or walking: stay coarse
        else {
            submit(1, true);
            emit status_changed(frame_status());
        }
    });
    // while a frame runs: the overlay's clock, and the start-up budget
    progress_timer_ = new QTimer(this);
    progress_timer_->setInterval(100);
    connect(progress_timer_, &QTimer::timeout, this, [this] {
        if (!rendering()) {
            progress_timer_->stop();
            progress_text_.clear();
            update();
            return;
        }
        double elapsed = running_clock_.isValid() ? double(running_clock_.elapsed()) : 0.0;
        if (full_frame_budget_ms_ > 0.0 && latest_is_full_ && running_job_id_ == latest_id_ &&
            elapsed > full_frame_budget_ms_) {
            double budget = full_frame_budget_ms_;
            full_frame_budget_ms_ = 0.0;
            worker_->cancel();
            rest_timer_->stop();
            emit frame_cancelled(QString("the full frame took longer than %1 with the restored settings (%2); "
                                         "showing the coarse frame: Render (F5) renders it in full")
                                     .arg(seconds_text(budget), QString::fromStdString(settings().algorithm)));
        }
        if (elapsed > kProgressAfterMs)
            update();
    });

    char dir[4096];
    oit_error err{};
    std::string argv0 = QCoreApplication::applicationFilePath().toStdString();
    if (oit_find_shader_dir(argv0.c_str(), dir, sizeof dir, &err) != OIT_OK) {
        startup_error_ = err.message; // no worker: the window refuses to start (main.cpp)
        return;
    }
    shader_dir_ = dir;
    oit_backend backend;
    if (!backend_from_environment(backend, startup_error_))
        return; // no worker: the window refuses to start, as without shaders
    worker_.reset(new RenderWorker(backend, shader_dir_));
    gl_ready_ = worker_->context_error().isEmpty();
    renderer_ = worker_->renderer().toStdString();
    gl_error_ = worker_->context_error().toStdString();
    connect(worker_.get(), &RenderWorker::progress, this,
            [this](quint64 id, const QString &stage, int stages_done, double elapsed_ms) {
                if (id < latest_coarse_id_ && id != export_id_)
                    return; // a frame already superseded
                if (stage == "start") {
                    running_clock_.restart();
                    running_job_id_ = id;
                }
                QString what = id == export_id_ ? "export" : id == latest_coarse_id_ ? "coarse frame" : "full frame";
                const std::string &algorithm = id == latest_coarse_id_ ? coarse_algorithm_ : settings().algorithm;
                progress_text_ = QString("%1 %2: %3, %4 stages, %5 — Esc cancels")
                                     .arg(QString::fromStdString(algorithm), what, stage)
                                     .arg(stages_done)
                                     .arg(seconds_text(elapsed_ms));
                emit frame_progress(stage, stages_done, elapsed_ms);
            });
    connect(worker_.get(), &RenderWorker::frame_done, this, &RenderView::frame_done);
}

RenderView::~RenderView()
{
    worker_.reset(); // abandons the frame and joins the thread before the model goes
}

void RenderView::set_model(std::shared_ptr<const oit_model> model)
{
    model_ = std::move(model);
    drawn_model_.reset(); // the last model's
    open_cut_.clear();
    highlight_.clear(); // the parts were the last model's
    last_full_ms_ = -1.0; // a new model: its cost is unknown
    full_ms_.clear();
    wboit_preview_ = false;
    requested_key_.clear(); // the keys do not name the model
    requested_view_key_.clear();
    coarse_scale_ = 2;
    request_frame(true);
}

void RenderView::reset_camera()
{
    if (!model_)
        return;
    QSize size = pixel_size();
    Camera &camera = settings_.camera();
    camera.set_mode(Camera::Mode::Orbit);
    camera.orthographic = false;
    camera.frame(*model_, size.width(), size.height());
    camera_moved();
}

QSize RenderView::pixel_size() const
{
    qreal ratio = devicePixelRatioF();
    return QSize(std::max(1, int(width() * ratio)), std::max(1, int(height() * ratio)));
}

QSize RenderView::side_pixel_size() const
{
    return split_view::side_size(settings().split, pixel_size());
}

QSize RenderView::render_size() const
{
    return shown_.isNull() ? side_pixel_size() : shown_.size();
}

QImage RenderView::shown_a() const
{
    const FrameResult *r = shown_result_.get();
    if (r && settings().error_view && r->error_map.present)
        return r->error_map.map;
    return shown_;
}

QImage RenderView::shown_b() const
{
    const FrameResult *r = shown_result_.get();
    if (!r || !r->split || settings().split == SplitMode::Off)
        return QImage();
    if (settings().error_view && r->b.error_map.present)
        return r->b.error_map.map;
    return r->b.image;
}

QImage RenderView::displayed() const
{
    QImage shown = shown_a();
    const oit_overlay_options aids = view_aids(settings());
    if ((!aids.axes && !aids.scale_bar) || !model_ || shown.isNull())
        return shown;
    // the GUI thread draws them: a few corner masks, no render to wait for
    const QSize size = pixel_size();
    std::vector<float> storage;
    const oit_frame_settings frame = current_frame(storage);
    std::vector<double> key(frame.modelview, frame.modelview + 16);
    key.insert(key.end(), frame.projection, frame.projection + 16);
    key.insert(key.end(), {double(size.width()), double(size.height()), double(aids.axes), double(aids.axes_corner),
                           double(aids.scale_bar), double(reinterpret_cast<uintptr_t>(model_.get()))});
    if (!aids_image_.isNull() && aids_source_ == shown.cacheKey() && aids_key_ == key)
        return aids_image_;
    QImage image = (shown.size() == size ? shown : shown.scaled(size, Qt::IgnoreAspectRatio, Qt::SmoothTransformation))
                       .convertToFormat(QImage::Format_RGBA8888);
    image.detach();
    oit_image target{image.width(), image.height(), image.bits()};
    if (image.bytesPerLine() != image.width() * 4)
        return shown; // never: RGBA8888 rows are width * 4 bytes
    oit_error err{};
    if (oit_overlay_draw(&target, &aids, frame.modelview, frame.projection, model_.get(), nullptr, &err) != OIT_OK)
        return shown; // matrices the frame refuses too: the view says so already
    aids_image_ = image;
    aids_source_ = shown.cacheKey();
    aids_key_ = std::move(key);
    return image;
}

void RenderView::update_overlays()
{
    const FrameResult *r = shown_result_.get();
    bool map = settings().error_view && r && (r->error_map.present || (r->split && r->b.error_map.present));
    legend_->set_bar_width(std::min(150, width() / 2 - 40)); // a small corner of a small view
    legend_->move(6, height() - legend_->height() - 6);
    legend_->setVisible(map);
    // the heatmap's scale is the shown frame's longest list (side A's, as rendered: not left out)
    bool heatmap = !map && r && r->status == OIT_OK && r->modulation.view == OIT_VIEW_HEATMAP && r->stats.max_list > 0;
    if (heatmap) {
        heatmap_legend_->set_longest(r->stats.max_list);
        heatmap_legend_->set_bar_width(std::min(150, width() / 2 - 40));
        heatmap_legend_->move(6, height() - heatmap_legend_->height() - 6);
    }
    heatmap_legend_->setVisible(heatmap);
    update();
}

bool RenderView::interacting() const
{
    return buttons_ != Qt::NoButton || !walk_keys_.isEmpty();
}

bool RenderView::rendering() const
{
    return worker_ && worker_->busy();
}

bool RenderView::settled() const
{
    return model_ && worker_ && !worker_->busy() && !rest_timer_->isActive() && latest_is_full_ &&
           last_result_ && last_result_->id == latest_id_;
}

oit_frame_settings RenderView::current_frame(std::vector<float> &storage) const
{
    QSize size = side_pixel_size();
    oit_frame_settings frame = make_frame(settings(), *model_, camera(), size.width(), size.height(), storage);
    if (!highlight_.empty()) {
        frame.local.component_highlight = highlight_.data();
        frame.local.component_highlight_count = uint32_t(highlight_.size());
    }
    return frame;
}

void RenderView::set_highlight(const std::vector<int> &parts)
{
    std::vector<float> weights;
    if (model_ && !parts.empty()) {
        weights.assign(model_->component_count, 0.0f);
        for (int part : parts)
            if (part >= 0 && uint32_t(part) < model_->component_count)
                weights[size_t(part)] = 1.0f;
    }
    if (weights == highlight_)
        return;
    highlight_ = std::move(weights);
    request_frame(false);
}

FrameJob RenderView::make_job(int width, int height, int coarse_scale) const
{
    FrameJob job;
    job.model = model_;
    job.algorithm = settings().algorithm;
    job.config = settings().config;
    job.frame = make_frame(settings(), *model_, camera(), width, height, job.component_alpha);
    job.frame.local.component_alpha = nullptr; // the worker points it at its copy
    job.component_highlight = highlight_;
    job.coarse_scale = coarse_scale;
    if (settings().split != SplitMode::Off)
        job.algorithm_b = settings().split_algorithm;
    job.error_view = settings().error_view;
    job.explode = settings().explode; // the model as drawn (render_worker.h)
    if (job.frame.local.section_parts)
        job.section_parts.assign(job.frame.local.section_parts,
                                 job.frame.local.section_parts + job.frame.local.section_parts_count);
    job.frame.local.section_parts = nullptr; // the worker points it at its copy
    return job;
}

std::string RenderView::preview_algorithm() const
{
    const std::string &choice = settings().preview_algorithm;
    if (choice == "same" || settings().split != SplitMode::Off)
        return settings().algorithm; // a split view compares its own two, coarse
    if (choice == "auto" || !oit_algorithm_find(choice.c_str()))
        return wboit_preview_ ? "wboit" : "ll";
    return choice;
}

void RenderView::request_frame(bool interactive)
{
    update_overlays(); // the error view or the split may have changed
    if (!model_ || !worker_) {
        update();
        return;
    }
    // the rules are render_worker.h's: what changed since the last request decides
    QSize size = side_pixel_size();
    FrameJob full = make_job(size.width(), size.height(), 1);
    full.frame.local.component_alpha = full.component_alpha.empty() ? nullptr : full.component_alpha.data();
    std::string view_key = frame_key(full.frame);
    view_key += "|explode " + std::to_string(full.explode); // the model as drawn changes the view
    std::string key = full.algorithm + "|" + full.algorithm_b + "|" + char('0' + full.error_view) + "|" +
                      config_key(full.config) + view_key;
    if (interactive && key == requested_key_) {
        update(); // nothing changed: its frames are shown or on their way
        return;
    }
    bool view_changed = view_key != requested_view_key_;
    requested_key_ = key;
    requested_view_key_ = view_key;
    auto known = full_ms_.find(settings().algorithm);
    bool slow = known == full_ms_.end() || known->second > slow_frame_ms_;
    if (interactive && progressive_ && slow && view_changed) {
        submit(coarse_scale_, false, preview_algorithm());
        rest_timer_->start();
    } else {
        rest_timer_->stop();
        submit(1);
    }
    emit status_changed(frame_status());
}

void RenderView::submit(int coarse_scale, bool refinement, const std::string &algorithm, int samples)
{
    QSize full = side_pixel_size();
    int width = std::max(1, full.width() / coarse_scale), height = std::max(1, full.height() / coarse_scale);
    if (!rendering())
        running_clock_.restart();
    FrameJob job = make_job(width, height, coarse_scale);
    if (!algorithm.empty())
        job.algorithm = algorithm;
    job.refinement = refinement;
    // anti-aliasing (render_worker.h): previews at 1 sample, Auto's first full frame too
    if (samples > 0)
        job.frame.samples = samples;
    else if (coarse_scale > 1 || settings().samples == 0)
        job.frame.samples = 1;
    std::string job_algorithm = job.algorithm;
    latest_id_ = worker_->submit(std::move(job));
    ++jobs_submitted_;
    latest_is_full_ = coarse_scale == 1;
    if (!latest_is_full_) {
        latest_coarse_id_ = latest_id_;
        coarse_algorithm_ = job_algorithm;
    }
    if (!progress_timer_->isActive())
        progress_timer_->start();
}

QString RenderView::frame_status() const
{
    const FrameResult *shown = shown_result_.get();
    QString chosen = QString::fromStdString(settings().algorithm);
    bool full_shown = shown && shown->coarse_scale == 1 && shown->algorithm == settings().algorithm;
    bool waiting = rest_timer_->isActive() || (rendering() && latest_id_ != shown_full_id_);
    if (!waiting || full_shown)
        return QString(); // the full frame of this algorithm is up: the stats say it
    QString what = rest_timer_->isActive() ? chosen + " refines when the input rests" : chosen + " refining…";
    if (!shown)
        return chosen + " rendering…";
    QString algorithm = QString::fromStdString(shown->algorithm);
    if (shown->coarse_scale > 1)
        return QString("%1, showing %2 %3 (1/%4 scale)")
            .arg(what, algorithm, shown->algorithm == settings().algorithm ? "coarse frame" : "preview")
            .arg(shown->coarse_scale);
    return QString("%1 rendering…, showing %2 (the previous algorithm)").arg(chosen, algorithm);
}

void RenderView::cancel_frame()
{
    if (!worker_)
        return;
    bool was_rendering = rendering() || rest_timer_->isActive();
    rest_timer_->stop();
    worker_->cancel();
    requested_key_.clear(); // the same request renders again
    if (was_rendering)
        emit frame_cancelled("cancelled: the view keeps the last frame; Render (F5) starts it again");
}

void RenderView::frame_done(FrameResultPointer result)
{
    if (result->kind == FrameJob::Kind::Export) {
        if (result->id == export_id_)
            export_result_ = result;
        // the export's progress ("compose, 4 stages") goes with it: cleared
        // now, not when the next view frame happens to arrive; a view frame
        // still running shows its own again with its next stage
        progress_text_.clear();
        update();
        emit frame_progress(QString(), 0, 0.0);
        return;
    }
    if (result->status == OIT_CANCELLED)
        return; // superseded, or cancelled (cancel_frame said so already)
    if (result->status != OIT_OK) {
        if (result->id == latest_id_) {
            last_result_ = result;
            shown_ = QImage();
            shown_result_.reset();
            update_overlays();
            emit render_failed(result->error);
        }
        return;
    }
    last_result_ = result;
    shown_ = result->image;
    shown_result_ = result;
    if (result->drawn_model)
        drawn_model_ = result->drawn_model;
    if (result->open_cut != open_cut_) {
        open_cut_ = result->open_cut;
        emit open_cut_changed(open_cut_);
    }
    update_overlays();
    QStringList left_out;
    for (const QString &message : result->left_out)
        left_out << message;
    if (result->split) { // side B's, said as its own
        QString b = QString::fromStdString(result->b.algorithm);
        if (result->b.status != OIT_OK)
            left_out << QString("split side B (%1) failed: %2").arg(b, result->b.error);
        for (const QString &message : result->b.left_out)
            left_out << QString("split side B (%1): %2").arg(b, message);
    }
    if (result->coarse_scale == 1) {
        last_image_ = result->image;
        last_stats_ = result->stats;
        last_full_ms_ = result->wall_ms;
        bool auto_samples = settings().samples == 0;
        if (!auto_samples || result->samples == 1) // Auto's still frame does not make frames "slow"
            full_ms_[result->algorithm] = result->wall_ms;
        shown_full_id_ = result->id;
        if (last_stats_.overflow_retries > 0)
            overflow_total_ += long(last_stats_.overflow_retries);
        if (fps_clock_.isValid() && continuous_) {
            double ms = double(fps_clock_.nsecsElapsed()) / 1e6;
            fps_ = ms > 0.0 ? 1000.0 / ms : 0.0;
        } else {
            fps_ = last_stats_.cpu_ms > 0.0 ? 1000.0 / last_stats_.cpu_ms : 0.0;
        }
        fps_clock_.start();
        full_frame_budget_ms_ = 0.0; // the budget guards the first full frame only
        update();
        emit options_left_out(left_out);
        emit frame_rendered();
        if (result->id != latest_id_)
            emit status_changed(frame_status()); // a newer frame is on its way: not the stats
        if (continuous_ && result->id == latest_id_)
            submit(1);
        else
            antialias_when_still();
    } else {
        // coarser when a preview is itself slow, finer when it is cheap (the
        // algorithms' time: an upload does not count); "auto" turns to wboit
        // when ll is too slow even at the coarsest scale
        double ms = result->render_ms + result->b.render_ms;
        if (ms > kPreviewBudgetMs && coarse_scale_ < kMaxCoarseScale)
            coarse_scale_ *= 2;
        else if (ms > kPreviewBudgetMs && result->algorithm == "ll" && settings().preview_algorithm == "auto")
            wboit_preview_ = true;
        else if (ms < kPreviewBudgetMs / 4.0 && coarse_scale_ > 2)
            coarse_scale_ /= 2;
        update();
        emit options_left_out(left_out);
        emit coarse_frame_rendered();
        emit status_changed(frame_status());
    }
}

void RenderView::antialias_when_still()
{
    // Auto's rule (render_worker.h): the latest full frame, at 1 sample, shown
    // while nothing moves and nothing newer waits, is rendered again at 4
    const FrameResult *r = last_result_.get();
    int samples = view_samples(settings());
    if (settings().samples != 0 || samples <= 1 || continuous_ || !worker_ || interacting() || rest_timer_->isActive() || !r ||
        r->status != OIT_OK || r->coarse_scale != 1 || r->samples != 1 || r->id != latest_id_ ||
        r->wall_ms > kAutoSamplesMaxMs)
        return;
    submit(1, false, std::string(), samples);
}

bool RenderView::render_offscreen(int width, int height, QImage &image, oit_frame_settings &frame, std::string &error,
                                  bool with_highlight, const double *modelview)
{
    if (!model_) {
        error = "no model is loaded";
        return false;
    }
    if (!worker_) {
        error = startup_error_.empty() ? "no OpenGL context: " + gl_error_ : startup_error_;
        return false;
    }
    if (export_id_) {
        error = "an export is already running";
        return false;
    }
    FrameJob job = make_job(width, height, 1);
    job.kind = FrameJob::Kind::Export; // side A's colour image, as `oit render`
    job.frame.samples = export_samples(settings()); // exports always anti-alias (render_worker.h)
    job.algorithm_b.clear();
    job.error_view = false;
    if (!with_highlight)
        job.component_highlight.clear();
    if (modelview)
        std::memcpy(job.frame.modelview, modelview, sizeof job.frame.modelview);
    frame = job.frame;
    export_result_.reset();
    QEventLoop loop;
    QMetaObject::Connection done = connect(worker_.get(), &RenderWorker::frame_done, &loop,
                                           [this, &loop](FrameResultPointer) {
                                               if (export_result_)
                                                   loop.quit();
                                           });
    export_id_ = worker_->submit(std::move(job));
    if (!progress_timer_->isActive())
        progress_timer_->start();
    // the view's own frame_done slot (connected first) stores the result
    loop.exec();
    disconnect(done);
    FrameResultPointer result = export_result_;
    export_result_.reset();
    export_id_ = 0;
    if (result->status != OIT_OK) {
        error = result->error.toStdString();
        return false;
    }
    image = result->image; // shared, not copied: 33 MB at 3840x2160
    frame.modulation = result->modulation;
    frame.local.focus_shape = result->focus_shape;
    return true;
}

void RenderView::set_continuous(bool on)
{
    continuous_ = on;
    fps_clock_.invalidate();
    request_frame(false);
}

void RenderView::set_progressive(bool on)
{
    progressive_ = on;
    request_frame(false);
}

// ------------------------------------------------------------------ painting

void RenderView::paintEvent(QPaintEvent *)
{
    QPainter painter(this);
    const FrameResult *r = shown_result_.get();
    if (settings().split != SplitMode::Off && r && r->split) {
        auto label = [this](const std::string &name, const oit_stats &stats, const ErrorResult &error) {
            QString text = QString("%1 %2 ms").arg(QString::fromStdString(name)).arg(stats.cpu_ms, 0, 'f', 1);
            if (settings().error_view && error.present)
                text += QString(", rmse %1").arg(error.figures.rmse, 0, 'f', 2);
            return text;
        };
        split_view::Side a{shown_a(), label(r->algorithm, r->stats, r->error_map)};
        split_view::Side b{shown_b(), r->b.status == OIT_OK
                                          ? label(r->b.algorithm, r->b.stats, r->b.error_map)
                                          : QString::fromStdString(r->b.algorithm) + " failed"};
        split_view::paint(painter, size(), devicePixelRatioF(), settings().split, settings().wipe, a, b);
    } else if (shown_.isNull()) {
        painter.fillRect(rect(), QColor(89, 89, 97));
    } else {
        QImage shown = displayed();
        if (shown.size() == pixel_size()) {
            shown.setDevicePixelRatio(devicePixelRatioF());
            painter.drawImage(QPoint(0, 0), shown);
        } else {
            // a coarse frame (or one from before a resize), scaled up
            painter.setRenderHint(QPainter::SmoothPixmapTransform);
            painter.drawImage(rect(), shown);
        }
    }
    paint_section(painter);
    paint_measure(painter);
    QString text;
    if (!startup_error_.empty())
        text = QString::fromStdString(startup_error_);
    else if (!gl_error_.empty() && !gl_ready_)
        text = "no OpenGL context: " + QString::fromStdString(gl_error_);
    else if (last_result_ && last_result_->status != OIT_OK && last_result_->id == latest_id_)
        text = "render failed: " + last_result_->error;
    else if (rendering() && running_clock_.isValid() && running_clock_.elapsed() > kProgressAfterMs &&
             !progress_text_.isEmpty())
        text = progress_text_;
    else if (settings().error_view && r && !r->error_map.problem.isEmpty())
        text = "error view: " + r->error_map.problem;
    if (!text.isEmpty()) {
        QFontMetrics metrics(font());
        QRect box = metrics.boundingRect(QRect(8, 0, width() - 16, height()), Qt::TextWordWrap, text);
        box.moveBottom(height() - 8);
        painter.fillRect(box.adjusted(-4, -3, 4, 3), QColor(0, 0, 0, 170));
        painter.setPen(Qt::white);
        painter.drawText(box, Qt::TextWordWrap, text);
    }
}

// The measurement (measure_tool.h) over the image with the current camera, so
// it follows the camera before the frame does; side by side, over each half.
void RenderView::set_measure(const MeasureTool *measure)
{
    measure_ = measure;
    update();
}

void RenderView::paint_measure(QPainter &painter) const
{
    if (!measure_ || measure_->empty() || !model_)
        return;
    std::vector<float> storage;
    const oit_frame_settings frame = current_frame(storage);
    const double ratio = devicePixelRatioF();
    measure_->paint(painter, frame, ratio, QPointF(0.0, 0.0));
    if (settings().split == SplitMode::SideBySide)
        measure_->paint(painter, frame, ratio, QPointF(frame.width / ratio, 0.0));
}

void RenderView::resizeEvent(QResizeEvent *event)
{
    QWidget::resizeEvent(event);
    request_frame(true); // and moves the legend
}

// ------------------------------------------------------------------ input

void RenderView::mousePressEvent(QMouseEvent *event)
{
    if (settings().split == SplitMode::Wipe && event->button() == Qt::LeftButton &&
        split_view::grabs_wipe_line(event->pos(), settings().wipe, size())) {
        dragging_wipe_ = true; // the line, not the camera
        setFocus();
        return;
    }
    last_mouse_ = press_position_ = event->pos();
    dragged_ = false;
    buttons_ = event->buttons();
    setFocus();
    QPointF handle;
    if (event->button() == Qt::LeftButton && section_handle(handle) &&
        QLineF(handle, QPointF(event->pos())).length() <= 10.0) {
        // the active section's handle: the drag moves the plane, one undo step
        dragging_section_ = true;
        section_press_ = event->pos();
        section_press_d_ = settings().sections[size_t(active_section_)].d;
        settings_.close_step();
    }
}

void RenderView::mouseMoveEvent(QMouseEvent *event)
{
    if (dragging_wipe_) {
        // the images are there already: only the boundary moves, nothing renders
        settings_.render_settings().wipe = split_view::wipe_at(event->pos().x(), width());
        update();
        emit wipe_moved(settings().wipe);
        return;
    }
    if (buttons_ == Qt::NoButton) {
        bool near = settings().split == SplitMode::Wipe &&
                    split_view::grabs_wipe_line(event->pos(), settings().wipe, size());
        if (near)
            setCursor(Qt::SplitHCursor);
        else
            unsetCursor();
    }
    if (!model_ || buttons_ == Qt::NoButton)
        return;
    if (dragging_section_) {
        double mv[16], proj[16];
        QSize size;
        std::vector<SectionPlane> &sections = settings_.render_settings().sections;
        if (active_section_ < 0 || size_t(active_section_) >= sections.size() || !view_matrices(mv, proj, size))
            return;
        SectionPlane &plane = sections[size_t(active_section_)];
        double box_min[3], box_max[3];
        section_overlay::model_box(*drawn_model(), box_min, box_max);
        glm::dvec3 centre = glm::dvec3(box_min[0] + box_max[0], box_min[1] + box_max[1], box_min[2] + box_max[2]) * 0.5;
        centre = section_overlay::nearest_on_plane(plane.normal, section_press_d_, centre);
        double scale = glm::length(glm::dvec3(box_max[0] - box_min[0], box_max[1] - box_min[1],
                                              box_max[2] - box_min[2])) * 0.25;
        qreal ratio = devicePixelRatioF();
        QPointF delta = QPointF(event->pos() - section_press_) * ratio;
        double low, high;
        section_overlay::offset_range(plane.normal, box_min, box_max, low, high);
        double d = section_overlay::dragged_offset(mv, proj, size.width(), size.height(), plane.normal,
                                                   section_press_d_, centre, scale, delta);
        plane.d = std::min(high, std::max(low, d));
        dragged_ = true;
        emit section_dragged();
        request_frame(true);
        return;
    }
    if (!dragged_ && (event->pos() - press_position_).manhattanLength() < 3)
        return; // a click that trembles is still a click
    dragged_ = true;
    qreal ratio = devicePixelRatioF();
    glm::vec2 from(float(last_mouse_.x() * ratio), float(last_mouse_.y() * ratio));
    glm::vec2 to(float(event->pos().x() * ratio), float(event->pos().y() * ratio));
    QSize size = pixel_size();
    bool pan = (event->buttons() & (Qt::RightButton | Qt::MiddleButton)) ||
               (event->modifiers() & Qt::ShiftModifier);
    Camera &camera = settings_.camera();
    if (pan)
        camera.pan(to - from, side_pixel_size().width(), side_pixel_size().height(),
                   double(size.width()) / double(size.height())); // side by side: a half of the view
    else if (camera.mode() == Camera::Mode::Orbit)
        camera.orbit(from, to, size.width(), size.height());
    else
        camera.look(to - from);
    last_mouse_ = event->pos();
    camera_moved();
}

void RenderView::mouseReleaseEvent(QMouseEvent *event)
{
    if (dragging_wipe_) {
        dragging_wipe_ = event->buttons() & Qt::LeftButton;
        return;
    }
    bool click = !dragged_ && (buttons_ & Qt::LeftButton) && !(event->buttons() & Qt::LeftButton);
    buttons_ = event->buttons();
    if (dragging_section_ && !(event->buttons() & Qt::LeftButton)) {
        dragging_section_ = false;
        settings_.record_change(); // the whole drag: one undo step
        settings_.close_step();
        request_frame(true); // the input rests: the full frame follows
        if (!dragged_)
            return; // a press on the handle is not a pick
    }
    if (click) {
        qreal ratio = devicePixelRatioF();
        emit clicked(QPoint(int(event->pos().x() * ratio), int(event->pos().y() * ratio)),
                     event->modifiers() & Qt::AltModifier);
    }
    antialias_when_still(); // the drag's last frame came while the button was down
}

void RenderView::wheelEvent(QWheelEvent *event)
{
    float steps = float(event->angleDelta().y()) / 120.0f;
    if (steps != 0.0f && model_) {
        settings_.camera().zoom(steps);
        camera_moved();
    }
    event->accept();
}

void RenderView::keyPressEvent(QKeyEvent *event)
{
    static const int walk_keys[] = {Qt::Key_W, Qt::Key_A, Qt::Key_S, Qt::Key_D, Qt::Key_Q, Qt::Key_E};
    if (event->key() == Qt::Key_Escape) {
        cancel_frame();
        return;
    }
    if (camera().mode() == Camera::Mode::Walk &&
        std::find(std::begin(walk_keys), std::end(walk_keys), event->key()) != std::end(walk_keys)) {
        if (!event->isAutoRepeat()) {
            walk_keys_.insert(event->key());
            walk_tick(); // one step at once, then smoothly while held
            walk_timer_->start();
        }
        return;
    }
    QWidget::keyPressEvent(event);
}

void RenderView::keyReleaseEvent(QKeyEvent *event)
{
    if (!event->isAutoRepeat()) {
        walk_keys_.remove(event->key());
        if (walk_keys_.isEmpty()) {
            walk_timer_->stop();
            antialias_when_still();
        }
    }
    QWidget::keyReleaseEvent(event);
}

void RenderView::focusOutEvent(QFocusEvent *event)
{
    walk_keys_.clear();
    walk_timer_->stop();
    QWidget::focusOutEvent(event);
}

void RenderView::walk_tick()
{
    if (!model_ || walk_keys_.isEmpty())
        return;
    glm::vec3 d(0.0f);
    d.x = float(walk_keys_.contains(Qt::Key_D)) - float(walk_keys_.contains(Qt::Key_A));
    d.y = float(walk_keys_.contains(Qt::Key_E)) - float(walk_keys_.contains(Qt::Key_Q));
    d.z = float(walk_keys_.contains(Qt::Key_W)) - float(walk_keys_.contains(Qt::Key_S));
    settings_.camera().walk(d);
    camera_moved();
}

void RenderView::camera_moved()
{
    settings_.camera_edited();
    request_frame(true);
}

// ------------------------------------------------------- sections (issue 28)

void RenderView::set_active_section(int index)
{
    if (index == active_section_)
        return;
    active_section_ = index;
    update();
}

bool RenderView::view_matrices(double modelview[16], double projection[16], QSize &size) const
{
    if (!model_ || settings().split == SplitMode::SideBySide)
        return false; // two half views: no single outline
    size = pixel_size();
    camera().matrices(size.width(), size.height(), modelview, projection);
    return true;
}

bool RenderView::section_handle(QPointF &centre) const
{
    const std::vector<SectionPlane> &sections = settings().sections;
    double mv[16], proj[16];
    QSize size;
    if (active_section_ < 0 || size_t(active_section_) >= sections.size() ||
        !sections[size_t(active_section_)].enabled || !view_matrices(mv, proj, size))
        return false;
    const SectionPlane &plane = sections[size_t(active_section_)];
    double box_min[3], box_max[3];
    section_overlay::model_box(*drawn_model(), box_min, box_max);
    if (section_overlay::box_polygon(plane.normal, plane.d, box_min, box_max).empty())
        return false;
    glm::dvec3 c = glm::dvec3(box_min[0] + box_max[0], box_min[1] + box_max[1], box_min[2] + box_max[2]) * 0.5;
    QPointF at;
    if (!section_overlay::project(mv, proj, size.width(), size.height(),
                                  section_overlay::nearest_on_plane(plane.normal, plane.d, c), at))
        return false;
    centre = at / devicePixelRatioF();
    return true;
}

void RenderView::paint_section(QPainter &painter) const
{
    const std::vector<SectionPlane> &sections = settings().sections;
    double mv[16], proj[16];
    QSize size;
    if (active_section_ < 0 || size_t(active_section_) >= sections.size() ||
        !sections[size_t(active_section_)].enabled || !view_matrices(mv, proj, size))
        return;
    const SectionPlane &plane = sections[size_t(active_section_)];
    double box_min[3], box_max[3];
    section_overlay::model_box(*drawn_model(), box_min, box_max);
    std::vector<glm::dvec3> polygon = section_overlay::box_polygon(plane.normal, plane.d, box_min, box_max);
    if (polygon.empty())
        return;
    const qreal ratio = devicePixelRatioF();
    QPolygonF outline;
    for (const glm::dvec3 &p : polygon) {
        QPointF at;
        if (!section_overlay::project(mv, proj, size.width(), size.height(), p, at))
            return; // a corner behind the eye: no outline rather than a wrong one
        outline << at / ratio;
    }
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(QPen(QColor(255, 140, 0, 230), 2.0));
    painter.setBrush(QColor(255, 140, 0, 28));
    painter.drawPolygon(outline);
    // the handle: a disc at the plane's centre and an arrow along its normal
    // (towards the side it removes)
    glm::dvec3 c = glm::dvec3(box_min[0] + box_max[0], box_min[1] + box_max[1], box_min[2] + box_max[2]) * 0.5;
    c = section_overlay::nearest_on_plane(plane.normal, plane.d, c);
    glm::dvec3 n(plane.normal[0], plane.normal[1], plane.normal[2]);
    double extent = glm::length(glm::dvec3(box_max[0] - box_min[0], box_max[1] - box_min[1], box_max[2] - box_min[2]));
    QPointF from, to;
    if (section_overlay::project(mv, proj, size.width(), size.height(), c, from) &&
        section_overlay::project(mv, proj, size.width(), size.height(), c + glm::normalize(n) * extent * 0.12, to)) {
        from /= ratio;
        to /= ratio;
        painter.setPen(QPen(QColor(255, 140, 0), 2.0));
        painter.drawLine(from, to);
        QPointF along = to - from;
        double length = std::hypot(along.x(), along.y());
        if (length > 6.0) {
            QPointF unit = along / length, side(-unit.y(), unit.x());
            painter.setBrush(QColor(255, 140, 0));
            painter.drawPolygon(QPolygonF() << to << to - unit * 9.0 + side * 4.5 << to - unit * 9.0 - side * 4.5);
        }
        painter.setBrush(dragging_section_ ? QColor(255, 200, 80) : QColor(255, 255, 255));
        painter.setPen(QPen(QColor(255, 140, 0), 2.0));
        painter.drawEllipse(from, 6.0, 6.0);
    }
    painter.restore();
}
