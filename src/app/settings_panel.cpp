// settings_panel.cpp: see settings_panel.h.
#include "settings_panel.h"

#include <QAbstractButton>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QIcon>
#include <QLabel>
#include <QListView>
#include <QPainter>
#include <QPixmap>
#include <QScrollArea>
#include <QSlider>
#include <QSpinBox>
#include <QStandardItemModel>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>

SettingsPanel::SettingsPanel(SettingsModel &settings, QWidget *parent) : QWidget(parent), model_(settings) {}

void SettingsPanel::sync()
{
    syncing_ = true;
    for (auto &action : sync_actions_)
        action();
    syncing_ = false;
}

QWidget *SettingsPanel::linked_row(QSlider *&slider, QDoubleSpinBox *&spin,
                                   std::function<void(QDoubleSpinBox *)> configure,
                                   std::function<double(int)> from_slider, std::function<int(double)> to_slider,
                                   std::function<void(float)> set, bool set_rounded)
{
    auto *row = new QWidget;
    auto *layout = new QHBoxLayout(row);
    layout->setContentsMargins(0, 0, 0, 0);
    slider = new QSlider(Qt::Horizontal);
    slider->setRange(0, 1000);
    slider->setMinimumWidth(64); // still a slider in a narrow panel (the row goes under its label)
    spin = new QDoubleSpinBox;
    configure(spin);
    spin->setMinimumWidth(56);
    spin->setMaximumWidth(88); // a number, not the range's longest text
    layout->addWidget(slider, 1);
    layout->addWidget(spin);
    QSlider *s = slider;
    QDoubleSpinBox *b = spin;
    connect(s, &QSlider::valueChanged, b, [=](int position) {
        if (syncing_)
            return;
        double value = from_slider(position);
        b->blockSignals(true);
        b->setValue(value);
        b->blockSignals(false);
        set(float(set_rounded ? b->value() : value));
    });
    connect(b, QOverload<double>::of(&QDoubleSpinBox::valueChanged), s, [=](double v) {
        if (syncing_)
            return;
        s->blockSignals(true);
        s->setValue(to_slider(v));
        s->blockSignals(false);
        set(float(v));
    });
    return row;
}

QWidget *SettingsPanel::slider_row(double low, double high, int decimals, std::function<float()> get,
                                   std::function<void(float)> set, QSlider **slider_out)
{
    auto to_slider = [=](double v) { return int(std::lround((v - low) / (high - low) * 1000.0)); };
    QSlider *slider;
    QDoubleSpinBox *spin;
    QWidget *row = linked_row(
        slider, spin,
        [=](QDoubleSpinBox *box) {
            box->setRange(low, high);
            box->setDecimals(decimals);
            box->setSingleStep(std::pow(10.0, -decimals) * 5);
        },
        [=](int v) { return low + (high - low) * v / 1000.0; }, to_slider, set, true);
    on_sync([=] {
        spin->setValue(double(get()));
        slider->setValue(to_slider(double(get())));
    });
    if (slider_out)
        *slider_out = slider;
    return row;
}

QWidget *SettingsPanel::log_length_row(std::function<std::pair<double, double>()> range, std::function<float()> get,
                                       std::function<void(float)> set)
{
    auto to_slider = [range](double v) {
        auto [low, high] = range();
        if (!(v > 0.0))
            return 0;
        double t = std::log(std::max(v, low) / low) / std::log(high / low);
        return std::max(1, int(std::lround(std::min(1.0, t) * 1000.0)));
    };
    auto from_slider = [range](int position) {
        auto [low, high] = range();
        return position == 0 ? 0.0 : low * std::pow(high / low, position / 1000.0);
    };
    QSlider *slider;
    QDoubleSpinBox *spin;
    QWidget *row = linked_row(
        slider, spin,
        [](QDoubleSpinBox *box) {
            box->setDecimals(6);
            box->setSpecialValueText("auto");
        },
        from_slider, to_slider, set, false);
    on_sync([=] {
        auto [low, high] = range();
        spin->setRange(0.0, high * 1000.0);
        spin->setSingleStep(low * 10.0);
        spin->setValue(double(get()));
        slider->setValue(to_slider(double(get())));
    });
    return row;
}

QStringList SettingsPanel::words(oit_setting setting)
{
    const char *const *words;
    QStringList list;
    for (int i = 0, count = oit_setting_words(setting, &words); i < count; ++i)
        list << words[i];
    return list;
}

QComboBox *SettingsPanel::combo(const QStringList &items, std::function<int()> get, std::function<void(int)> set)
{
    auto *box = new QComboBox;
    box->addItems(items);
    // narrow in the panel (a long item does not widen it); the open list shows whole items
    box->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    box->setMinimumContentsLength(8);
    box->view()->setMinimumWidth(box->view()->sizeHintForColumn(0) + 24);
    connect(box, QOverload<int>::of(&QComboBox::currentIndexChanged), box, [=](int i) {
        if (!syncing_ && i >= 0)
            set(i);
    });
    on_sync([=] { box->setCurrentIndex(get()); });
    return box;
}

