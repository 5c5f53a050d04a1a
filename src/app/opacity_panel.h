// opacity_panel.h: the settings panel's Opacity tab: what every algorithm
// does (alpha, contrast, the focus shape and its region), then in groups the
// modulations (curvature, distance), the transparency fields (halos) and the
// surface neighbours' search, each row shown only for the algorithms that
// render it (the core's capability tables).
#pragma once

#include "settings_panel.h"

class QComboBox;
class QSlider;

class OpacityPanel : public SettingsPanel {
    Q_OBJECT
public:
    // capabilities: which algorithm renders which modulation (hidden for the others)
    OpacityPanel(SettingsModel &settings, const CapabilityTable &capabilities, QWidget *parent = nullptr);
    QSlider *alpha_slider() const { return alpha_slider_; }

private:
    QSlider *alpha_slider_ = nullptr;
    QComboBox *modulation_ = nullptr, *distance_ = nullptr;
};
