// parts_model.cpp: the Parts tab's data (parts_model.h): the rows, found through
// flat arrays built once, so 10,000 parts cost only the rows the view asks for.
#include "parts_model.h"

#include <QApplication>
#include <QHBoxLayout>
#include <QHash>
#include <QHeaderView>
#include <QIcon>
#include <QItemSelectionModel>
#include <QKeyEvent>
#include <QLabel>
#include <QLineEdit>
#include <QMouseEvent>
#include <QPainter>
#include <QPixmap>
#include <QPushButton>
#include <QSortFilterProxyModel>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QStyledItemDelegate>
#include <QTreeView>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace {

float clamp_alpha(float alpha)
{
    if (!(alpha >= 0.0f)) // also NaN
        return 0.0f;
    return std::min(alpha, 1.0f);
}

QString number(double value) { return QString::number(value, 'g', 6); }

} // namespace

QString parts_opacity_help()
{
    return QStringLiteral("click or drag the slider; +/- or Left/Right: %1% steps on the current row")
        .arg(parts_alpha_step_percent);
}

// ------------------------------------------------------------------ PartsModel

PartsModel::PartsModel(QObject *parent) : QAbstractItemModel(parent) {}

int PartsModel::percent(float alpha) { return int(std::lround(double(clamp_alpha(alpha)) * 100.0)); }

void PartsModel::set_model(const oit_model *model, const std::vector<float> &alpha,
                           const std::vector<char> &visible)
{
    beginResetModel();
    parts_.clear();
    nodes_.clear();
    names_.clear();
    swatches_.clear();
    const size_t count = model && model->components ? model->component_count : 0;
    // a tree only when every part's node is known (component_node NULL: the file has none)
    const size_t node_count = count && model->nodes && model->component_node ? model->node_count : 0;
    parts_.reserve(count);
    nodes_.reserve(node_count);
    // the names' bytes in one block, a QString made when a row is shown or
    // filtered: at 100,000 parts one string each kept the GUI thread 3 times longer
    size_t bytes = 0;
    for (size_t i = 0; i < count; ++i)
        bytes += strnlen(model->components[i].name, sizeof model->components[i].name);
    for (size_t n = 0; n < node_count; ++n)
        bytes += strnlen(model->nodes[n].name, sizeof model->nodes[n].name);
    names_.reserve(int(bytes));
    for (size_t n = 0; n < node_count; ++n) {
        const oit_model_node &source = model->nodes[n];
        Node node{};
        node.name_offset = uint32_t(names_.size());
        node.name_length = uint32_t(strnlen(source.name, sizeof source.name));
        names_.append(source.name, int(node.name_length));
        // oit_model_finish checked parents come first; a model that was not finished falls to the top
        node.parent = source.parent < n ? source.parent : OIT_NO_NODE;
        nodes_.push_back(node);
    }
    for (size_t i = 0; i < count; ++i) {
        const oit_component &c = model->components[i];
        Part part;
        part.name_offset = uint32_t(names_.size());
        part.name_length = uint32_t(strnlen(c.name, sizeof c.name));
        names_.append(c.name, int(part.name_length));
        std::copy(c.colour, c.colour + 3, part.colour);
        part.material_opacity = c.opacity;
        part.triangle_count = c.triangle_count;
        parts_.push_back(part);
    }

    // children per group (a counting sort: nodes first, then parts, each in index order)
    const uint32_t items = item_count();
    auto parent_group = [&](uint32_t item) -> uint32_t {
        uint32_t parent = OIT_NO_NODE;
        if (item < node_count)
            parent = nodes_[item].parent;
        else if (node_count)
            parent = model->component_node[item - node_count];
        return parent < node_count ? parent + 1 : 0;
    };
    group_first_.assign(node_count + 2, 0);
    for (uint32_t item = 0; item < items; ++item)
        ++group_first_[parent_group(item) + 1];
    for (size_t g = 1; g < group_first_.size(); ++g)
        group_first_[g] += group_first_[g - 1];
    children_.resize(items);
    item_row_.resize(items);
    item_parent_.resize(items);
    std::vector<uint32_t> next(group_first_.begin(), group_first_.end() - 1);
    for (uint32_t item = 0; item < items; ++item) {
        const uint32_t group = parent_group(item);
        item_parent_[item] = group ? group - 1 : OIT_NO_NODE;
        item_row_[item] = next[group] - group_first_[group];
        children_[next[group]++] = item;
    }
    take_values(alpha, visible);
    set_filter(filter_text_); // the filter field keeps its text across models
    endResetModel();
}

