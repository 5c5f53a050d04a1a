// parts_panel.cpp: the Parts tab (parts_panel.h): the view of PartsModel
// (parts_model.cpp). Everything per row is data in the model and painting in
// delegates, so 10,000 parts cost only the rows on screen: no widget per row,
// uniform row heights, filtering in a proxy.
#include "parts_panel.h"

#include <QApplication>
#include <QGridLayout>
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
#include <QSpinBox>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QStyledItemDelegate>
#include <QTreeView>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

// --------------------------------------------------------- the opacity slider

namespace {

// Paints the opacity column as a slider (QStyle's CC_Slider on the cell) and
// edits it by mouse: a press sets the value under the pointer (editorEvent),
// and the drag that follows is followed through the viewport's events, since
// the view hands a delegate only the cell under the pointer, and not at all
// once the pointer leaves the rows.
class OpacityDelegate : public QStyledItemDelegate {
public:
    // set_selection: a selected row's slider sets every selected row (true), else only its own
    using SetSelection = std::function<bool(const QModelIndex &, float)>;
    OpacityDelegate(QAbstractItemView *view, SetSelection set_selection)
        : QStyledItemDelegate(view), view_(view), viewport_(view->viewport()), set_selection_(std::move(set_selection))
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
        slider.pageStep = parts_alpha_step_percent;
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
        if (!set_selection_(index, float(value) / 100.0f))
            model->setData(index, double(value) / 100.0, PartsModel::AlphaRole);
    }

    QAbstractItemView *view_;
    QWidget *viewport_;
    QPersistentModelIndex dragging_; // the row whose slider the mouse holds
    SetSelection set_selection_;
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
            handled = (plain || modifiers == Qt::ShiftModifier) && panel_->step_current_alpha(parts_alpha_step_percent);
            break;
        case Qt::Key_Minus:
            handled = (plain || modifiers == Qt::ShiftModifier) && panel_->step_current_alpha(-parts_alpha_step_percent);
            break;
        case Qt::Key_Right:
            handled = plain && panel_->step_current_alpha(parts_alpha_step_percent);
            break;
        case Qt::Key_Left:
            handled = plain && panel_->step_current_alpha(-parts_alpha_step_percent);
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
    view_->setItemDelegateForColumn(
        PartsModel::OpacityColumn,
        new OpacityDelegate(view_, [this](const QModelIndex &row, float alpha) { return set_selected_alpha(row, alpha); }));
    view_->setContextMenuPolicy(Qt::ActionsContextMenu);
    view_->setRootIsDecorated(false);
    view_->setItemsExpandable(false);
    view_->setUniformRowHeights(true); // row geometry without asking every row
    view_->setAllColumnsShowFocus(true);
    view_->setSelectionMode(QAbstractItemView::ExtendedSelection);
    view_->setSelectionBehavior(QAbstractItemView::SelectRows);
    view_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    view_->setToolTip("checkbox (or Space): show or hide the part; slider: its opacity (" + parts_opacity_help() +
                      "; with several rows selected, a selected row's slider and the keys set them all"
                      "); an assembly's check box and slider: every part under it (Shift+Right / Shift+Left "
                      "or its arrow: expand, collapse); Ctrl/Shift-click: select several; double-click a "
                      "part's name: frame it");
    QHeaderView *header = view_->header();
    header->setStretchLastSection(false);
    header->setSectionResizeMode(PartsModel::PartColumn, QHeaderView::Stretch);
    // fixed widths: ResizeToContents would measure rows on every layout
    header->setSectionResizeMode(PartsModel::OpacityColumn, QHeaderView::Fixed);
    header->resizeSection(PartsModel::OpacityColumn, 90); // the name gets the narrow panel's width
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

