// views_panel.cpp: see views_panel.h.
#include "views_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>

ViewsPanel::ViewsPanel(SettingsModel &model, const CapabilityTable &capabilities, QWidget *parent)
    : SettingsPanel(model, parent)
{
    RenderSettings &s = settings();
    oit_modulation &m = s.modulation;
    auto *form = new QFormLayout(this);
    form->setRowWrapPolicy(QFormLayout::WrapLongRows); // narrow panels put fields under labels
    QStringList views = {"colour", "heatmap", "peel-limit:N", "layer:L", "neighbours (ib)",
                         "curvature:L (ib)", "distance:L (ib)", "fields:L (ib)"};
    form->addRow("view (--view)", view_ = combo(views, [&m] { return int(m.view); },
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
    auto *previous = new QPushButton("◀ nearer");
    previous->setToolTip("the layer (or peel limit) one nearer the eye");
    auto *next = new QPushButton("farther ▶");
    next->setToolTip("the layer (or peel limit) one farther from the eye");
    connect(previous, &QPushButton::clicked, parameter, [parameter] { parameter->setValue(parameter->value() - 1); });
    connect(next, &QPushButton::clicked, parameter, [parameter] { parameter->setValue(parameter->value() + 1); });
    auto *row = new QHBoxLayout;
    row->addWidget(parameter);
    row->addWidget(previous);
    row->addWidget(next);
    form->addRow("N / layer L", row);
    form->addRow(new QLabel("Layer by layer: choose layer:L and step with the buttons.\n"
                            "heatmap and peel-limit: ll and ib; the others: ib."));
    form->addRow(check_box("edge view (ib: --modulation edges)", [&m] { return m.mode == OIT_MODULATE_EDGES; },
                           [this, &s, &m](bool on) {
                               m.mode = on ? OIT_MODULATE_EDGES : OIT_MODULATE_NONE;
                               if (on && s.algorithm != "ib") { // the edges are ib's
                                   s.algorithm = "ib";
                                   emit changed();
                               }
                               emit changed();
                           }));

    // what the algorithm cannot express is greyed out (the settings keep it)
    on_sync([this, &s, &capabilities] {
        grey_out_items(view_, {{1, "view:heatmap"},
                               {2, "view:peel-limit"},
                               {3, "view:layer"},
                               {4, "view:neighbours"},
                               {5, "view:curvature"},
                               {6, "view:distance"},
                               {7, "view:fields"}},
                       capabilities, QString::fromStdString(s.algorithm));
    });
}
