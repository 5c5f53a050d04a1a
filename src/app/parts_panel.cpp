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

PartsModel::PartsModel(QObject *parent) : QAbstractTableModel(parent) {}

int PartsModel::percent(float alpha) { return int(std::lround(double(clamp_alpha(alpha)) * 100.0)); }

void PartsModel::set_model(const oit_model *model, const std::vector<float> &alpha,
                           const std::vector<char> &visible)
{
    beginResetModel();
    parts_.clear();
    names_.clear();
    swatches_.clear();
    const size_t count = model && model->components ? model->component_count : 0;
    parts_.reserve(count);
    // the names' bytes in one block, a QString made when a row is shown or
    // filtered: at 100,000 parts one string each kept the GUI thread 3 times longer
    size_t bytes = 0;
    for (size_t i = 0; i < count; ++i)
        bytes += strnlen(model->components[i].name, sizeof model->components[i].name);
    names_.reserve(int(bytes));
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
    take_values(alpha, visible);
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
}

void PartsModel::set_values(const std::vector<float> &alpha, const std::vector<char> &visible)
{
    // dataChanged for the rows that changed only: a load sets the values it
    // has just shown, and 100,000 rows through the filter cost the GUI thread
    const std::vector<float> old_alpha = alpha_;
    const std::vector<char> old_visible = visible_;
    take_values(alpha, visible);
    int first = -1, last = -1;
    for (int row = 0; row < part_count(); ++row)
        if (alpha_[size_t(row)] != old_alpha[size_t(row)] || visible_[size_t(row)] != old_visible[size_t(row)]) {
            if (first < 0)
                first = row;
            last = row;
        }
    emit_rows_changed(first, last);
}

bool PartsModel::set_alpha(int part, float alpha)
{
    if (part < 0 || part >= part_count())
        return false;
    alpha = clamp_alpha(alpha);
    if (alpha_[size_t(part)] == alpha)
        return false;
    alpha_[size_t(part)] = alpha;
    emit dataChanged(index(part, OpacityColumn), index(part, PercentColumn));
    return true;
}

bool PartsModel::set_visible(int part, bool visible)
{
    if (part < 0 || part >= part_count() || bool(visible_[size_t(part)]) == visible)
        return false;
    visible_[size_t(part)] = visible;
    emit dataChanged(index(part, PartColumn), index(part, PartColumn), {Qt::CheckStateRole});
    return true;
}

bool PartsModel::set_all(const std::vector<float> &alpha, const std::vector<char> &visible)
{
    if (alpha.size() != parts_.size() || visible.size() != parts_.size())
        return false;
    // one dataChanged over the changed span, not one per row
    int first = -1, last = -1;
    for (size_t i = 0; i < parts_.size(); ++i) {
        const float a = clamp_alpha(alpha[i]);
        const char v = visible[i] != 0;
        if (alpha_[i] == a && visible_[i] == v)
            continue;
        alpha_[i] = a;
        visible_[i] = v;
        if (first < 0)
            first = int(i);
        last = int(i);
    }
    emit_rows_changed(first, last);
    return first >= 0;
}

void PartsModel::emit_rows_changed(int first, int last)
{
    if (first >= 0 && last >= first)
        emit dataChanged(index(first, 0), index(last, ColumnCount - 1));
}

int PartsModel::rowCount(const QModelIndex &parent) const { return parent.isValid() ? 0 : part_count(); }

int PartsModel::columnCount(const QModelIndex &parent) const { return parent.isValid() ? 0 : ColumnCount; }

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
    if (!index.isValid() || index.row() >= part_count())
        return {};
    const size_t row = size_t(index.row());
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
    if (!index.isValid() || index.row() >= part_count())
        return false;
    bool changed = false;
    if (index.column() == PartColumn && role == Qt::CheckStateRole)
        changed = set_visible(index.row(), value.toInt() == Qt::Checked);
    else if (index.column() == OpacityColumn && role == AlphaRole)
        changed = set_alpha(index.row(), float(value.toDouble()));
    else
        return false;
    if (changed)
        emit edited();
    return true;
}

Qt::ItemFlags PartsModel::flags(const QModelIndex &index) const
{
    if (!index.isValid())
        return Qt::NoItemFlags;
    // ItemNeverHasChildren spares the tree view a hasChildren() per row
    Qt::ItemFlags flags = Qt::ItemIsEnabled | Qt::ItemIsSelectable | Qt::ItemNeverHasChildren;
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

// Case-insensitive substring match on the part name, straight from the model's strings.
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
        invalidateFilter();
    }

protected:
    bool filterAcceptsRow(int row, const QModelIndex &parent) const override
    {
        return parent.isValid() || text_.isEmpty() || parts_->name(row).contains(text_, Qt::CaseInsensitive);
    }

private:
    PartsModel *parts_;
    QString text_;
};

} // namespace

// ------------------------------------------------------------------ PartsView

// The list: QTreeView without a tree, with the opacity keys and Space for the checkbox.
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
        default:
            break;
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
    connect(filter_, &QLineEdit::textChanged, this, [filter_model](const QString &text) { filter_model->set_text(text); });
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
                      "); Ctrl/Shift-click: select several; double-click a name: frame it");
    QHeaderView *header = view_->header();
    header->setStretchLastSection(false);
    header->setSectionResizeMode(PartsModel::PartColumn, QHeaderView::Stretch);
    // fixed widths: ResizeToContents would measure rows on every layout
    header->setSectionResizeMode(PartsModel::OpacityColumn, QHeaderView::Fixed);
    header->resizeSection(PartsModel::OpacityColumn, 130);
    header->setSectionResizeMode(PartsModel::PercentColumn, QHeaderView::Fixed);
    header->resizeSection(PartsModel::PercentColumn, view_->fontMetrics().horizontalAdvance("100%") + 16);
    connect(view_, &QAbstractItemView::doubleClicked, this, [this](const QModelIndex &index) {
        if (index.column() == PartsModel::PartColumn)
            emit frame_selected_requested({proxy_->mapToSource(index).row()});
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
    const QString note = QStringLiteral("%1 parts; checkbox: visible, slider: opacity (--component-alpha).").arg(count);
    note_->setText(note);
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
    for (const QModelIndex &index : rows)
        parts.push_back(proxy_->mapToSource(index).row());
    std::sort(parts.begin(), parts.end());
    return parts;
}

void PartsPanel::select_part(int index)
{
    if (index < 0 || index >= model_->part_count())
        return;
    if (!filter_->text().isEmpty() && !model_->name(index).contains(filter_->text(), Qt::CaseInsensitive))
        filter_->clear();
    const QModelIndex row = proxy_->mapFromSource(model_->index(index, PartsModel::PartColumn));
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
    const int part = proxy_->mapToSource(current).row();
    const int percent = std::clamp(PartsModel::percent(model_->alpha()[size_t(part)]) + delta_percent, 0, 100);
    if (model_->set_alpha(part, float(percent) / 100.0f))
        emit parts_changed();
    return true;
}

bool PartsPanel::toggle_current_visible()
{
    const QModelIndex current = view_->currentIndex();
    if (!current.isValid())
        return false;
    const int part = proxy_->mapToSource(current).row();
    if (model_->set_visible(part, !model_->visible()[size_t(part)]))
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
