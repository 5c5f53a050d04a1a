// views_panel.cpp: see views_panel.h.
#include "views_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

ViewsPanel::ViewsPanel(SettingsModel &model, const CapabilityTable &capabilities, QWidget *parent)
    : SettingsPanel(model, parent)
{
    RenderSettings &s = settings();
    oit_modulation &m = s.modulation;
    auto *layout = new QVBoxLayout(this);
    QFormLayout *form = group(layout, "View");
    // in oit_view's order; those the algorithm cannot show are hidden (below)
    QStringList views = {"colour", "heatmap", "peel-limit:N", "layer:L", "neighbours",
                         "curvature:L", "distance:L", "fields:L"};
    form->addRow("view", view_ = combo(views, [&m] { return int(m.view); },
                                                [this, &m](int i) {
                                                    m.view = oit_view(i);
                                                    if ((m.view == OIT_VIEW_PEEL_LIMIT) && m.view_parameter < 1)
                                                        m.view_parameter = 1;
                                                    emit changed();
                                                }));
    auto *parameter = spin_box(0, 1000, [&m] { return m.view_parameter; },
                               [this, &m](int n) {
                                   m.view_parameter = n;
                                   emit edited();
                               });
    auto *previous = new QPushButton("◀");
    previous->setToolTip("the layer (or peel limit) one nearer the eye");
    auto *next = new QPushButton("▶");
    next->setToolTip("the layer (or peel limit) one farther from the eye");
    previous->setMinimumWidth(24); // below the style's 80 px: the panel is narrow
    next->setMinimumWidth(24);
    connect(previous, &QPushButton::clicked, parameter, [parameter] { parameter->setValue(parameter->value() - 1); });
    connect(next, &QPushButton::clicked, parameter, [parameter] { parameter->setValue(parameter->value() + 1); });
    auto *row = new QWidget;
    auto *row_layout = new QHBoxLayout(row);
    row_layout->setContentsMargins(0, 0, 0, 0);
    row_layout->addWidget(parameter);
    row_layout->addWidget(previous);
    row_layout->addWidget(next);
    form->addRow("N / layer L", row);
    // the layers and buffers are shown by the algorithms that keep them (the core's capability tables)
    auto renders = [&capabilities](const QStringList &keys) { return renders_any(capabilities, keys); };
    show_row_when(form, row,
                  renders({"view:peel-limit", "view:layer", "view:curvature", "view:distance", "view:fields"}));
    auto *hint = new QLabel("Layer by layer: choose layer:L and step nearer (◀) or farther (▶).");
    hint->setWordWrap(true);
    form->addRow(hint);
    show_row_when(form, hint, renders({"view:layer"}));
    QCheckBox *edges = check_box("edge view", [&m] { return m.mode == OIT_MODULATE_EDGES; },
                                 [this, &m](bool on) {
                                     m.mode = on ? OIT_MODULATE_EDGES : OIT_MODULATE_NONE;
                                     emit changed();
                                 });
    form->addRow(edges);
    show_row_when(form, edges, renders({"modulation:edges"}));
    layout->addStretch(1);

    // what the algorithm cannot express is hidden and disabled (the settings keep it)
    on_sync([this, &s, &capabilities] {
        hide_items_not_rendered(view_, {{1, "view:heatmap"},
                               {2, "view:peel-limit"},
                               {3, "view:layer"},
                               {4, "view:neighbours"},
                               {5, "view:curvature"},
                               {6, "view:distance"},
                               {7, "view:fields"}},
                       capabilities, QString::fromStdString(s.algorithm));
    });
}
