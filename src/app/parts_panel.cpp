// parts_panel.cpp: the Parts tab (parts_panel.h). Everything per row is data in
// PartsModel and painting in delegates, so 10,000 parts cost only the rows on
// screen: no widget per row, uniform row heights, filtering in a proxy.
#include "parts_panel.h"

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

const int alpha_step_percent = 5; // keyboard step

float clamp_alpha(float alpha)
{
    if (!(alpha >= 0.0f)) // also NaN
        return 0.0f;
    return std::min(alpha, 1.0f);
}

QString number(double value) { return QString::number(value, 'g', 6); }

QString opacity_help()
{
    return QStringLiteral("click or drag the slider; +/- or Left/Right: %1% steps on the current row")
        .arg(alpha_step_percent);
}

} // namespace

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
    const int node = node_at(index);
    if (node >= 0) {
        const Node &n = nodes_[size_t(node)];
        const bool mixed = node_mixed_alpha(node);
        auto opacity_text = [&] {
            return mixed ? QStringLiteral("%1-%2%").arg(percent(n.alpha_min)).arg(percent(n.alpha_max))
                         : QStringLiteral("%1%").arg(percent(n.alpha_min));
        };
        auto opacity_tip = [&] {
            return QStringLiteral("opacity of every part under %1: %2 (%3)")
                .arg(node_name(node), opacity_text(), opacity_help());
        };
        switch (index.column()) {
        case PartColumn:
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
            break;
        case OpacityColumn:
            switch (role) {
            case AlphaRole:
                return double(node_alpha(node));
            case MixedAlphaRole:
                return mixed;
            case Qt::ToolTipRole:
                return opacity_tip();
            case Qt::AccessibleTextRole:
                return opacity_text();
            }
            break;
        case PercentColumn:
            switch (role) {
            case Qt::DisplayRole:
                return opacity_text();
            case Qt::TextAlignmentRole:
                return int(Qt::AlignRight | Qt::AlignVCenter);
            case Qt::ToolTipRole:
                return opacity_tip();
            }
            break;
        }
        return {};
    }
    const size_t row = size_t(part_at(index));
    const Part &part = parts_[row];
    auto part_name = [&] { return name(int(row)); };
    const int pct = percent(alpha_[row]);
    // built only when asked for: painting asks each cell for a dozen roles
    auto opacity_tip = [&] {
        return QStringLiteral("opacity of %1: %2% (%3)").arg(part_name(), QString::number(pct), opacity_help());
    };
    switch (index.column()) {
    case PartColumn:
        switch (role) {
        case Qt::DisplayRole:
            return part_name();
        case Qt::DecorationRole:
            return swatch(part.colour);
        case Qt::CheckStateRole:
            return visible_[row] ? Qt::Checked : Qt::Unchecked;
        case Qt::ToolTipRole:
            // concatenated, not arg()-chained: a '%1' in a part's name stays as it is
            return part_name() + QStringLiteral(": colour ") + number(double(part.colour[0])) + ',' +
                   number(double(part.colour[1])) + ',' + number(double(part.colour[2])) +
                   QStringLiteral(", material opacity ") + number(double(part.material_opacity)) +
                   QStringLiteral(", ") + QString::number(part.triangle_count) + QStringLiteral(" triangles");
        }
        break;
    case OpacityColumn:
        switch (role) {
        case AlphaRole:
            return double(alpha_[row]);
        case MixedAlphaRole:
            return false;
        case Qt::ToolTipRole:
            return opacity_tip();
        case Qt::AccessibleTextRole:
            return QStringLiteral("%1%").arg(pct);
        }
        break;
    case PercentColumn:
        switch (role) {
        case Qt::DisplayRole:
            return QStringLiteral("%1%").arg(pct);
        case Qt::TextAlignmentRole:
            return int(Qt::AlignRight | Qt::AlignVCenter);
        case Qt::ToolTipRole:
            return opacity_tip();
        }
        break;
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
            return QStringLiteral("the part's opacity multiplier (--component-alpha): ") + opacity_help();
        case PercentColumn:
            return QStringLiteral("the part's opacity multiplier in percent");
        }
    }
    return {};
}