void PartsModel::take_values(const std::vector<float> &alpha, const std::vector<char> &visible)
{
    const size_t count = parts_.size();
    if (alpha.size() == count && visible.size() == count) {
        alpha_.resize(count);
        std::transform(alpha.begin(), alpha.end(), alpha_.begin(), clamp_alpha);
        visible_.resize(count);
        std::transform(visible.begin(), visible.end(), visible_.begin(), [](char v) { return char(v != 0); });
    } else {
        alpha_.assign(count, 1.0f);
        visible_.assign(count, 1);
    }
    update_nodes();
}

void PartsModel::update_nodes()
{
    if (nodes_.empty())
        return;
    for (Node &node : nodes_) {
        node.part_count = node.visible_count = 0;
        node.alpha_min = 1.0f;
        node.alpha_max = 0.0f;
        node.alpha_sum = 0.0;
    }
    const uint32_t node_count = uint32_t(nodes_.size());
    for (size_t part = 0; part < parts_.size(); ++part) {
        const int node = part_node(int(part));
        if (node < 0)
            continue;
        Node &n = nodes_[size_t(node)];
        ++n.part_count;
        n.visible_count += visible_[part] ? 1 : 0;
        n.alpha_min = std::min(n.alpha_min, alpha_[part]);
        n.alpha_max = std::max(n.alpha_max, alpha_[part]);
        n.alpha_sum += double(alpha_[part]);
    }
    // children before parents: backwards, since parents come first
    for (uint32_t node = node_count; node-- > 0;) {
        const Node &n = nodes_[node];
        if (n.parent == OIT_NO_NODE || n.part_count == 0)
            continue;
        Node &p = nodes_[n.parent];
        p.part_count += n.part_count;
        p.visible_count += n.visible_count;
        p.alpha_min = std::min(p.alpha_min, n.alpha_min);
        p.alpha_max = std::max(p.alpha_max, n.alpha_max);
        p.alpha_sum += n.alpha_sum;
    }
    for (Node &node : nodes_)
        if (node.part_count == 0) // nothing under it: shown as visible at full opacity
            node.alpha_min = node.alpha_max = 1.0f;
}

int PartsModel::part_node(int part) const
{
    if (part < 0 || part >= part_count())
        return -1;
    const uint32_t parent = item_parent_[nodes_.size() + size_t(part)];
    return parent == OIT_NO_NODE ? -1 : int(parent);
}

int PartsModel::node_parent(int node) const
{
    if (node < 0 || node >= node_count() || nodes_[size_t(node)].parent == OIT_NO_NODE)
        return -1;
    return int(nodes_[size_t(node)].parent);
}

void PartsModel::parts_under(int node, std::vector<int> &out) const
{
    if (node < 0 || node >= node_count())
        return;
    // depth first through the children arrays, without recursion (trees can be deep)
    std::vector<uint32_t> stack{uint32_t(node)};
    const uint32_t node_count = uint32_t(nodes_.size());
    while (!stack.empty()) {
        const uint32_t group = stack.back() + 1;
        stack.pop_back();
        // its child nodes come first: push them in reverse, take its parts now
        const uint32_t first = group_first_[group], end = group_first_[group + 1];
        uint32_t k = first;
        while (k < end && children_[k] < node_count)
            ++k;
        for (uint32_t j = k; j-- > first;)
            stack.push_back(children_[j]);
        for (; k < end; ++k)
            out.push_back(int(children_[k] - node_count));
    }
}

