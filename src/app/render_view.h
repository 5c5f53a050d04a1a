// render_view.h: the render view. A QOpenGLWidget (4.3 core) whose context
// runs the core's algorithms: the scene is uploaded here, every frame renders
// into the algorithm's RGBA8 output, is read back (that image is also what
// tests and Export PNG see) and blitted to the widget.
#pragma once

#include <QElapsedTimer>
#include <QImage>
#include <QOpenGLWidget>
#include <QPoint>
#include <QSet>

#include <string>
#include <vector>

#include "camera.h"
#include "oit.h"
#include "settings.h"

class QTimer;

class RenderView : public QOpenGLWidget {
    Q_OBJECT
public:
    explicit RenderView(QWidget *parent = nullptr);
    ~RenderView() override;

    RenderSettings settings;
    Camera camera;

    // Upload a model (GUI thread; the model stays owned by the caller and must
    // outlive the view's use of it). Returns false with a message.
    bool set_model(const oit_model *model, std::string &error);
    const oit_model *model() const { return model_; }
    // Frame the model again with the default three-quarter view.
    void reset_camera();

    // Render the current settings offscreen at any size into image (the
    // matrices used are returned in frame). The on-screen algorithm is untouched.
    bool render_offscreen(int width, int height, oit_image &image, oit_frame_settings &frame,
                          std::string &error);
    // The frame the view shows now (its size in pixels and its matrices).
    oit_frame_settings current_frame(std::vector<float> &storage) const;
    QSize pixel_size() const;

    const QImage &last_image() const { return last_image_; }
    const oit_stats &last_stats() const { return last_stats_; }
    double measured_fps() const { return fps_; }
    long total_overflow_retries() const { return overflow_total_; }
    const std::string &renderer() const { return renderer_; }
    const std::string &shader_dir() const { return shader_dir_; }
    bool gl_ready() const { return gl_ready_; }
    const std::string &gl_error() const { return gl_error_; }

    void set_continuous(bool on);
    // While the mouse drags or walk keys are held, render at half resolution
    // (scaled up on screen); the full resolution returns on release.
    void set_fast_interaction(bool on);
    // The size the algorithm renders at now (pixel_size, or half of it while interacting).
    QSize render_size() const;

signals:
    void frame_rendered();
    void render_failed(const QString &message);
    void camera_changed();

protected:
    void initializeGL() override;
    void paintGL() override;
    void mousePressEvent(QMouseEvent *event) override;
    void mouseMoveEvent(QMouseEvent *event) override;
    void mouseReleaseEvent(QMouseEvent *event) override;
    void wheelEvent(QWheelEvent *event) override;
    void keyPressEvent(QKeyEvent *event) override;
    void keyReleaseEvent(QKeyEvent *event) override;
    void focusOutEvent(QFocusEvent *event) override;

private:
    bool ensure_algorithm(std::string &error);
    void destroy_algorithm();
    void release_gl();
    void walk_tick();
    void show_image(const oit_image &image);

    const oit_model *model_ = nullptr;
    oit_scene gpu_scene_{};
    oit_scene cpu_scene_{};
    bool scene_uploaded_ = false;

    const oit_algorithm_ops *ops_ = nullptr;
    oit_algorithm *algorithm_ = nullptr;
    std::string algorithm_key_;
    int algorithm_width_ = 0, algorithm_height_ = 0;

    bool gl_ready_ = false;
    std::string gl_error_, renderer_, shader_dir_;
    unsigned blit_texture_ = 0, blit_framebuffer_ = 0;
    int blit_width_ = 0, blit_height_ = 0;

    QImage last_image_;
    oit_stats last_stats_{};
    long overflow_total_ = 0;
    bool continuous_ = false;
    bool fast_interaction_ = true;
    QElapsedTimer fps_clock_;
    double fps_ = 0.0;

    QPoint last_mouse_;
    Qt::MouseButtons buttons_ = Qt::NoButton;
    QSet<int> walk_keys_;
    QTimer *walk_timer_ = nullptr;
};