    auto *buttons = new QGridLayout; // two a row: the panel is narrow
    auto button = [&](const char *name, const char *text, const char *tooltip) {
        auto *b = new QPushButton(text);
        b->setObjectName(name);
        b->setToolTip(tooltip);
        buttons->addWidget(b, buttons->count() / 2, buttons->count() % 2);
        return b;
    };
    reset_ = button("parts_reset", "Reset", "every part visible and at full opacity");
    isolate_ = button("parts_isolate", "Isolate selected", "show only the selected parts, hide every other one");
    show_all_ = button("parts_show_all", "Show all", "make every part visible (opacities stay)");
    frame_ = button("parts_frame", "Frame selected", "frame the camera on the selected parts");
    layout->addLayout(buttons);
    // ghosting on a row of its own: the panel stays narrow
    auto *fade_row = new QHBoxLayout;
    fade_ = new QPushButton("Fade others");
    fade_->setObjectName("parts_fade");
    fade_->setToolTip("ghosting: every part not selected to the opacity beside (selected ones keep theirs); "
                      "one undo step (G)");
    fade_percent_ = new QSpinBox;
    fade_percent_->setObjectName("parts_fade_percent");
    fade_percent_->setRange(0, 100);
    fade_percent_->setSuffix("%");
    fade_percent_->setValue(10);
    fade_percent_->setToolTip("the opacity Fade others gives the parts not selected");
    fade_row->addWidget(fade_);
    fade_row->addWidget(fade_percent_);
    fade_row->addStretch(1);
    layout->addLayout(fade_row);
    connect(fade_, &QPushButton::clicked, this, &PartsPanel::fade_requested);
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

void PartsPanel::select_parts(const std::vector<int> &indices)
{
    if (indices.empty()) {
        view_->selectionModel()->clearSelection();
        return;
    }
    for (int index : indices)
        if (index >= 0 && index < model_->part_count() && !model_->filter_shows_part(index))
            filter_->clear(); // a filter would hide a part to be selected
    select_part(indices.front()); // the first: current, its assemblies open, scrolled to
    for (size_t i = 1; i < indices.size(); ++i) {
        const int index = indices[i];
        if (index < 0 || index >= model_->part_count())
            continue;
        view_->selectionModel()->select(proxy_->mapFromSource(model_->part_index(index)),
                                        QItemSelectionModel::Select | QItemSelectionModel::Rows);
    }
}

QAbstractItemView *PartsPanel::view() const { return view_; }

QLineEdit *PartsPanel::filter() const { return filter_; }

int PartsPanel::shown_row_count() const { return proxy_->rowCount(); }

bool PartsPanel::fade_others(float alpha)
{
    const std::vector<int> selected = selected_parts();
    if (selected.empty())
        return false;
    std::vector<float> faded(size_t(model_->part_count()), alpha);
    for (int part : selected)
        faded[size_t(part)] = model_->alpha()[size_t(part)];
    if (!model_->set_all(faded, model_->visible()))
        return false;
    emit parts_changed();
    return true;
}

int PartsPanel::fade_percent() const { return fade_percent_->value(); }

void PartsPanel::set_fade_percent(int percent) { fade_percent_->setValue(percent); }

void PartsPanel::add_context_action(QAction *action) { view_->addAction(action); }

bool PartsPanel::set_selected_alpha(const QModelIndex &row, float alpha)
{
    QItemSelectionModel *selection = view_->selectionModel();
    if (!selection->isRowSelected(row.row(), row.parent()) || selection->selectedRows().size() < 2)
        return false;
    std::vector<float> values = model_->alpha();
    for (int part : selected_parts())
        values[size_t(part)] = alpha;
    if (model_->set_all(values, model_->visible()))
        emit parts_changed();
    return true;
}

bool PartsPanel::step_current_alpha(int delta_percent)
{
    const QModelIndex current = view_->currentIndex();
    if (!current.isValid())
        return false;
    QItemSelectionModel *selection = view_->selectionModel();
    if (selection->isRowSelected(current.row(), current.parent()) && selection->selectedRows().size() > 1) {
        // bulk: every selected part by the step from its own percent
        std::vector<float> values = model_->alpha();
        for (int part : selected_parts())
            values[size_t(part)] =
                float(std::clamp(PartsModel::percent(values[size_t(part)]) + delta_percent, 0, 100)) / 100.0f;
        if (model_->set_all(values, model_->visible()))
            emit parts_changed();
        return true;
    }
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
    fade_->setEnabled(selected);
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