float PartsModel::node_alpha(int node) const
{
    const Node &n = nodes_[size_t(node)];
    if (n.part_count == 0)
        return 1.0f;
    return n.alpha_min == n.alpha_max ? n.alpha_min : clamp_alpha(float(n.alpha_sum / double(n.part_count)));
}

int PartsModel::part_at(const QModelIndex &index) const
{
    if (!index.isValid() || index.model() != this)
        return -1;
    const uint32_t item = item_of(index);
    return item >= nodes_.size() && item < item_count() ? int(item - nodes_.size()) : -1;
}

int PartsModel::node_at(const QModelIndex &index) const
{
    if (!index.isValid() || index.model() != this)
        return -1;
    const uint32_t item = item_of(index);
    return item < nodes_.size() ? int(item) : -1;
}

QModelIndex PartsModel::item_index(uint32_t item, int column) const
{
    if (item >= item_count() || column < 0 || column >= ColumnCount)
        return {};
    return createIndex(int(item_row_[item]), column, quintptr(item));
}

QModelIndex PartsModel::part_index(int part, int column) const
{
    if (part < 0 || part >= part_count())
        return {};
    return item_index(uint32_t(nodes_.size() + size_t(part)), column);
}

QModelIndex PartsModel::node_index(int node, int column) const
{
    if (node < 0 || node >= node_count())
        return {};
    return item_index(uint32_t(node), column);
}

uint32_t PartsModel::group_of(const QModelIndex &parent) const
{
    if (!parent.isValid())
        return 0;
    const uint32_t item = item_of(parent);
    return item < nodes_.size() ? item + 1 : UINT32_MAX;
}

QModelIndex PartsModel::index(int row, int column, const QModelIndex &parent) const
{
    if (row < 0 || column < 0 || column >= ColumnCount || (parent.isValid() && parent.column() != 0))
        return {};
    const uint32_t group = group_of(parent);
    if (group == UINT32_MAX || group + 1 >= group_first_.size())
        return {};
    const uint32_t first = group_first_[group];
    if (uint32_t(row) >= group_first_[group + 1] - first)
        return {};
    return createIndex(row, column, quintptr(children_[first + uint32_t(row)]));
}

QModelIndex PartsModel::parent(const QModelIndex &child) const
{
    if (!child.isValid() || item_of(child) >= item_count())
        return {};
    const uint32_t parent = item_parent_[item_of(child)];
    return parent == OIT_NO_NODE ? QModelIndex() : item_index(parent, 0);
}

int PartsModel::rowCount(const QModelIndex &parent) const
{
    if (parent.isValid() && parent.column() != 0)
        return 0;
    const uint32_t group = group_of(parent);
    if (group == UINT32_MAX || group + 1 >= group_first_.size())
        return 0;
    return int(group_first_[group + 1] - group_first_[group]);
}

int PartsModel::columnCount(const QModelIndex &parent) const
{
    return group_of(parent) == UINT32_MAX ? 0 : ColumnCount;
}

bool PartsModel::hasChildren(const QModelIndex &parent) const { return rowCount(parent) > 0; }

void PartsModel::set_values(const std::vector<float> &alpha, const std::vector<char> &visible)
{
    // dataChanged for the rows that changed only: a load sets the values it
    // has just shown, and 100,000 rows through the filter cost the GUI thread
    const std::vector<float> old_alpha = alpha_;
    const std::vector<char> old_visible = visible_;
    take_values(alpha, visible);
    std::vector<char> dirty(parts_.size(), 0);
    for (size_t part = 0; part < parts_.size(); ++part)
        dirty[part] = alpha_[part] != old_alpha[part] || visible_[part] != old_visible[part];
    emit_parts_changed(dirty);
}

bool PartsModel::set_alpha(int part, float alpha)
{
    if (part < 0 || part >= part_count())
        return false;
    alpha = clamp_alpha(alpha);
    if (alpha_[size_t(part)] == alpha)
        return false;
    alpha_[size_t(part)] = alpha;
    update_nodes();
    emit_part_changed(part);
    return true;
}