// --------------------------------------------------------- the opacity slider

namespace {

// Paints the opacity column as a slider (QStyle's CC_Slider on the cell) and
// edits it by mouse: a press sets the value under the pointer (editorEvent),
// and the drag that follows is followed through the viewport's events, since
// the view hands a delegate only the cell under the pointer, and not at all
// once the pointer leaves the rows.
class OpacityDelegate : public QStyledItemDelegate {
public:
    explicit OpacityDelegate(QAbstractItemView *view)
        : QStyledItemDelegate(view), view_(view), viewport_(view->viewport())
    {
        viewport_->installEventFilter(this);
    }

    void paint(QPainter *painter, const QStyleOptionViewItem &option, const QModelIndex &index) const override
    {
        QStyleOptionViewItem cell = option;
        initStyleOption(&cell, index);
        QStyle *style = this->style(option);
        // the cell's background, selection and focus as in the other columns
        style->drawControl(QStyle::CE_ItemViewItem, &cell, painter, option.widget);
        const QStyleOptionSlider slider = slider_option(option, index);
        style->drawComplexControl(QStyle::CC_Slider, &slider, painter, option.widget);
    }

    QSize sizeHint(const QStyleOptionViewItem &option, const QModelIndex &) const override
    {
        return QSize(120, style(option)->pixelMetric(QStyle::PM_SliderThickness, nullptr, option.widget) + 2);
    }

    bool editorEvent(QEvent *event, QAbstractItemModel *model, const QStyleOptionViewItem &option,
                     const QModelIndex &index) override
    {
        if (event->type() != QEvent::MouseButtonPress && event->type() != QEvent::MouseButtonDblClick)
            return false;
        auto *mouse = static_cast<QMouseEvent *>(event);
        if (mouse->button() != Qt::LeftButton)
            return false;
        dragging_ = index;
        // the touched row becomes current (for the keys) without changing the selection
        if (view_->selectionModel())
            view_->selectionModel()->setCurrentIndex(index, QItemSelectionModel::NoUpdate);
        set_from(model, index, option, mouse->pos().x());
        return true; // consumed: no selection change, no drag-select
    }

protected:
    bool eventFilter(QObject *watched, QEvent *event) override
    {
        // compared with the pointer kept, not view_->viewport(): the viewport also sends
        // events while the view is being destroyed, when view_ is no longer a view
        if (!dragging_.isValid() || watched != viewport_)
            return false;
        if (event->type() != QEvent::MouseMove && event->type() != QEvent::MouseButtonRelease)
            return false;
        auto *mouse = static_cast<QMouseEvent *>(event);
        const QModelIndex index = dragging_;
        if (event->type() == QEvent::MouseButtonRelease || !(mouse->buttons() & Qt::LeftButton)) {
            // release (or a move after a release we did not see): the drag ends here
            dragging_ = QPersistentModelIndex();
            view_->viewport()->update(view_->visualRect(index));
            return event->type() == QEvent::MouseButtonRelease;
        }
        QStyleOptionViewItem option;
        option.initFrom(view_->viewport());
        option.widget = view_;
        option.rect = view_->visualRect(index);
        set_from(view_->model(), index, option, mouse->pos().x());
        return true;
    }

private:
    QStyle *style(const QStyleOptionViewItem &option) const
    {
        return option.widget ? option.widget->style() : QApplication::style();
    }

