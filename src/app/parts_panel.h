// parts_panel.h: the Parts tab: one row per model component (part) with its
// visibility and opacity, filtered by name, fluid at 10,000+ parts: a model/view
// list with a painted slider per row instead of one widget per row.
#pragma once

#include <QAbstractTableModel>
#include <QByteArray>
#include <QColor>
#include <QHash>
#include <QIcon>
#include <QString>
#include <QWidget>

#include <vector>

#include "oit.h"

class QAbstractItemView;
class QLabel;
class QLineEdit;
class QPushButton;
class QSortFilterProxyModel;
class QTreeView;

// The parts as a table: part (name, colour swatch, checkbox = visible), opacity
// (a slider, painted by the panel's delegate), percent. Row == component index.
// It copies what it shows, so the oit_model need not outlive it.
class PartsModel : public QAbstractTableModel {
    Q_OBJECT
public:
    enum Column { PartColumn, OpacityColumn, PercentColumn, ColumnCount };
    // the row's alpha (float in [0, 1]); settable on OpacityColumn
    static constexpr int AlphaRole = Qt::UserRole + 1;

    explicit PartsModel(QObject *parent = nullptr);

    // A new part list (model reset); sizes other than component_count mean 1 / visible.
    void set_model(const oit_model *model, const std::vector<float> &alpha, const std::vector<char> &visible);
    // New values for the same parts: dataChanged only. Same size rule as set_model.
    void set_values(const std::vector<float> &alpha, const std::vector<char> &visible);
    // Change one or every part; true if anything changed. They emit dataChanged, not edited().
    bool set_alpha(int part, float alpha);
    bool set_visible(int part, bool visible);
    bool set_all(const std::vector<float> &alpha, const std::vector<char> &visible);

    const std::vector<float> &alpha() const { return alpha_; }
    const std::vector<char> &visible() const { return visible_; }
    QString name(int part) const
    {
        const Part &p = parts_[size_t(part)];
        return QString::fromUtf8(names_.constData() + p.name_offset, int(p.name_length));
    }
    int part_count() const { return int(parts_.size()); }
    // the slider's value: alpha as an integer percent
    static int percent(float alpha);

    int rowCount(const QModelIndex &parent = QModelIndex()) const override;
    int columnCount(const QModelIndex &parent = QModelIndex()) const override;
    QVariant data(const QModelIndex &index, int role) const override;
    // CheckStateRole on PartColumn, AlphaRole on OpacityColumn: the user's edits (emit edited())
    bool setData(const QModelIndex &index, const QVariant &value, int role) override;
    Qt::ItemFlags flags(const QModelIndex &index) const override;
    QVariant headerData(int section, Qt::Orientation orientation, int role) const override;

signals:
    void edited(); // setData changed a value: the checkbox or the slider

private:
    struct Part {
        uint32_t name_offset, name_length; // in names_
        float colour[3];
        float material_opacity;
        uint32_t triangle_count;
    };
    void take_values(const std::vector<float> &alpha, const std::vector<char> &visible);
    void emit_rows_changed(int first, int last);
    QIcon swatch(const float colour[3]) const;

    std::vector<Part> parts_;
    QByteArray names_; // every part's name, UTF-8, one after the other
    mutable QHash<QRgb, QIcon> swatches_; // by colour, made when first shown
    std::vector<float> alpha_;
    std::vector<char> visible_;
};

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
    std::vector<int> selected_parts() const; // component indices, ascending
    void select_part(int index);             // select only it, make it current, scroll to it (clears a filter that hides it)
    QAbstractItemView *view() const;
    QLineEdit *filter() const;
    int shown_row_count() const; // rows after filtering

signals:
    void parts_changed(); // alpha()/visible() changed by the user (checkbox, slider, keys, Reset, Isolate, Show all)
    void frame_selected_requested(std::vector<int> parts);
    void selection_changed(std::vector<int> parts);

private:
    friend class PartsView;
    // the current row's opacity by delta percent (keys); true if it had a current row
    bool step_current_alpha(int delta_percent);
    bool toggle_current_visible();
    void apply(const std::vector<float> &alpha, const std::vector<char> &visible);
    void update_buttons();

    PartsModel *model_;
    QSortFilterProxyModel *proxy_;
    QLineEdit *filter_;
    QTreeView *view_;
    QLabel *note_;
    QPushButton *reset_, *isolate_, *show_all_, *frame_;
};