bool PartsModel::set_visible(int part, bool visible)
{
    if (part < 0 || part >= part_count() || bool(visible_[size_t(part)]) == visible)
        return false;
    visible_[size_t(part)] = visible;
    update_nodes();
    emit_part_changed(part);
    return true;
}

bool PartsModel::set_all(const std::vector<float> &alpha, const std::vector<char> &visible)
{
    if (alpha.size() != parts_.size() || visible.size() != parts_.size())
        return false;
    std::vector<char> dirty(parts_.size(), 0);
    bool changed = false;
    for (size_t i = 0; i < parts_.size(); ++i) {
        const float a = clamp_alpha(alpha[i]);
        const char v = visible[i] != 0;
        if (alpha_[i] == a && visible_[i] == v)
            continue;
        alpha_[i] = a;
        visible_[i] = v;
        dirty[i] = changed = true;
    }
    return commit_parts(dirty, changed);
}

bool PartsModel::set_node_alpha(int node, float alpha)
{
    std::vector<int> parts;
    parts_under(node, parts);
    alpha = clamp_alpha(alpha);
    std::vector<char> dirty(parts_.size(), 0);
    bool changed = false;
    for (int part : parts)
        if (alpha_[size_t(part)] != alpha) {
            alpha_[size_t(part)] = alpha;
            dirty[size_t(part)] = changed = true;
        }
    return commit_parts(dirty, changed);
}

bool PartsModel::set_node_visible(int node, bool visible)
{
    std::vector<int> parts;
    parts_under(node, parts);
    std::vector<char> dirty(parts_.size(), 0);
    bool changed = false;
    for (int part : parts)
        if (bool(visible_[size_t(part)]) != visible) {
            visible_[size_t(part)] = visible;
            dirty[size_t(part)] = changed = true;
        }
    return commit_parts(dirty, changed);
}

void PartsModel::emit_part_changed(int part)
{
    // the row and its ancestors' (their check box and slider sum it up)
    uint32_t item = uint32_t(nodes_.size() + size_t(part));
    while (item != OIT_NO_NODE) {
        emit dataChanged(item_index(item, 0), item_index(item, ColumnCount - 1));
        item = item_parent_[item];
    }
}

bool PartsModel::commit_parts(const std::vector<char> &dirty, bool changed)
{
    if (!changed)
        return false;
    update_nodes();
    emit_parts_changed(dirty);
    return true;
}

void PartsModel::emit_parts_changed(const std::vector<char> &dirty)
{
    // the dirty items: the parts, then their ancestors (parents come first, so backwards)
    const size_t node_count = nodes_.size();
    std::vector<char> item_dirty(item_count(), 0);
    bool any = false;
    for (size_t part = 0; part < dirty.size() && part < parts_.size(); ++part)
        if (dirty[part]) {
            item_dirty[node_count + part] = any = true;
            const uint32_t parent = item_parent_[node_count + part];
            if (parent != OIT_NO_NODE)
                item_dirty[parent] = 1;
        }
    if (!any)
        return;
    for (size_t node = node_count; node-- > 0;)
        if (item_dirty[node] && nodes_[node].parent != OIT_NO_NODE)
            item_dirty[nodes_[node].parent] = 1;
    // one dataChanged per group over its dirty rows' span, not one per row
    for (size_t group = 0; group + 1 < group_first_.size(); ++group) {
        if (group > 0 && !item_dirty[group - 1])
            continue; // nothing under a clean node changed
        int first = -1, last = -1;
        for (uint32_t k = group_first_[group]; k < group_first_[group + 1]; ++k)
            if (item_dirty[children_[k]]) {
                const int row = int(k - group_first_[group]);
                if (first < 0)
                    first = row;
                last = row;
            }
        if (first < 0)
            continue;
        const QModelIndex parent = group ? item_index(uint32_t(group - 1), 0) : QModelIndex();
        emit dataChanged(index(first, 0, parent), index(last, ColumnCount - 1, parent));
    }
}