    QStyleOptionSlider slider_option(const QStyleOptionViewItem &option, const QModelIndex &index) const
    {
        QStyleOptionSlider slider;
        slider.rect = option.rect.adjusted(4, 0, -4, 0);
        slider.palette = option.palette;
        slider.direction = option.direction;
        slider.fontMetrics = option.fontMetrics;
        slider.state = (option.state & (QStyle::State_Enabled | QStyle::State_Active)) | QStyle::State_Horizontal;
        slider.orientation = Qt::Horizontal;
        slider.minimum = 0;
        slider.maximum = 100;
        slider.singleStep = 1;
        slider.pageStep = alpha_step_percent;
        slider.sliderPosition = slider.sliderValue = PartsModel::percent(float(index.data(PartsModel::AlphaRole).toDouble()));
        slider.upsideDown = option.direction == Qt::RightToLeft; // as QSlider does
        slider.subControls = QStyle::SC_SliderGroove | QStyle::SC_SliderHandle;
        if (dragging_.isValid() && dragging_ == index) {
            slider.activeSubControls = QStyle::SC_SliderHandle;
            slider.state |= QStyle::State_Sunken;
        }
        return slider;
    }

    // the percent under pixel column x, as QSlider maps a click (the handle centred on it)
    void set_from(QAbstractItemModel *model, const QModelIndex &index, const QStyleOptionViewItem &option, int x)
    {
        const QStyleOptionSlider slider = slider_option(option, index);
        QStyle *style = this->style(option);
        const QRect groove = style->subControlRect(QStyle::CC_Slider, &slider, QStyle::SC_SliderGroove, option.widget);
        const QRect handle = style->subControlRect(QStyle::CC_Slider, &slider, QStyle::SC_SliderHandle, option.widget);
        const int span = groove.width() - handle.width();
        const int value = QStyle::sliderValueFromPosition(slider.minimum, slider.maximum,
                                                          x - handle.width() / 2 - groove.x(), span, slider.upsideDown);
        model->setData(index, double(value) / 100.0, PartsModel::AlphaRole);
    }

    QAbstractItemView *view_;
    QWidget *viewport_;
    QPersistentModelIndex dragging_; // the row whose slider the mouse holds
};

// Case-insensitive substring match on the names, worked out by the model in
// one pass (PartsModel::set_filter: ancestors and subtrees of matches too).
class PartsFilter : public QSortFilterProxyModel {
public:
    PartsFilter(PartsModel *parts, QObject *parent) : QSortFilterProxyModel(parent), parts_(parts)
    {
        setSourceModel(parts);
        // names do not change while a model is shown: no re-filtering on value changes
        setDynamicSortFilter(false);
    }

    void set_text(const QString &text)
    {
        if (text == text_)
            return;
        text_ = text;
        parts_->set_filter(text);
        invalidateFilter();
    }

protected:
    bool filterAcceptsRow(int row, const QModelIndex &parent) const override
    {
        return parts_->filter_shows(row, parent);
    }

private:
    PartsModel *parts_;
    QString text_;
};

} // namespace

// ------------------------------------------------------------------ PartsView

// The list (a tree when the model has one), with the opacity keys and Space for
// the checkbox; Shift+Right / Shift+Left expand and collapse, since the plain
// arrows and +/- step the opacity.
class PartsView : public QTreeView {
public:
    explicit PartsView(PartsPanel *panel) : QTreeView(panel), panel_(panel) {}

