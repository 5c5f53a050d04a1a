// render_view.cpp: see render_view.h.
#include "render_view.h"

#include <QCoreApplication>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QOpenGLExtraFunctions>
#include <QTimer>
#include <QWheelEvent>

#include <cstring>

#include "gl_setup.h"

namespace {

// What makes an algorithm instance reusable: its name and its configuration.
std::string algorithm_key(const RenderSettings &s)
{
    return s.algorithm + "/" + std::to_string(int(s.config.ll_sort)) + "/" +
           std::to_string(s.config.max_memory_bytes) + "/" + std::to_string(s.config.max_layers) + "/" +
           std::to_string(s.config.initial_fragment_capacity) + "/" + std::to_string(s.config.debug);
}

// The GL state a fresh context has, which is what `oit render` starts from.
// Qt's context has been used by Qt and by other algorithms before; the core's
// algorithms set what they change, but not always what they merely rely on
// (dp clears its depth target with glClearBufferfv, which obeys glDepthMask,
// and ll leaves the mask off), so each frame starts from the defaults.
void reset_gl_state(QOpenGLExtraFunctions *gl)
{
    gl->glDepthMask(GL_TRUE);
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->glStencilMask(0xffffffffu);
    gl->glDisable(GL_BLEND);
    gl->glDisable(GL_DEPTH_TEST);
    gl->glDisable(GL_CULL_FACE);
    gl->glDisable(GL_SCISSOR_TEST);
    gl->glDisable(GL_STENCIL_TEST);
    gl->glBlendEquation(GL_FUNC_ADD);
    gl->glBlendFunc(GL_ONE, GL_ZERO);
    gl->glDepthFunc(GL_LESS);
    gl->glActiveTexture(GL_TEXTURE0);
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    gl->glUseProgram(0);
    gl->glBindVertexArray(0);
    gl->glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    gl->glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl->glPixelStorei(GL_PACK_ALIGNMENT, 4);
}

} // namespace

RenderView::RenderView(QWidget *parent) : QOpenGLWidget(parent)
{
    setFocusPolicy(Qt::StrongFocus);
    setMinimumSize(64, 64);
    walk_timer_ = new QTimer(this);
    walk_timer_->setInterval(33);
    connect(walk_timer_, &QTimer::timeout, this, &RenderView::walk_tick);
    oit_stats_reset(&last_stats_);
}

RenderView::~RenderView()
{
    // the context outlives this part of the object: its aboutToBeDestroyed
    // must not call back into members that are gone
    if (context())
        disconnect(context(), nullptr, this, nullptr);
    if (gl_ready_) {
        makeCurrent();
        release_gl();
        doneCurrent();
    }
}

void RenderView::release_gl()
{
    destroy_algorithm();
    if (scene_uploaded_)
        oit_scene_release(&gpu_scene_);
    scene_uploaded_ = false;
    if (blit_framebuffer_) {
        QOpenGLExtraFunctions *gl = context()->extraFunctions();
        gl->glDeleteFramebuffers(1, &blit_framebuffer_);
        gl->glDeleteTextures(1, &blit_texture_);
        blit_framebuffer_ = blit_texture_ = 0;
    }
}

void RenderView::initializeGL()
{
    std::string error;
    if (!workbench_gl_init(renderer_, error)) {
        gl_error_ = error;
        emit render_failed(QString::fromStdString(error));
        return;
    }
    char dir[4096];
    oit_error err{};
    std::string argv0 = QCoreApplication::applicationFilePath().toStdString();
    if (oit_find_shader_dir(argv0.c_str(), dir, sizeof dir, &err) != OIT_OK) {
        gl_error_ = err.message;
        emit render_failed(QString::fromUtf8(err.message));
        return;
    }
    shader_dir_ = dir;
    gl_ready_ = true;
    connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, [this] {
        makeCurrent();
        release_gl();
        doneCurrent();
        gl_ready_ = false;
    });
    if (model_ && !set_model(model_, error))
        emit render_failed(QString::fromStdString(error));
}

