// views_panel.h: the settings panel's Views tab: what the view shows (the
// colour, the list-length heatmap, a peel limit or one layer, ib's buffers),
// stepping layer by layer, and the edge view; the views and rows the
// algorithm cannot show are hidden (the core's capability tables).
#pragma once

#include "settings_panel.h"

class QComboBox;

class ViewsPanel : public SettingsPanel {
    Q_OBJECT
public:
    // capabilities: which algorithm renders which view (hidden for the others)
    ViewsPanel(SettingsModel &settings, const CapabilityTable &capabilities, QWidget *parent = nullptr);

private:
    QComboBox *view_ = nullptr;
};