    // select_part() on a hidden tab: the view has no real size yet, so scroll when shown
    bool scroll_when_shown = false;

protected:
    void keyPressEvent(QKeyEvent *event) override
    {
        const Qt::KeyboardModifiers modifiers = event->modifiers() & ~Qt::KeypadModifier;
        // '+' takes Shift on many layouts
        const bool plain = modifiers == Qt::NoModifier;
        bool handled = false;
        switch (event->key()) {
        case Qt::Key_Plus:
            handled = (plain || modifiers == Qt::ShiftModifier) && panel_->step_current_alpha(alpha_step_percent);
            break;
        case Qt::Key_Minus:
            handled = (plain || modifiers == Qt::ShiftModifier) && panel_->step_current_alpha(-alpha_step_percent);
            break;
        case Qt::Key_Right:
            handled = plain && panel_->step_current_alpha(alpha_step_percent);
            break;
        case Qt::Key_Left:
            handled = plain && panel_->step_current_alpha(-alpha_step_percent);
            break;
        case Qt::Key_Space:
            handled = plain && panel_->toggle_current_visible();
            break;
        case Qt::Key_Asterisk: // QTreeView's "expand everything under it": not an opacity key
            break;
        default:
            break;
        }
        if (!handled && modifiers == Qt::ShiftModifier &&
            (event->key() == Qt::Key_Right || event->key() == Qt::Key_Left) && currentIndex().isValid()) {
            // as QTreeView's plain Left/Right: expand, collapse, or up to the parent
            const QModelIndex current = currentIndex().siblingAtColumn(0);
            const bool expand = event->key() == Qt::Key_Right;
            if (expand && model()->hasChildren(current))
                setExpanded(current, true);
            else if (!expand && isExpanded(current))
                setExpanded(current, false);
            else if (!expand && current.parent().isValid())
                selectionModel()->setCurrentIndex(current.parent(),
                                                  QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
            handled = true;
        }
        if (handled)
            event->accept();
        else
            QTreeView::keyPressEvent(event);
    }

    void showEvent(QShowEvent *event) override
    {
        QTreeView::showEvent(event);
        if (scroll_when_shown && currentIndex().isValid())
            scrollTo(currentIndex());
        scroll_when_shown = false;
    }

private:
    PartsPanel *panel_;
};

// ------------------------------------------------------------------ PartsPanel

PartsPanel::PartsPanel(QWidget *parent) : QWidget(parent)
{
    // for queued connections and QSignalSpy
    qRegisterMetaType<std::vector<int>>("std::vector<int>");

    model_ = new PartsModel(this);
    auto *filter_model = new PartsFilter(model_, this);
    proxy_ = filter_model;

    auto *layout = new QVBoxLayout(this);
    filter_ = new QLineEdit;
    filter_->setObjectName("parts_filter");
    filter_->setPlaceholderText("filter parts by name");
    filter_->setClearButtonEnabled(true);
    filter_->setToolTip("show only the parts whose name contains this text (case-insensitive)");
    connect(filter_, &QLineEdit::textChanged, this, [this, filter_model](const QString &text) {
        filter_model->set_text(text);
        filter_changed();
    });
    layout->addWidget(filter_);

    auto *view = new PartsView(this);
    view_ = view;
    view_->setObjectName("parts_view");
    view_->setModel(proxy_);
    view_->setItemDelegateForColumn(PartsModel::OpacityColumn, new OpacityDelegate(view_));
    view_->setRootIsDecorated(false);
    view_->setItemsExpandable(false);
    view_->setUniformRowHeights(true); // row geometry without asking every row
    view_->setAllColumnsShowFocus(true);
    view_->setSelectionMode(QAbstractItemView::ExtendedSelection);
    view_->setSelectionBehavior(QAbstractItemView::SelectRows);
    view_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    view_->setToolTip("checkbox (or Space): show or hide the part; slider: its opacity (" + opacity_help() +
                      "); an assembly's check box and slider: every part under it (Shift+Right / Shift+Left "
                      "or its arrow: expand, collapse); Ctrl/Shift-click: select several; double-click a "
                      "part's name: frame it");
    QHeaderView *header = view_->header();
    header->setStretchLastSection(false);
    header->setSectionResizeMode(PartsModel::PartColumn, QHeaderView::Stretch);
    // fixed widths: ResizeToContents would measure rows on every layout
    header->setSectionResizeMode(PartsModel::OpacityColumn, QHeaderView::Fixed);
    header->resizeSection(PartsModel::OpacityColumn, 130);
    header->setSectionResizeMode(PartsModel::PercentColumn, QHeaderView::Fixed);
    header->resizeSection(PartsModel::PercentColumn, view_->fontMetrics().horizontalAdvance("100%") + 16);
    connect(view_, &QAbstractItemView::doubleClicked, this, [this](const QModelIndex &index) {
        // an assembly's row expands or collapses instead (QTreeView's own double-click)
        const int part = model_->part_at(proxy_->mapToSource(index));
        if (index.column() == PartsModel::PartColumn && part >= 0)
            emit frame_selected_requested({part});
    });
    connect(view_->selectionModel(), &QItemSelectionModel::selectionChanged, this, [this] {
        update_buttons();
        emit selection_changed(selected_parts());
    });
    connect(model_, &PartsModel::edited, this, &PartsPanel::parts_changed);
    layout->addWidget(view_, 1);

    note_ = new QLabel;
    note_->setWordWrap(true);
    note_->setToolTip("what the list holds, and which parts the per-part settings reach");
    layout->addWidget(note_);

    auto *buttons = new QHBoxLayout;
    auto button = [&](const char *name, const char *text, const char *tooltip) {
        auto *b = new QPushButton(text);
        b->setObjectName(name);
        b->setToolTip(tooltip);
        buttons->addWidget(b);
        return b;
    };
    reset_ = button("parts_reset", "Reset", "every part visible and at full opacity");
    isolate_ = button("parts_isolate", "Isolate selected", "show only the selected parts, hide every other one");
    show_all_ = button("parts_show_all", "Show all", "make every part visible (opacities stay)");
    frame_ = button("parts_frame", "Frame selected", "frame the camera on the selected parts");
    buttons->addStretch(1);
    layout->addLayout(buttons);
    connect(reset_, &QPushButton::clicked, this, [this] {
        apply(std::vector<float>(size_t(model_->part_count()), 1.0f), std::vector<char>(size_t(model_->part_count()), 1));
    });
    connect(isolate_, &QPushButton::clicked, this, [this] {
        const std::vector<int> selected = selected_parts();
        if (selected.empty())
            return;
        std::vector<char> visible(size_t(model_->part_count()), 0);
        for (int part : selected)
            visible[size_t(part)] = 1;
        apply(model_->alpha(), visible);
    });
    connect(show_all_, &QPushButton::clicked, this,
            [this] { apply(model_->alpha(), std::vector<char>(size_t(model_->part_count()), 1)); });
    connect(frame_, &QPushButton::clicked, this, [this] {
        std::vector<int> selected = selected_parts();
        if (!selected.empty())
            emit frame_selected_requested(std::move(selected));
    });

    set_model(nullptr, {}, {});
}

void PartsPanel::set_model(const oit_model *model, const std::vector<float> &alpha, const std::vector<char> &visible)
{
    // a reset clears the selection without selectionChanged: say so ourselves
    const bool had_selection = view_->selectionModel()->hasSelection();
    model_->set_model(model, alpha, visible);
    const int count = model_->part_count();
    const bool tree = model_->node_count() > 0;
    view_->setRootIsDecorated(tree);
    view_->setItemsExpandable(tree);
    // an assembly's percent can be a range ("20-100%")
    view_->header()->resizeSection(PartsModel::PercentColumn,
                                   view_->fontMetrics().horizontalAdvance(tree ? "100-100%" : "100%") + 16);
    if (tree) {
        // the top assemblies open: their subassemblies in sight, the rest on demand (a filter's matches: all)
        if (filter_->text().isEmpty())
            view_->expandToDepth(0);
        else
            view_->expandAll();
        note_->setText(QStringLiteral("%1 parts in %2 assemblies; checkbox: visible, slider: opacity "
                                      "(--component-alpha); an assembly's: every part under it.")
                           .arg(count)
                           .arg(model_->node_count()));
    } else {
        note_->setText(QStringLiteral("%1 parts; checkbox: visible, slider: opacity (--component-alpha).").arg(count));
    }
    update_buttons();
    if (had_selection)
        emit selection_changed({});
}

void PartsPanel::set_values(const std::vector<float> &alpha, const std::vector<char> &visible)
{
    model_->set_values(alpha, visible);
}

const std::vector<float> &PartsPanel::alpha() const { return model_->alpha(); }

const std::vector<char> &PartsPanel::visible() const { return model_->visible(); }

std::vector<int> PartsPanel::selected_parts() const
{
    std::vector<int> parts;
    const QModelIndexList rows = view_->selectionModel()->selectedRows(PartsModel::PartColumn);
    parts.reserve(size_t(rows.size()));
    bool nodes = false;
    for (const QModelIndex &index : rows) {
        const QModelIndex source = proxy_->mapToSource(index);
        const int part = model_->part_at(source);
        if (part >= 0) {
            parts.push_back(part);
        } else {
            // an assembly stands for every part under it, shown by the filter or not
            model_->parts_under(model_->node_at(source), parts);
            nodes = true;
        }
    }
    std::sort(parts.begin(), parts.end());
    if (nodes) // a part and its assembly both selected
        parts.erase(std::unique(parts.begin(), parts.end()), parts.end());
    return parts;
}

void PartsPanel::select_part(int index)
{
    if (index < 0 || index >= model_->part_count())
        return;
    if (!model_->filter_shows_part(index))
        filter_->clear();
    const QModelIndex row = proxy_->mapFromSource(model_->part_index(index));
    // its assemblies open, top first (a new current row opens them too, through the view's
    // autoScroll and QTreeView::scrollTo, but only while the view is not in a drag or an edit)
    std::vector<QModelIndex> ancestors;
    for (QModelIndex parent = row.parent(); parent.isValid(); parent = parent.parent())
        ancestors.push_back(parent);
    for (auto it = ancestors.rbegin(); it != ancestors.rend(); ++it)
        view_->expand(*it);
    view_->selectionModel()->setCurrentIndex(row, QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
    view_->scrollTo(row);
    static_cast<PartsView *>(view_)->scroll_when_shown = !view_->isVisible();
}

QAbstractItemView *PartsPanel::view() const { return view_; }

QLineEdit *PartsPanel::filter() const { return filter_; }

int PartsPanel::shown_row_count() const { return proxy_->rowCount(); }

bool PartsPanel::step_current_alpha(int delta_percent)
{
    const QModelIndex current = view_->currentIndex();
    if (!current.isValid())
        return false;
    const QModelIndex source = proxy_->mapToSource(current);
    const int part = model_->part_at(source), node = model_->node_at(source);
    // an assembly: every part under it to its (mean) percent plus the step
    const float alpha = part >= 0 ? model_->alpha()[size_t(part)] : model_->node_alpha(node);
    const float stepped = float(std::clamp(PartsModel::percent(alpha) + delta_percent, 0, 100)) / 100.0f;
    if (part >= 0 ? model_->set_alpha(part, stepped) : model_->set_node_alpha(node, stepped))
        emit parts_changed();
    return true;
}

bool PartsPanel::toggle_current_visible()
{
    const QModelIndex current = view_->currentIndex();
    if (!current.isValid())
        return false;
    const QModelIndex source = proxy_->mapToSource(current);
    const int part = model_->part_at(source), node = model_->node_at(source);
    // an assembly: all shown when some part under it is hidden, else all hidden
    const bool changed =
        part >= 0 ? model_->set_visible(part, !model_->visible()[size_t(part)])
                  : model_->set_node_visible(node, model_->node_visible_count(node) < model_->node_part_count(node));
    if (changed)
        emit parts_changed();
    return true;
}

void PartsPanel::apply(const std::vector<float> &alpha, const std::vector<char> &visible)
{
    if (model_->set_all(alpha, visible))
        emit parts_changed();
}

void PartsPanel::update_buttons()
{
    const bool any = model_->part_count() > 0;
    const bool selected = view_->selectionModel()->hasSelection();
    reset_->setEnabled(any);
    show_all_->setEnabled(any);
    isolate_->setEnabled(selected);
    frame_->setEnabled(selected);
}

void PartsPanel::filter_changed()
{
    if (model_->node_count() == 0)
        return;
    if (!filter_->text().isEmpty()) {
        // the matches in sight: every row the filter keeps, opened
        view_->expandAll();
        return;
    }
    // back to the top assemblies open, and the current row still in sight
    view_->collapseAll();
    view_->expandToDepth(0);
    const QModelIndex current = view_->currentIndex();
    if (current.isValid()) {
        for (QModelIndex parent = current.parent(); parent.isValid(); parent = parent.parent())
            view_->expand(parent);
        view_->scrollTo(current);
    }
}