bool RenderView::set_model(const oit_model *model, std::string &error)
{
    model_ = model;
    if (!gl_ready_)
        return true; // uploaded by initializeGL
    makeCurrent();
    destroy_algorithm(); // algorithms may keep buffers sized for the last scene
    if (scene_uploaded_)
        oit_scene_release(&gpu_scene_);
    scene_uploaded_ = false;
    oit_error err{};
    oit_status status = oit_scene_upload(&gpu_scene_, model, &err);
    doneCurrent();
    if (status != OIT_OK) {
        error = err.message;
        model_ = nullptr;
        return false;
    }
    scene_uploaded_ = true;
    oit_scene_cpu(&cpu_scene_, model);
    update();
    return true;
}

void RenderView::reset_camera()
{
    if (!model_)
        return;
    QSize size = pixel_size();
    camera.set_mode(Camera::Mode::Orbit);
    camera.orthographic = false;
    camera.frame(*model_, size.width(), size.height());
    emit camera_changed();
    update();
}

QSize RenderView::pixel_size() const
{
    qreal ratio = devicePixelRatioF();
    return QSize(std::max(1, int(width() * ratio)), std::max(1, int(height() * ratio)));
}

QSize RenderView::render_size() const
{
    QSize full = pixel_size();
    bool interacting = buttons_ != Qt::NoButton || !walk_keys_.isEmpty();
    if (!fast_interaction_ || !interacting)
        return full;
    return QSize(std::max(1, (full.width() + 1) / 2), std::max(1, (full.height() + 1) / 2));
}

void RenderView::set_fast_interaction(bool on)
{
    fast_interaction_ = on;
    update();
}

oit_frame_settings RenderView::current_frame(std::vector<float> &storage) const
{
    QSize size = pixel_size();
    return make_frame(settings, *model_, camera, size.width(), size.height(), storage);
}

void RenderView::destroy_algorithm()
{
    if (algorithm_)
        ops_->destroy(algorithm_);
    algorithm_ = nullptr;
    ops_ = nullptr;
    algorithm_key_.clear();
    algorithm_width_ = algorithm_height_ = 0;
}

bool RenderView::ensure_algorithm(std::string &error)
{
    oit_error err{};
    if (!algorithm_ || algorithm_key_ != algorithm_key(settings)) {
        destroy_algorithm();
        const oit_algorithm_ops *ops = oit_algorithm_find(settings.algorithm.c_str());
        if (!ops) {
            error = "unknown algorithm '" + settings.algorithm + "'";
            return false;
        }
        oit_algorithm_config config = settings.config;
        config.shader_dir = shader_dir_.c_str();
        if (ops->create(&config, &algorithm_, &err) != OIT_OK) {
            algorithm_ = nullptr;
            error = err.message;
            return false;
        }
        ops_ = ops;
        algorithm_key_ = algorithm_key(settings);
    }
    QSize size = render_size();
    if (size.width() != algorithm_width_ || size.height() != algorithm_height_) {
        if (ops_->resize(algorithm_, size.width(), size.height(), &err) != OIT_OK) {
            error = err.message;
            destroy_algorithm();
            return false;
        }
        algorithm_width_ = size.width();
        algorithm_height_ = size.height();
    }
    return true;
}

