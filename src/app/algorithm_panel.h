// algorithm_panel.h: the settings panel's Algorithm tab: the algorithm and
// its configuration (sort, neighbours, memory budget, layer cap, the
// approximations' layers and moments), shading and background.
#pragma once

#include "settings_panel.h"

class AlgorithmPanel : public SettingsPanel {
    Q_OBJECT
public:
    explicit AlgorithmPanel(SettingsModel &settings, QWidget *parent = nullptr);

signals:
    // --tessellation changed: a STEP or IGES model must be loaded again
    void tessellation_changed();
};