void PartsModel::set_filter(const QString &text)
{
    filter_text_ = text;
    filtering_ = !text.isEmpty();
    if (!filtering_) {
        filter_shown_.clear();
        return;
    }
    const size_t node_count = nodes_.size();
    const uint32_t items = item_count();
    // 1: its own name matches or an ancestor's does (shows everything under a matching node)
    // 2: something under it matches (shows the way down to a match)
    std::vector<char> state(items, 0);
    for (uint32_t item = 0; item < items; ++item) {
        const QString name = item < node_count ? node_name(int(item)) : this->name(int(item - node_count));
        const uint32_t parent = item_parent_[item];
        // parents come first among the nodes, and every node before every part
        if (name.contains(text, Qt::CaseInsensitive) || (parent != OIT_NO_NODE && (state[parent] & 1)))
            state[item] |= 1;
    }
    for (uint32_t item = items; item-- > 0;) {
        const uint32_t parent = item_parent_[item];
        if (parent != OIT_NO_NODE && (state[item] & 3))
            state[parent] |= 2;
    }
    filter_shown_.assign(items, 0);
    for (uint32_t item = 0; item < items; ++item)
        filter_shown_[item] = state[item] != 0;
}

bool PartsModel::filter_shows(int row, const QModelIndex &parent) const
{
    if (!filtering_)
        return true;
    const QModelIndex child = index(row, 0, parent);
    return child.isValid() && filter_shown_[item_of(child)];
}

bool PartsModel::filter_shows_part(int part) const
{
    return !filtering_ || (part >= 0 && part < part_count() && filter_shown_[nodes_.size() + size_t(part)]);
}

QIcon PartsModel::swatch(const float colour[3]) const
{
    QColor fill = QColor::fromRgbF(qBound(0.0, double(colour[0]), 1.0), qBound(0.0, double(colour[1]), 1.0),
                                   qBound(0.0, double(colour[2]), 1.0));
    // parts share few colours: one icon per colour, made when first shown
    auto found = swatches_.constFind(fill.rgb());
    if (found != swatches_.constEnd())
        return *found;
    QPixmap pixmap(14, 14);
    pixmap.fill(fill);
    QPainter painter(&pixmap);
    painter.setPen(Qt::black);
    painter.drawRect(0, 0, 13, 13);
    painter.end();
    QIcon icon(pixmap);
    swatches_.insert(fill.rgb(), icon);
    return icon;
}

QVariant PartsModel::data(const QModelIndex &index, int role) const
{
    if (!index.isValid() || item_of(index) >= item_count())
        return {};
    const int node = node_at(index), part = node >= 0 ? -1 : part_at(index);
    if (index.column() == PartColumn)
        return node >= 0 ? node_name_data(node, role) : part_name_data(part, role);
    // the opacity columns, alike for a part and an assembly (whose parts may differ: a range)
    const Node *n = node >= 0 ? &nodes_[size_t(node)] : nullptr;
    const bool mixed = n && node_mixed_alpha(node);
    // built only when asked for: painting asks each cell for a dozen roles
    auto opacity_text = [&] {
        return mixed ? QStringLiteral("%1-%2%").arg(percent(n->alpha_min)).arg(percent(n->alpha_max))
                     : QStringLiteral("%1%").arg(percent(n ? n->alpha_min : alpha_[size_t(part)]));
    };
    auto opacity_tip = [&] {
        return n ? QStringLiteral("opacity of every part under %1: %2 (%3)")
                       .arg(node_name(node), opacity_text(), parts_opacity_help())
                 : QStringLiteral("opacity of %1: %2 (%3)").arg(name(part), opacity_text(), parts_opacity_help());
    };
    switch (role) {
    case AlphaRole:
        return index.column() == OpacityColumn ? QVariant(double(n ? node_alpha(node) : alpha_[size_t(part)]))
                                               : QVariant();
    case MixedAlphaRole:
        return index.column() == OpacityColumn ? QVariant(mixed) : QVariant();
    case Qt::ToolTipRole:
        return opacity_tip();
    case Qt::AccessibleTextRole:
        return index.column() == OpacityColumn ? QVariant(opacity_text()) : QVariant();
    case Qt::DisplayRole:
        return index.column() == PercentColumn ? QVariant(opacity_text()) : QVariant();
    case Qt::TextAlignmentRole:
        return index.column() == PercentColumn ? QVariant(int(Qt::AlignRight | Qt::AlignVCenter)) : QVariant();
    }
    return {};
}