QSpinBox *SettingsPanel::spin_box(int low, int high, std::function<int()> get, std::function<void(int)> set)
{
    auto *box = new QSpinBox;
    box->setRange(low, high);
    connect(box, QOverload<int>::of(&QSpinBox::valueChanged), box, [=](int v) {
        if (!syncing_)
            set(v);
    });
    on_sync([=] { box->setValue(get()); });
    return box;
}

QCheckBox *SettingsPanel::check_box(const QString &text, std::function<bool()> get, std::function<void(bool)> set)
{
    auto *box = new QCheckBox(text);
    connect(box, &QCheckBox::toggled, box, [=](bool on) {
        if (!syncing_)
            set(on);
    });
    on_sync([=] { box->setChecked(get()); });
    return box;
}

QFormLayout *SettingsPanel::group(QVBoxLayout *layout, const QString &title, QGroupBox **box_out)
{
    auto *box = new QGroupBox(title);
    auto *form = new QFormLayout(box);
    form->setRowWrapPolicy(QFormLayout::WrapLongRows); // narrow panels put fields under labels
    layout->addWidget(box);
    if (box_out)
        *box_out = box;
    return form;
}

void SettingsPanel::show_row_when(QFormLayout *form, QWidget *field, std::function<bool(const QString &)> applies)
{
    QStringList where = algorithms_where(applies);
    size_t count;
    oit_algorithm_list(&count);
    if (!where.isEmpty() && size_t(where.size()) < count) // for the tooltip: the algorithms it applies to
        field->setProperty("applies_to", where);
    if (!row_applies_.count(form))
        on_sync([this, form] { refresh_rows(form); }); // once per form, where its first such row is
    row_applies_[form][field] = std::move(applies);
}

void SettingsPanel::refresh_rows(QFormLayout *form)
{
    // Qt 5's QFormLayout keeps a hidden row's spacing: a row that does not
    // apply is taken out of the form (its widgets hidden), and put back in its place
    std::vector<FormRow> &rows = form_rows_[form];
    if (rows.empty())
        for (int r = 0; r < form->rowCount(); ++r) {
            QLayoutItem *label = form->itemAt(r, QFormLayout::LabelRole);
            QLayoutItem *field = form->itemAt(r, QFormLayout::FieldRole);
            if (!field)
                field = form->itemAt(r, QFormLayout::SpanningRole);
            if (field && field->widget())
                rows.push_back({label ? label->widget() : nullptr, field->widget()});
        }
    const QString algorithm = QString::fromStdString(settings().algorithm);
    const auto &applies = row_applies_[form];
    int at = 0; // where the next row shown goes
    for (const FormRow &row : rows) {
        auto rule = applies.find(row.field);
        bool shown = rule == applies.end() || rule->second(algorithm);
        int present = -1;
        QFormLayout::ItemRole role;
        form->getWidgetPosition(row.field, &present, &role);
        if (shown && present < 0) {
            if (row.label)
                form->insertRow(at, row.label, row.field);
            else
                form->insertRow(at, row.field);
        } else if (!shown && present >= 0) {
            QFormLayout::TakeRowResult taken = form->takeRow(present);
            delete taken.labelItem; // the layout items, not the widgets
            delete taken.fieldItem;
        }
        row.field->setVisible(shown);
        if (row.label)
            row.label->setVisible(shown);
        at += shown;
    }
}

void SettingsPanel::show_group_when_used(QGroupBox *box)
{
    on_sync([box] {
        bool used = false;
        auto *form = qobject_cast<QFormLayout *>(box->layout());
        for (int i = 0; form && i < form->count(); ++i)
            if (QWidget *w = form->itemAt(i)->widget())
                used = used || !w->isHidden();
        box->setVisible(used);
    });
}

QWidget *scrolled(QWidget *content)
{
    auto *area = new QScrollArea;
    area->setWidget(content);
    area->setWidgetResizable(true);
    area->setFrameShape(QFrame::NoFrame);
    return area;
}

QIcon swatch(const float colour[3])
{
    QPixmap pixmap(14, 14);
    pixmap.fill(QColor::fromRgbF(colour[0], colour[1], colour[2]));
    QPainter painter(&pixmap);
    painter.setPen(Qt::black);
    painter.drawRect(0, 0, 13, 13);
    return QIcon(pixmap);
}

QString colour_text(const float c[3])
{
    return QString("%1,%2,%3").arg(double(c[0])).arg(double(c[1])).arg(double(c[2]));
}

// ------------------------------------------------------------ capabilities

