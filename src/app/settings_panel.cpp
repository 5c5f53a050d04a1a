// settings_panel.cpp: see settings_panel.h.
#include "settings_panel.h"

#include <QAbstractButton>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QIcon>
#include <QLabel>
#include <QPainter>
#include <QPixmap>
#include <QScrollArea>
#include <QSlider>
#include <QSpinBox>
#include <QStandardItemModel>

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
    spin = new QDoubleSpinBox;
    configure(spin);
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

void grey_out_items(QComboBox *box, const std::vector<std::pair<int, QString>> &keys, const CapabilityTable &table,
                    const QString &algorithm)
{
    if (table.empty())
        return;
    auto *model = qobject_cast<QStandardItemModel *>(box->model());
    if (!model)
        return;
    for (const auto &[index, key] : keys) {
        auto [ok, tip] = capability(table, key, box->itemText(index), algorithm);
        QStandardItem *item = model->item(index);
        item->setEnabled(ok);
        item->setToolTip(tip);
    }
}

// --------------------------------------------------------------- tooltips

// What each row of the settings panel does, by its label (the flag in
// brackets is `oit render`'s, which Copy as command writes).
static const std::pair<const char *, const char *> kRowTips[] = {
    {"algorithm", "how transparency is composited: the exact ones (dp, ddp, ll, ib, reference) agree; "
                  "blend and wboit approximate"},
    {"sort", "ll's per-pixel sort: insertion sort in the lists, or a copy into a local array"},
    {"neighbours", "ib: how a fragment finds its neighbours on the surface (shared vertex index, welded "
                   "position, or the epsilon depth/normal search)"},
    {"memory budget", "the most the fragment pools of ll and ib may grow to"},
    {"layer cap", "dp/ddp: stop after this many layers (none: peel until nothing is left); a frame cut short "
                  "is marked TRUNCATED"},
    {"shading", "flat: the material colour; headlight: lit from the eye"},
    {"background", "the colour behind the model"},
    {"alpha", "opacity of every surface, times the part's own opacity"},
    {"contrast", "stretch the composited colour about mid-grey (1: unchanged)"},
    {"focus shape", "fade surfaces by their distance to a point, plane or box (every algorithm)"},
    {"focus (model units)", "the focus shape's point, plane (a b c d) or box (min, max), model coordinates"},
    {"focus region", "fall-off length of the focus shape and of ib's distance modulation; logarithmic slider, "
                     "left end 0 = automatic"},
    {"modulation", "ib's opacity modulation from the surface around each fragment; other algorithms do "
                   "what they can and the Messages say what they left out"},
    {"curvature effect", "how strongly curvature raises opacity (delta_c)"},
    {"curvature neighbours", "curvature from 4 or 8 neighbours"},
    {"distance", "ib: distance to the next fragment, to the one K places on, or to the last"},
    {"skip K", "ib: the fragment K places on for the skip distance"},
    {"fields", "ib: which transparency fields (alpha, beta, gamma) modulate"},
    {"diffusion iterations", "ib: diffusion steps of the fields over the surface (0 = none)"},
    {"blur iterations", "ib: blur passes of the beta field (0 = none)"},
    {"lambda", "ib: weight of the field (0 = automatic)"},
    {"epsilon max", "ib: the largest epsilon the epsilon neighbour search accepts"},
    {"halo colour", "ib: the colour of the halos the fields draw"},
    {"view", "what the view shows: the colour, the list-length heatmap, one layer, or ib's buffers"},
    {"N / layer L", "the peel limit or layer the view shows"},
    {"mode", "orbit turns about the target; walk moves with W/A/S/D, Q/E"},
    {"projection", "perspective or orthographic"},
    {"field of view", "vertical field of view of the perspective camera"},
    {"saved views", "camera poses kept for this model: double-click one to return to it"},
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
            QString tip;
            for (const auto &entry : kRowTips)
                if (!name.isEmpty() && name.startsWith(entry.first))
                    tip = QString("%1: %2").arg(name, entry.second);
            if (tip.isEmpty())
                tip = name;
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