void RenderView::paintGL()
{
    QOpenGLExtraFunctions *gl = context()->extraFunctions();
    auto clear = [&] {
        gl->glBindFramebuffer(GL_FRAMEBUFFER, defaultFramebufferObject());
        gl->glClearColor(0.35f, 0.35f, 0.38f, 1.0f);
        gl->glClear(GL_COLOR_BUFFER_BIT);
    };
    if (!gl_ready_ || !model_ || !scene_uploaded_) {
        clear();
        return;
    }
    std::string error;
    if (!ensure_algorithm(error)) {
        clear();
        emit render_failed(QString::fromStdString(error));
        return;
    }
    std::vector<float> storage;
    QSize size = render_size();
    oit_frame_settings frame = make_frame(settings, *model_, camera, size.width(), size.height(), storage);
    oit_error err{};
    const oit_scene *scene = ops_->uses_gl ? &gpu_scene_ : &cpu_scene_;
    oit_image image{};
    reset_gl_state(gl);
    oit_status status = ops_->render(algorithm_, scene, &frame, &err);
    if (status == OIT_OK)
        status = ops_->read_image(algorithm_, &image, &err);
    if (status != OIT_OK) {
        // a failed frame (an exhausted memory budget...) leaves the algorithm unusable
        destroy_algorithm();
        clear();
        emit render_failed(QString::fromUtf8(err.message));
        return;
    }
    ops_->stats(algorithm_, &last_stats_);
    if (last_stats_.overflow_retries > 0)
        overflow_total_ += long(last_stats_.overflow_retries);
    show_image(image);
    last_image_ = QImage(image.rgba, image.width, image.height, QImage::Format_RGBA8888).copy();
    oit_image_free(&image);

    if (fps_clock_.isValid() && continuous_) {
        double ms = double(fps_clock_.nsecsElapsed()) / 1e6;
        fps_ = ms > 0.0 ? 1000.0 / ms : 0.0;
    } else {
        fps_ = last_stats_.cpu_ms > 0.0 ? 1000.0 / last_stats_.cpu_ms : 0.0;
    }
    fps_clock_.start();
    emit frame_rendered();
    if (continuous_)
        update();
}

// The read-back image goes into a texture and is blitted to the widget's
// framebuffer, flipped (the image is top row first, GL's origin is the bottom).
void RenderView::show_image(const oit_image &image)
{
    QOpenGLExtraFunctions *gl = context()->extraFunctions();
    if (!blit_texture_) {
        gl->glGenTextures(1, &blit_texture_);
        gl->glGenFramebuffers(1, &blit_framebuffer_);
    }
    gl->glBindTexture(GL_TEXTURE_2D, blit_texture_);
    if (blit_width_ != image.width || blit_height_ != image.height) {
        gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                         nullptr);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        blit_width_ = image.width;
        blit_height_ = image.height;
    }
    gl->glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl->glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    gl->glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba);
    gl->glBindFramebuffer(GL_READ_FRAMEBUFFER, blit_framebuffer_);
    gl->glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, blit_texture_, 0);
    gl->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, defaultFramebufferObject());
    gl->glDisable(GL_SCISSOR_TEST);
    QSize full = pixel_size(); // larger than the image while interacting at half resolution
    bool scaled = full.width() != image.width || full.height() != image.height;
    gl->glBlitFramebuffer(0, 0, image.width, image.height, 0, full.height(), full.width(), 0, GL_COLOR_BUFFER_BIT,
                          scaled ? GL_LINEAR : GL_NEAREST);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, defaultFramebufferObject());
    gl->glViewport(0, 0, full.width(), full.height());
}

bool RenderView::render_offscreen(int width, int height, oit_image &image, oit_frame_settings &frame,
                                  std::string &error)
{
    if (!gl_ready_ || !model_ || !scene_uploaded_) {
        error = gl_ready_ ? "no model is loaded" : "no OpenGL context: " + gl_error_;
        return false;
    }
    const oit_algorithm_ops *ops = oit_algorithm_find(settings.algorithm.c_str());
    if (!ops) {
        error = "unknown algorithm '" + settings.algorithm + "'";
        return false;
    }
    makeCurrent();
    std::vector<float> storage;
    frame = make_frame(settings, *model_, camera, width, height, storage);
    oit_algorithm_config config = settings.config;
    config.shader_dir = shader_dir_.c_str();
    oit_error err{};
    oit_algorithm *alg = nullptr;
    oit_status status = ops->create(&config, &alg, &err);
    if (status == OIT_OK)
        status = ops->resize(alg, width, height, &err);
    reset_gl_state(context()->extraFunctions());
    if (status == OIT_OK)
        status = ops->render(alg, ops->uses_gl ? &gpu_scene_ : &cpu_scene_, &frame, &err);
    if (status == OIT_OK)
        status = ops->read_image(alg, &image, &err);
    if (alg)
        ops->destroy(alg);
    doneCurrent();
    frame.local.component_alpha = nullptr; // storage ends here
    if (status != OIT_OK)
        error = err.message;
    return status == OIT_OK;
}