std::pair<bool, QString> capability(const CapabilityTable &table, const QString &key, const QString &what,
                                    const QString &algorithm)
{
    auto found = table.find(key);
    QStringList can = found == table.end() ? QStringList() : found->second;
    bool ok = can.contains(algorithm);
    QString tip = can.isEmpty() ? QString("%1: no algorithm can").arg(what)
                                : QString("%1: %2 can").arg(what, can.join(", "));
    if (!ok)
        tip += QString(" — not %1, which renders without it (the Messages say so)").arg(algorithm);
    return std::make_pair(ok, tip);
}

void hide_items_not_rendered(QComboBox *box, const std::vector<std::pair<int, QString>> &keys,
                             const CapabilityTable &table, const QString &algorithm)
{
    if (table.empty())
        return;
    auto *model = qobject_cast<QStandardItemModel *>(box->model());
    if (!model)
        return;
    auto *list = qobject_cast<QListView *>(box->view());
    for (const auto &[index, key] : keys) {
        auto [ok, tip] = capability(table, key, box->itemText(index), algorithm);
        QStandardItem *item = model->item(index);
        item->setEnabled(ok);
        item->setToolTip(tip);
        if (list)
            list->setRowHidden(index, !ok && index != box->currentIndex());
    }
}

bool algorithm_renders(const CapabilityTable &table, const QString &key, const QString &algorithm)
{
    auto found = table.find(key);
    return found != table.end() && found->second.contains(algorithm);
}

bool algorithm_reads(const QString &algorithm, unsigned option)
{
    return oit_algorithm_reads(oit_algorithm_find(algorithm.toUtf8().constData()), option);
}

std::function<bool(const QString &)> renders_any(const CapabilityTable &table, const QStringList &keys)
{
    return [&table, keys](const QString &algorithm) {
        for (const QString &key : keys)
            if (algorithm_renders(table, key, algorithm))
                return true;
        return false;
    };
}

QStringList algorithms_where(const std::function<bool(const QString &)> &applies)
{
    size_t count;
    const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
    QStringList names;
    for (size_t i = 0; i < count; ++i)
        if (applies(QString::fromUtf8(list[i]->name)))
            names << list[i]->name;
    return names;
}

// --------------------------------------------------------------- tooltips

// What each row of the settings panel does, by its label: the `oit render`
// flag it sets (which Copy as command writes), and a description.
struct RowTip {
    const char *label, *flag, *description;
};
static const RowTip kRowTips[] = {
    {"algorithm", "--algorithm", "how transparency is composited: the exact ones (dp, ddp, ll, ib, reference) agree; "
                                 "blend and wboit approximate"},
    {"sort", "--sort", "ll's per-pixel sort: insertion in the lists, a local array, bma (Knowles' arrays by length) or merge (default); the same image"},
    {"neighbours", "--neighbours", "how a fragment finds its neighbours on the surface (shared vertex index, welded "
                                   "position, or the epsilon depth/normal search)"},
    {"memory budget", "--max-memory", "the most the fragment pools and buffers may grow to"},
    {"layer cap", "--max-layers", "stop after this many layers (none: peel until nothing is left); a frame cut short "
                                  "is marked TRUNCATED"},
    {"layers", "--layers", "layers kept per pixel (k): exact where no pixel has more fragments; memory grows with k"},
    {"moments", "--moments", "the moments kept per pixel: 4 or 6 power moments, or 3 trigonometric ones"},
    {"shading", "--shading", "flat: the material colour; headlight: lit from the eye"},
    {"background", "--background", "the colour behind the model"},
    {"anti-aliasing", "--samples", "samples per pixel, averaged: auto renders 1 while the view moves and 4 once it "
                                   "is still; exports use at least 4"},
    {"tessellation", "--tessellation", "how STEP and IGES surfaces become triangles: the linear deflection 1/1000 "
                                       "(normal), 1/250 (coarse) or 1/4000 (fine) of the model's diagonal; the model "
                                       "is loaded again (other formats have their triangles)"},
    {"alpha", "--alpha", "opacity of every surface, times the part's own opacity"},
    {"contrast", "--contrast", "stretch the composited colour about mid-grey (1: unchanged)"},
    {"focus shape", "--focus-point, --focus-plane, --focus-box",
     "fade surfaces by their distance to a point, plane or box (every algorithm)"},
    {"focus (model units)", "--focus-point, --focus-plane, --focus-box",
     "the focus shape's point, plane (a b c d) or box (min, max), model coordinates"},
    {"focus region", "--focus-region", "fall-off length of the focus shape and of the distance modulation; "
                                       "logarithmic slider, left end 0 = automatic"},
    {"modulation", "--modulation", "opacity modulation from the surface around each fragment; the values the "
                                   "algorithm cannot render are hidden"},
    {"curvature effect", "--curvature-effect", "how strongly curvature raises opacity (delta_c)"},
    {"curvature neighbours", "--curvature-neighbours", "curvature from 4 or 8 neighbours"},
    {"distance", "--distance", "distance to the next fragment, to the one K places on, or to the last"},
    {"skip K", "--distance skip:K", "the fragment K places on for the skip distance"},
    {"fields", "--fields", "which transparency fields (alpha, beta, gamma) modulate"},
    {"diffusion iterations", "--diffusion-iterations", "diffusion steps of the fields over the surface (0 = none)"},
    {"blur iterations", "--blur-iterations", "blur passes of the beta field (0 = none)"},
    {"lambda alpha", "--lambda-alpha", "diffusion rate of the alpha field (0 = automatic)"},
    {"lambda beta", "--lambda-beta", "diffusion rate of the beta field (0 = automatic)"},
    {"lambda gamma", "--lambda-gamma", "diffusion rate of the gamma field (0 = automatic)"},
    {"epsilon max", "--epsilon-max", "the largest epsilon the epsilon neighbour search accepts"},
    {"halo colour", "--halo-colour", "the colour of the halos the gamma field draws"},
    {"last layer opaque", "--last-layer-opaque", "the farthest fragment of every pixel is opaque"},
    {"view", "--view", "what the view shows: the colour, the list-length heatmap, one layer, or a buffer; the "
                       "views the algorithm cannot show are hidden"},
    {"N / layer L", "--view peel-limit:N, layer:L", "the peel limit or layer the view shows"},
    {"edge view", "--modulation edges", "opaque where a fragment has fewer than four surface neighbours"},
    {"normal", "--section NX,NY,NZ,D", "the section plane's normal: it keeps the points p with n·p <= d"},
    {"offset", "--section NX,NY,NZ,D", "the section plane's offset d along its normal; the slider spans the model"},
    {"align", "--section NX,NY,NZ,D", "the plane's normal along an axis, towards the eye, or on a picked face"},
    {"explode", "--explode", "move every part away from the assembly's centre, along the direction to its own "
                             "centre, scaled by the factor (0: as built); the parts follow the slider"},
    {"mode", nullptr, "orbit turns about the target; walk moves with W/A/S/D, Q/E"},
    {"projection", nullptr, "perspective or orthographic"},
    {"field of view", nullptr, "vertical field of view of the perspective camera"},
    {"saved views", nullptr, "camera poses kept for this model: double-click one to return to it"},
};

