// settings_panel.h: what the settings panel's tabs share. A SettingsPanel
// binds its controls to the settings model (settings_model.h): each control
// reads its setting in sync() and writes it when the user changes it, then
// says so with edited() (render) or changed() (other controls show it too:
// refresh them, then render); the window records the undo step and asks for
// the frame. Also: the rows an algorithm cannot use hidden, the values it
// cannot express hidden and disabled in a combo box (both from the core's
// capability tables), and a tooltip on every control (with its flag).
#pragma once

#include <QString>
#include <QWidget>

#include <functional>
#include <map>
#include <utility>
#include <vector>

#include "render_worker.h" // CapabilityTable
#include "settings_model.h"

class QCheckBox;
class QComboBox;
class QFormLayout;
class QGroupBox;
class QVBoxLayout;
class QIcon;
class QDoubleSpinBox;
class QSlider;
class QSpinBox;

class SettingsPanel : public QWidget {
    Q_OBJECT
public:
    explicit SettingsPanel(SettingsModel &settings, QWidget *parent = nullptr);
    // Refresh every control from the settings (no edited() or changed()).
    void sync();

signals:
    void edited();  // a control changed a setting: record it and render
    void changed(); // a setting that other controls show changed: refresh them, record, render

protected:
    RenderSettings &settings() { return model_.render_settings(); }
    Camera &camera() { return model_.camera(); }
    SettingsModel &settings_model() { return model_; }
    // Run by sync(), in the order added.
    void on_sync(std::function<void()> action) { sync_actions_.push_back(std::move(action)); }
    bool syncing() const { return syncing_; }

    // A labelled group of rows (Layers, Modulation, ...) added to layout, and its form.
    QFormLayout *group(QVBoxLayout *layout, const QString &title, QGroupBox **box_out = nullptr);
    // Show form's row of field (and its label) only while applies(the current
    // algorithm) (read from the core's capabilities, algorithm_uses below);
    // the field remembers the algorithms it applies to for its tooltip.
    void show_row_when(QFormLayout *form, QWidget *field, std::function<bool(const QString &)> applies);
    // Show the group only while one of its rows is shown (after its rows' show_row_when).
    void show_group_when_used(QGroupBox *box);

    // Controls bound to one value: get() shows it, set() takes the user's.
    // A slider with a numeric field, linear between low and high.
    QWidget *slider_row(double low, double high, int decimals, std::function<float()> get,
                        std::function<void(float)> set, QSlider **slider_out = nullptr);
    // A length from 0 ("auto") over many orders of magnitude: the slider is
    // logarithmic between range()'s ends, which follow the model, and its left end is 0.
    QWidget *log_length_row(std::function<std::pair<double, double>()> range, std::function<float()> get,
                            std::function<void(float)> set);
    QComboBox *combo(const QStringList &items, std::function<int()> get, std::function<void(int)> set);
    // The core's words for a setting, in the order of its values (oit_setting_words).
    static QStringList words(oit_setting setting);
    QSpinBox *spin_box(int low, int high, std::function<int()> get, std::function<void(int)> set);
    QCheckBox *check_box(const QString &text, std::function<bool()> get, std::function<void(bool)> set);

private:
    SettingsModel &model_;
    // show_row_when's rows: each form's rows as built (label or none, field), and the rule of those shown for some
    struct FormRow {
        QWidget *label, *field;
    };
    std::map<QFormLayout *, std::vector<FormRow>> form_rows_;
    std::map<QFormLayout *, std::map<QWidget *, std::function<bool(const QString &)>>> row_applies_;
    void refresh_rows(QFormLayout *form);
    std::vector<std::function<void()>> sync_actions_;
    bool syncing_ = false; // true while sync() sets the controls
    // A slider (0..1000) and a spin box (set up by configure first) in one row,
    // each following the other: from_slider maps a position to a value,
    // to_slider back; set gets the spin box's value (rounded to its decimals)
    // when set_rounded, else the slider's own.
    QWidget *linked_row(QSlider *&slider, QDoubleSpinBox *&spin, std::function<void(QDoubleSpinBox *)> configure,
                        std::function<double(int)> from_slider, std::function<int(double)> to_slider,
                        std::function<void(float)> set, bool set_rounded);
};

// content in a frameless scroll area that resizes it (a tab of the panel).
QWidget *scrolled(QWidget *content);
// A 14x14 swatch of an RGB colour, and the colour as "r,g,b".
QIcon swatch(const float colour[3]);
QString colour_text(const float colour[3]);

// Whether algorithm renders the option key ("view:heatmap", ...) of the
// capability table, and a tooltip naming the algorithms that do; what is the
// option's name in the tooltip.
std::pair<bool, QString> capability(const CapabilityTable &table, const QString &key, const QString &what,
                                    const QString &algorithm);
// The combo box's items (index, capability key) the algorithm cannot express
// are disabled and hidden from its list (shown while chosen), each with that
// tooltip; the settings keep them, and a frame leaves them out and says so.
void hide_items_not_rendered(QComboBox *box, const std::vector<std::pair<int, QString>> &keys,
                             const CapabilityTable &table, const QString &algorithm);

// Whether the algorithm renders the capability key ("modulation:fields", ...),
// and whether it reads an OIT_OPTION_* (the core's oit_algorithm_reads).
bool algorithm_renders(const CapabilityTable &table, const QString &key, const QString &algorithm);
bool algorithm_reads(const QString &algorithm, unsigned option);
// Whether an algorithm renders any of the keys (for show_row_when).
std::function<bool(const QString &)> renders_any(const CapabilityTable &table, const QStringList &keys);
// The algorithms of the core's list for which applies() holds.
QStringList algorithms_where(const std::function<bool(const QString &)> &applies);

// Every control in root's form layouts gets a tooltip: its label, the
// command-line flag it sets and the algorithms it applies to (rows shown for
// some only), then what it does.
void give_every_control_a_tooltip(QWidget *root);
