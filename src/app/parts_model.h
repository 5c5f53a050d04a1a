// parts_model.h: the Parts tab's data (parts_panel.h shows it): every part's
// visibility and opacity, and the assembly tree when the model has one.
#pragma once

#include <QAbstractItemModel>
#include <QByteArray>
#include <QColor>
#include <QHash>
#include <QIcon>
#include <QString>

#include <vector>

#include "oit.h"

// The keyboard's opacity step, in percent, and the tooltip line that says how to change opacity.
constexpr int parts_alpha_step_percent = 5;
QString parts_opacity_help();

// The parts as a table, or as a tree when the model has assembly nodes: part
// (name, colour swatch, checkbox = visible), opacity (a slider, painted by the
// panel's delegate), percent. Without a tree, row == component index. A node's
// row shows its parts together: the check box partly checked when some are
// hidden, the slider at their mean opacity (MixedAlphaRole when they differ);
// setting either sets every part under it. It copies what it shows, so the
// oit_model need not outlive it. Rows are found through flat arrays built once
// (children per node, each item's parent and row), so nothing per row is made
// before the view asks for it.
class PartsModel : public QAbstractItemModel {
    Q_OBJECT
public:
    enum Column { PartColumn, OpacityColumn, PercentColumn, ColumnCount };
    // the row's alpha (float in [0, 1]; a node's: its parts' mean); settable on OpacityColumn
    static constexpr int AlphaRole = Qt::UserRole + 1;
    // on a node's OpacityColumn: true when its parts' opacities differ
    static constexpr int MixedAlphaRole = Qt::UserRole + 2;

    explicit PartsModel(QObject *parent = nullptr);

    // A new part list (model reset); sizes other than component_count mean 1 / visible.
    void set_model(const oit_model *model, const std::vector<float> &alpha, const std::vector<char> &visible);
    // New values for the same parts: dataChanged only. Same size rule as set_model.
    void set_values(const std::vector<float> &alpha, const std::vector<char> &visible);
    // Change one or every part; true if anything changed. They emit dataChanged, not edited().
    bool set_alpha(int part, float alpha);
    bool set_visible(int part, bool visible);
    bool set_all(const std::vector<float> &alpha, const std::vector<char> &visible);
    // Every part under a node (at any depth); true if anything changed. No edited().
    bool set_node_alpha(int node, float alpha);
    bool set_node_visible(int node, bool visible);

    const std::vector<float> &alpha() const { return alpha_; }
    const std::vector<char> &visible() const { return visible_; }
    QString name(int part) const { return text(parts_[size_t(part)].name_offset, parts_[size_t(part)].name_length); }
    int part_count() const { return int(parts_.size()); }
    // the slider's value: alpha as an integer percent
    static int percent(float alpha);

    // The tree (node_count() == 0: a flat list).
    int node_count() const { return int(nodes_.size()); }
    QString node_name(int node) const { return text(nodes_[size_t(node)].name_offset, nodes_[size_t(node)].name_length); }
    int part_node(int part) const;  // the node a part hangs under, -1 at the top
    int node_parent(int node) const; // -1 at the top
    // the parts under a node at any depth, appended in tree order
    void parts_under(int node, std::vector<int> &out) const;
    // a node's parts: how many, how many visible, their mean opacity, and whether they differ
    int node_part_count(int node) const { return int(nodes_[size_t(node)].part_count); }
    int node_visible_count(int node) const { return int(nodes_[size_t(node)].visible_count); }
    float node_alpha(int node) const;
    bool node_mixed_alpha(int node) const { return nodes_[size_t(node)].alpha_min != nodes_[size_t(node)].alpha_max; }
    // What a row (of this model) shows: a part, or a node (-1: not that kind / invalid).
    int part_at(const QModelIndex &index) const;
    int node_at(const QModelIndex &index) const;
    QModelIndex part_index(int part, int column = PartColumn) const;
    QModelIndex node_index(int node, int column = PartColumn) const;

    // The filter (case-insensitive substring of a name): a matching row shows
    // with its ancestors, and a matching node with everything under it.
    void set_filter(const QString &text);
    bool filter_shows(int row, const QModelIndex &parent) const;
    bool filter_shows_part(int part) const;

    QModelIndex index(int row, int column, const QModelIndex &parent = QModelIndex()) const override;
    QModelIndex parent(const QModelIndex &child) const override;
    int rowCount(const QModelIndex &parent = QModelIndex()) const override;
    int columnCount(const QModelIndex &parent = QModelIndex()) const override;
    bool hasChildren(const QModelIndex &parent = QModelIndex()) const override;
    QVariant data(const QModelIndex &index, int role) const override;
    QVariant node_name_data(int node, int role) const; // the part column of an assembly row
    QVariant part_name_data(int part, int role) const; // the part column of a part row
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
    struct Node {
        uint32_t name_offset, name_length; // in names_
        uint32_t parent;                   // OIT_NO_NODE at the top
        // its parts at any depth (recomputed after every change: one pass over the parts)
        uint32_t part_count, visible_count;
        float alpha_min, alpha_max;
        double alpha_sum;
    };
    // An item is a node (item < node_count) or a part (node_count + part);
    // a group is the top (0) or a node's children (node + 1).
    uint32_t item_count() const { return uint32_t(nodes_.size() + parts_.size()); }
    uint32_t item_of(const QModelIndex &index) const { return uint32_t(index.internalId()); }
    uint32_t group_of(const QModelIndex &parent) const; // UINT32_MAX: a part (no children)
    QModelIndex item_index(uint32_t item, int column) const;
    QString text(uint32_t offset, uint32_t length) const
    {
        return QString::fromUtf8(names_.constData() + offset, int(length));
    }
    void take_values(const std::vector<float> &alpha, const std::vector<char> &visible);
    void update_nodes(); // the nodes' counts and opacities from the parts'
    // dataChanged for these parts' rows (dirty: per part) and their ancestors', one per span of siblings
    void emit_parts_changed(const std::vector<char> &dirty);
    // after a change to parts' values: the nodes updated and the rows signalled, if any changed
    bool commit_parts(const std::vector<char> &dirty, bool changed);
    void emit_part_changed(int part);
    QIcon swatch(const float colour[3]) const;

    std::vector<Part> parts_;
    std::vector<Node> nodes_;
    QByteArray names_; // every part's and node's name, UTF-8, one after the other
    std::vector<uint32_t> group_first_; // per group + 1: where its children start in children_
    std::vector<uint32_t> children_;    // items, group by group: nodes first, then parts, each in index order
    std::vector<uint32_t> item_row_;    // per item: its row among its siblings
    std::vector<uint32_t> item_parent_; // per item: its node, OIT_NO_NODE at the top
    std::vector<char> filter_shown_;    // per item, while a filter is set
    QString filter_text_;
    bool filtering_ = false;
    mutable QHash<QRgb, QIcon> swatches_; // by colour, made when first shown
    std::vector<float> alpha_;
    std::vector<char> visible_;
};
