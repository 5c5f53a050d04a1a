// main_window_session.cpp: File > Save session…, Open session… and Open
// recent session (main_window.h, session.h, docs/sessions.md).
#include "camera_panel.h"
#include "file_io.h"
#include "main_window.h"
#include "session.h"

#include <QFileInfo>
#include <QMenu>

bool MainWindow::save_session(const QString &path, QString &error)
{
    if (!model_) {
        error = "no model is loaded: a session needs one";
        return false;
    }
    QString absolute = QFileInfo(path).absoluteFilePath();
    // what Export PNG renders: its chosen size, else the view's (side A's)
    QSize size = export_size_.isValid() ? export_size_ : view_->side_pixel_size();
    SessionExport exported;
    exported.width = size.width();
    exported.height = size.height();
    const oit_overlay_options aids = export_aids(settings_->render_settings());
    exported.aids = aids.axes || aids.scale_bar;
    exported.samples = export_samples(settings_->render_settings());
    std::vector<float> storage;
    oit_frame_settings frame =
        make_frame(settings_->render_settings(), *model_, settings_->camera(), size.width(), size.height(), storage);
    std::copy(frame.modelview, frame.modelview + 16, exported.modelview);
    std::copy(frame.projection, frame.projection + 16, exported.projection);
    std::string text = session_to_json(absolute.toStdString(), model_path_.toStdString(), settings_->render_settings(),
                                       settings_->camera(), model_.get(), camera_panel_->saved_views(), exported);
    // atomically (beside the file, renamed over it once whole), a regular file only (file_io.h)
    if (!write_output_file(absolute, "session", QByteArray::fromStdString(text), error))
        return false;
    add_recent_session(absolute);
    log_message("session", QString("saved %1 (%2x%3 export)").arg(absolute).arg(size.width()).arg(size.height()));
    return true;
}

bool MainWindow::open_session(const QString &path, QString &error)
{
    if (loader_->running()) {
        error = "still loading " + loading_path_ + ": open the session once it is in";
        return false;
    }
    QString absolute = QFileInfo(path).absoluteFilePath();
    QByteArray bytes;
    if (!read_regular_file(absolute, "session", bytes, error)) {
        recent_sessions_.removeAll(absolute);
        rebuild_recent_sessions_menu();
        return false;
    }
    SessionData data;
    std::string message;
    if (!session_from_json(absolute.toStdString(), bytes.toStdString(), data, message)) {
        error = QString::fromStdString(message);
        return false;
    }
    // the settings now (the tessellation applies to the load), the parts and
    // the camera once the model is in (load_finished), as a preset's
    std::string render = data.render.empty() ? std::string("{}") : data.render;
    RenderSettings s = settings_->render_settings();
    Camera camera = settings_->camera();
    bool has_camera = false;
    if (!preset_from_json(absolute.toStdString(), render, s, camera, has_camera, nullptr, message)) {
        error = QString::fromStdString(message);
        return false;
    }
    for (const std::string &warning : data.warnings)
        log_message("warning", QString::fromStdString(warning));
    if (data.export_aids >= 0)
        s.aids_in_export = data.export_aids == 1;
    settings_->render_settings() = s;
    if (has_camera)
        settings_->camera() = camera;
    pending_preset_ = render;
    pending_preset_name_ = absolute;
    pending_views_ = data.views;
    pending_session_ = true;
    if (data.export_width > 0 && data.export_height > 0)
        export_size_ = QSize(data.export_width, data.export_height);
    add_recent_session(absolute);
    log_message("session", "opening " + absolute);
    sync_panel_from_settings();
    load_model(QString::fromStdString(data.model_path));
    return true;
}

void MainWindow::add_recent_session(const QString &path)
{
    recent_sessions_.removeAll(path);
    recent_sessions_.prepend(path);
    while (recent_sessions_.size() > 8)
        recent_sessions_.removeLast();
    rebuild_recent_sessions_menu();
    save_state(false);
}

void MainWindow::rebuild_recent_sessions_menu()
{
    if (!recent_sessions_menu_)
        return;
    recent_sessions_menu_->clear();
    for (const QString &path : recent_sessions_)
        recent_sessions_menu_->addAction(path, this, [this, path] {
            QString error;
            if (!open_session(path, error))
                show_error("Open session", error);
        });
    recent_sessions_menu_->setEnabled(!recent_sessions_.isEmpty());
}
