// parts_panel.h: the Parts tab: one row per model component (part) with its
// visibility and opacity, filtered by name, fluid at 10,000+ parts: a model/view
// list with a painted slider per row instead of one widget per row. A model with
// an assembly tree (oit_model.nodes) shows it: subassemblies as rows that expand,
// their check box and slider standing for every part under them.
#pragma once

#include <QString>
#include <QWidget>

#include <vector>

#include "parts_model.h"

class QAbstractItemView;
class QAction;
class QModelIndex;
class QSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QSortFilterProxyModel;
class QTreeView;

class PartsPanel : public QWidget {
    Q_OBJECT
public:
    explicit PartsPanel(QWidget *parent = nullptr);
    // Show model's parts (nullptr: none) with these values (sizes == component_count, else reset to 1 / visible).
    // The panel copies names, colours and counts: model need not outlive the call.
    void set_model(const oit_model *model, const std::vector<float> &alpha, const std::vector<char> &visible);
    // New values after an outside change (preset, undo): no rebuild, only dataChanged.
    void set_values(const std::vector<float> &alpha, const std::vector<char> &visible);
    const std::vector<float> &alpha() const;
    const std::vector<char> &visible() const;
    std::vector<int> selected_parts() const; // component indices, ascending (an assembly's row: every part under it)
    // select only it, make it current, open its assemblies and scroll to it (clears a filter that hides it)
    void select_part(int index);
    // select exactly these parts (the first made current, opened and scrolled to)
    void select_parts(const std::vector<int> &indices);
    // Ghosting: every part not selected to opacity alpha (selected ones keep
    // theirs), as one change (one parts_changed); false when nothing is
    // selected or nothing changed.
    bool fade_others(float alpha);
    // the opacity Fade others sets, in percent (the spin box beside the list; default 10)
    int fade_percent() const;
    void set_fade_percent(int percent);
    // An entry of the list's context menu (the window's actions: Fade others, Highlight selection).
    void add_context_action(QAction *action);
    QAbstractItemView *view() const;
    QLineEdit *filter() const;
    int shown_row_count() const; // rows after filtering

signals:
    void parts_changed(); // alpha()/visible() changed by the user (checkbox, slider, keys, Reset, Isolate, Show all)
    void frame_selected_requested(std::vector<int> parts);
    void selection_changed(std::vector<int> parts);
    void fade_requested(); // the Fade others button: the window does it as one undo step

private:
    friend class PartsView;
    // the current row's opacity by delta percent (keys); true if it had a current row
    // (every selected row when the current one is among several selected)
    bool step_current_alpha(int delta_percent);
    // The slider of a selected row moved while several are selected: every
    // selected part to alpha (true); false for any other row (the row alone).
    bool set_selected_alpha(const QModelIndex &row, float alpha);
    bool toggle_current_visible();
    void apply(const std::vector<float> &alpha, const std::vector<char> &visible);
    void update_buttons();
    void filter_changed(); // a tree opens to show the matches, and closes again when cleared

    PartsModel *model_;
    QSortFilterProxyModel *proxy_;
    QLineEdit *filter_;
    QTreeView *view_;
    QLabel *note_;
    QPushButton *reset_, *isolate_, *show_all_, *frame_, *fade_;
    QSpinBox *fade_percent_;
};