void give_every_control_a_tooltip(QWidget *root)
{
    for (QFormLayout *form : root->findChildren<QFormLayout *>()) {
        for (int row = 0; row < form->rowCount(); ++row) {
            QLayoutItem *label_item = form->itemAt(row, QFormLayout::LabelRole);
            QLayoutItem *field_item = form->itemAt(row, QFormLayout::FieldRole);
            if (!field_item)
                field_item = form->itemAt(row, QFormLayout::SpanningRole);
            auto *label = label_item ? qobject_cast<QLabel *>(label_item->widget()) : nullptr;
            // the field: a widget, or a row of them in a layout
            QList<QWidget *> controls;
            std::function<void(QLayoutItem *)> collect = [&](QLayoutItem *item) {
                if (!item)
                    return;
                if (QWidget *w = item->widget()) {
                    controls << w << w->findChildren<QWidget *>();
                } else if (QLayout *layout = item->layout()) {
                    for (int i = 0; i < layout->count(); ++i)
                        collect(layout->itemAt(i));
                }
            };
            collect(field_item);
            if (controls.isEmpty())
                continue;
            QWidget *field = controls.first();
            QString name = label ? label->text() : QString();
            if (name.isEmpty())
                if (auto *button = qobject_cast<QAbstractButton *>(field))
                    name = button->text().remove('&');
            const RowTip *row_tip = nullptr;
            for (const auto &entry : kRowTips) // the longest label that starts the name
                if (!name.isEmpty() && name.startsWith(entry.label) &&
                    (!row_tip || qstrlen(entry.label) > qstrlen(row_tip->label)))
                    row_tip = &entry;
            // the algorithms it applies to, where only some (show_row_when)
            QStringList applies_to = field->property("applies_to").toStringList();
            QString where = applies_to.isEmpty() ? QString() : applies_to.join(", ");
            QString tip = name;
            if (row_tip && row_tip->flag)
                tip += QString(" (%1%2)").arg(row_tip->flag, where.isEmpty() ? "" : "; " + where);
            else if (!where.isEmpty())
                tip += QString(" (%1)").arg(where);
            if (row_tip)
                tip += QString(": %1").arg(row_tip->description);
            if (tip.isEmpty())
                continue;
            for (QWidget *control : controls)
                if (control->toolTip().isEmpty())
                    control->setToolTip(tip);
            if (label && label->toolTip().isEmpty())
                label->setToolTip(tip);
        }
    }
}
