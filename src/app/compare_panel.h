// compare_panel.h: the settings panel's Compare tab: the error view (the map
// against the CPU reference, `oit render --error-vs-reference`), the split
// view's mode and its second algorithm (side B; side A is the Algorithm tab's),
// and the figures of the last frame against the reference.
#pragma once

#include <QWidget>

#include "settings.h"

class QCheckBox;
class QComboBox;
class QLabel;
class QDoubleSpinBox;

class ComparePanel : public QWidget {
    Q_OBJECT
public:
    // Edits settings in place; changed() follows every edit by the user.
    explicit ComparePanel(RenderSettings &settings, QWidget *parent = nullptr);
    // Refresh the controls from the settings (no changed()).
    void sync();
    // The last full frame's figures against the reference (empty: none).
    void set_figures(const QString &text);
    QCheckBox *error_check() const { return error_; }
    QComboBox *split_combo() const { return split_; }
    QComboBox *algorithm_b_combo() const { return algorithm_b_; }

signals:
    void changed();      // a setting that needs a new frame
    void wipe_changed(); // the wipe line moved: repaint only

private:
    RenderSettings &settings_;
    QCheckBox *error_ = nullptr;
    QComboBox *split_ = nullptr, *algorithm_b_ = nullptr;
    QDoubleSpinBox *wipe_ = nullptr;
    QLabel *figures_ = nullptr;
    bool syncing_ = false;
};
