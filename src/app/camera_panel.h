// camera_panel.h: the settings panel's Camera tab: orbit or walk, turntable
// or trackball orbit, the up axis (Y or Z; changing it frames the model again),
// perspective or orthographic, the field of view, Reset, and the camera poses
// saved for the model: named, renamed (edit in the list), deleted, and kept
// with the model in the saved state (MainWindow).
#pragma once

#include <vector>

#include "settings_panel.h"

class QListWidget;

class CameraPanel : public SettingsPanel {
    Q_OBJECT
public:
    explicit CameraPanel(SettingsModel &settings, QWidget *parent = nullptr);
    // The model's saved views (from the saved state; another model: its own).
    void set_saved_views(const std::vector<SavedView> &views);
    const std::vector<SavedView> &saved_views() const { return saved_; }
    // Save the camera's pose as name ("" names it "view N", the first N free).
    void save_view(const QString &name = QString());
    // Row's name (not empty; the list's edit does the same); false for a bad row or name.
    bool rename_view(int row, const QString &name);
    bool delete_view(int row);
    bool go_to_view(int row);

signals:
    void reset_camera_requested(); // frame the whole model again (the view knows its size)
    void saved_views_changed();    // saved, renamed or deleted: the window keeps them

private:
    void refill();
    QListWidget *list_ = nullptr;
    std::vector<SavedView> saved_;
    bool filling_ = false;
};
