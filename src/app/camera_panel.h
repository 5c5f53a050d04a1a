// camera_panel.h: the settings panel's Camera tab: orbit or walk,
// perspective or orthographic, the field of view, Reset, and the camera poses
// saved for the model.
#pragma once

#include <vector>

#include "settings_panel.h"

class QListWidget;

class CameraPanel : public SettingsPanel {
    Q_OBJECT
public:
    explicit CameraPanel(SettingsModel &settings, QWidget *parent = nullptr);
    // Forget the saved poses (another model).
    void clear_saved_views();

signals:
    void reset_camera_requested(); // frame the whole model again (the view knows its size)

private:
    QListWidget *saved_views_ = nullptr;
    std::vector<Camera> saved_cameras_;
};
