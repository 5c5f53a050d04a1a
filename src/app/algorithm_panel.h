// algorithm_panel.h: the settings panel's Algorithm tab: the algorithm, the
// group of options only some algorithms read (sort, layer cap, the
// approximations' layers and moments, memory budget; each shown for the
// algorithms that read it), and shading, background and tessellation.
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