QVariant PartsModel::node_name_data(int node, int role) const
{
    const Node &n = nodes_[size_t(node)];
    switch (role) {
    case Qt::DisplayRole:
        return node_name(node);
    case Qt::CheckStateRole:
        return n.visible_count == n.part_count ? Qt::Checked
               : n.visible_count == 0         ? Qt::Unchecked
                                              : Qt::PartiallyChecked;
    case Qt::ToolTipRole:
        return node_name(node) + QStringLiteral(": an assembly of ") + QString::number(n.part_count) +
               QStringLiteral(" parts, ") + QString::number(n.visible_count) +
               QStringLiteral(" visible; its check box and slider set every part under it");
    }
    return {};
}

QVariant PartsModel::part_name_data(int part, int role) const
{
    const Part &p = parts_[size_t(part)];
    switch (role) {
    case Qt::DisplayRole:
        return name(part);
    case Qt::DecorationRole:
        return swatch(p.colour);
    case Qt::CheckStateRole:
        return visible_[size_t(part)] ? Qt::Checked : Qt::Unchecked;
    case Qt::ToolTipRole:
        // concatenated, not arg()-chained: a '%1' in a part's name stays as it is
        return name(part) + QStringLiteral(": colour ") + number(double(p.colour[0])) + ',' +
               number(double(p.colour[1])) + ',' + number(double(p.colour[2])) +
               QStringLiteral(", material opacity ") + number(double(p.material_opacity)) + QStringLiteral(", ") +
               QString::number(p.triangle_count) + QStringLiteral(" triangles");
    }
    return {};
}

bool PartsModel::setData(const QModelIndex &index, const QVariant &value, int role)
{
    if (!index.isValid() || item_of(index) >= item_count())
        return false;
    const int node = node_at(index), part = part_at(index);
    bool changed = false;
    if (index.column() == PartColumn && role == Qt::CheckStateRole) {
        const bool visible = value.toInt() == Qt::Checked;
        changed = node >= 0 ? set_node_visible(node, visible) : set_visible(part, visible);
    } else if (index.column() == OpacityColumn && role == AlphaRole) {
        const float alpha = float(value.toDouble());
        changed = node >= 0 ? set_node_alpha(node, alpha) : set_alpha(part, alpha);
    } else {
        return false;
    }
    if (changed)
        emit edited();
    return true;
}

Qt::ItemFlags PartsModel::flags(const QModelIndex &index) const
{
    if (!index.isValid())
        return Qt::NoItemFlags;
    Qt::ItemFlags flags = Qt::ItemIsEnabled | Qt::ItemIsSelectable;
    // ItemNeverHasChildren spares the tree view a hasChildren() per row
    if (part_at(index) >= 0)
        flags |= Qt::ItemNeverHasChildren;
    if (index.column() == PartColumn)
        flags |= Qt::ItemIsUserCheckable;
    return flags;
}

QVariant PartsModel::headerData(int section, Qt::Orientation orientation, int role) const
{
    if (orientation != Qt::Horizontal)
        return {};
    if (role == Qt::DisplayRole) {
        switch (section) {
        case PartColumn:
            return QStringLiteral("part");
        case OpacityColumn:
            return QStringLiteral("opacity");
        default:
            return QString();
        }
    }
    if (role == Qt::ToolTipRole) {
        switch (section) {
        case PartColumn:
            return QStringLiteral("the part's name and material colour; checkbox: visible");
        case OpacityColumn:
            return QStringLiteral("the part's opacity multiplier (--component-alpha): ") + parts_opacity_help();
        case PercentColumn:
            return QStringLiteral("the part's opacity multiplier in percent");
        }
    }
    return {};
}