void RenderView::set_continuous(bool on)
{
    continuous_ = on;
    fps_clock_.invalidate();
    update();
}

// ------------------------------------------------------------------ input

void RenderView::mousePressEvent(QMouseEvent *event)
{
    last_mouse_ = event->pos();
    buttons_ = event->buttons();
    setFocus();
}

void RenderView::mouseMoveEvent(QMouseEvent *event)
{
    if (!model_ || buttons_ == Qt::NoButton)
        return;
    qreal ratio = devicePixelRatioF();
    glm::vec2 from(float(last_mouse_.x() * ratio), float(last_mouse_.y() * ratio));
    glm::vec2 to(float(event->pos().x() * ratio), float(event->pos().y() * ratio));
    QSize size = pixel_size();
    bool pan = (event->buttons() & (Qt::RightButton | Qt::MiddleButton)) ||
               (event->modifiers() & Qt::ShiftModifier);
    if (pan)
        camera.pan(to - from, size.height());
    else if (camera.mode() == Camera::Mode::Orbit)
        camera.trackball(from, to, size.width(), size.height());
    else
        camera.look(to - from);
    last_mouse_ = event->pos();
    emit camera_changed();
    update();
}

void RenderView::mouseReleaseEvent(QMouseEvent *event)
{
    buttons_ = event->buttons();
    if (fast_interaction_)
        update(); // the full resolution again
}

void RenderView::wheelEvent(QWheelEvent *event)
{
    float steps = float(event->angleDelta().y()) / 120.0f;
    if (steps != 0.0f && model_) {
        camera.zoom(steps);
        emit camera_changed();
        update();
    }
    event->accept();
}

void RenderView::keyPressEvent(QKeyEvent *event)
{
    static const int walk_keys[] = {Qt::Key_W, Qt::Key_A, Qt::Key_S, Qt::Key_D, Qt::Key_Q, Qt::Key_E};
    if (camera.mode() == Camera::Mode::Walk && std::find(std::begin(walk_keys), std::end(walk_keys), event->key()) != std::end(walk_keys)) {
        if (!event->isAutoRepeat()) {
            walk_keys_.insert(event->key());
            walk_tick(); // one step at once, then smoothly while held
            walk_timer_->start();
        }
        return;
    }
    QOpenGLWidget::keyPressEvent(event);
}

void RenderView::keyReleaseEvent(QKeyEvent *event)
{
    if (!event->isAutoRepeat()) {
        walk_keys_.remove(event->key());
        if (walk_keys_.isEmpty()) {
            walk_timer_->stop();
            update(); // the full resolution again
        }
    }
    QOpenGLWidget::keyReleaseEvent(event);
}

void RenderView::focusOutEvent(QFocusEvent *event)
{
    walk_keys_.clear();
    walk_timer_->stop();
    QOpenGLWidget::focusOutEvent(event);
}

void RenderView::walk_tick()
{
    if (!model_ || walk_keys_.isEmpty())
        return;
    glm::vec3 d(0.0f);
    d.x = float(walk_keys_.contains(Qt::Key_D)) - float(walk_keys_.contains(Qt::Key_A));
    d.y = float(walk_keys_.contains(Qt::Key_E)) - float(walk_keys_.contains(Qt::Key_Q));
    d.z = float(walk_keys_.contains(Qt::Key_W)) - float(walk_keys_.contains(Qt::Key_S));
    camera.walk(d);
    emit camera_changed();
    update();
}
