// sections_panel.h: the settings panel's Sections tab (issue 28,
// docs/sections.md "In the workbench"): the section planes (add, remove,
// flip, enable), the active plane's normal and offset (a slider over the
// model's extent along the normal), aligning it to a standard view, the view
// direction or a picked face, the caps, cutting only the selected parts, and
// the exploded view's factor. Every change is a setting of the settings model
// (RenderSettings::sections, section_parts, caps, explode): undone, kept in
// presets and written by Copy as command like the others.
#pragma once

#include <functional>
#include <vector>

#include "settings_panel.h"

class QCheckBox;
class QDoubleSpinBox;
class QLabel;
class QListWidget;
class QPushButton;
class QSlider;

class SectionsPanel : public SettingsPanel {
    Q_OBJECT
public:
    explicit SectionsPanel(SettingsModel &settings, QWidget *parent = nullptr);

    // What the panel needs of the window: the model as drawn (the box new
    // planes go through and the slider spans; exploded where it is) and the
    // Parts tab's selection.
    std::function<const oit_model *()> drawn_model;
    std::function<std::vector<int>()> selected_parts;

    // The plane the controls (and the view's outline) edit; -1: none.
    int active() const { return active_; }
    void set_active(int index);

    // The tab's actions (its buttons; tests call them too). Each is one undo step.
    // A plane through the drawn model's centre, its normal towards the eye
    // (the half facing you is removed: you look at the cut), or +X without a model.
    void add_plane();
    void remove_plane();
    void flip_plane(); // n and d negated: the other half is kept
    // The normal set to n, the plane kept through its point nearest the model's centre.
    void align(const double n[3]);
    void align_to_view(); // the normal towards the eye
    // The offset at fraction t (0..1) of the drawn model's extent along the normal (the slider).
    void set_offset_fraction(double t);
    // The plane through point with this normal (a picked face's, towards the eye).
    void set_plane(const double point[3], const double normal[3]);
    // Cut only the parts selected in the Parts tab (on), or every part (off).
    void cut_selected_only(bool on);

    // "Pick face": the next click in the view aligns the active plane (the window routes it).
    bool picking_face() const;
    void stop_picking_face();

    QListWidget *plane_list() const { return list_; }
    QSlider *offset_slider() const { return offset_slider_; }
    QSlider *explode_slider() const { return explode_slider_; }

signals:
    void active_changed(int index);

private:
    // the offset range along the active plane's normal over the drawn model's box
    void offset_range(const SectionPlane &plane, double &low, double &high) const;
    void box_centre(double centre[3]) const;
    void refresh_list();
    void discrete_step(); // a button's change: changed(), one undo step of its own

    int active_ = -1;
    QListWidget *list_ = nullptr;
    QPushButton *remove_ = nullptr, *flip_ = nullptr, *pick_face_ = nullptr;
    QDoubleSpinBox *normal_[3] = {nullptr, nullptr, nullptr};
    QDoubleSpinBox *offset_ = nullptr;
    QSlider *offset_slider_ = nullptr;
    QSlider *explode_slider_ = nullptr;
    QCheckBox *selected_only_ = nullptr;
    QLabel *parts_label_ = nullptr;
    QWidget *plane_box_ = nullptr;
};
