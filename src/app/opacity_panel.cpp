// opacity_panel.cpp: see opacity_panel.h.
#include "opacity_panel.h"

#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

#include <algorithm>

OpacityPanel::OpacityPanel(SettingsModel &model, const CapabilityTable &capabilities, QWidget *parent)
    : SettingsPanel(model, parent)
{
    RenderSettings &s = settings();
    oit_modulation &m = s.modulation;
    auto *layout = new QVBoxLayout(this);
    auto edit = [this] { emit edited(); };
    QFormLayout *gform = group(layout, "Every algorithm");
    gform->addRow("alpha", slider_row(0, 1, 3, [&s] { return s.alpha; },
                                                [&s, edit](float v) {
                                                    s.alpha = v;
                                                    edit();
                                                },
                                                &alpha_slider_));
    gform->addRow("contrast", slider_row(0.1, 10, 2, [&s] { return s.contrast == 0.0f ? 1.0f : s.contrast; },
                                                      [&s, edit](float v) {
                                                          s.contrast = v;
                                                          edit();
                                                      }));
    gform->addRow("focus shape", combo({"none", "point", "plane", "box"},
                                       [&s] { return int(s.focus_shape); },
                                       [this, &s](int i) {
                                           s.focus_shape = oit_focus_shape(i);
                                           const oit_model *model = settings_model().model();
                                           if (model && i != OIT_FOCUS_NONE) {
                                               // start from something visible: the model's centre / bounds
                                               // (in file coordinates: origin + relative bounds)
                                               const oit_model &mo = *model;
                                               const double *o = mo.origin;
                                               double defaults[4][6] = {
                                                   {0, 0, 0, 0, 0, 0},
                                                   {o[0], o[1], o[2], 0, 0, 0},
                                                   {0, 0, 1, -o[2], 0, 0},
                                                   {o[0] + mo.bounds_min[0], o[1] + mo.bounds_min[1],
                                                    o[2] + mo.bounds_min[2], o[0], o[1], o[2]}};
                                               std::copy(defaults[i], defaults[i] + 6, s.focus);
                                           }
                                           emit this->changed();
                                       }));
    auto *focus_row = new QWidget;
    auto *focus_layout = new QGridLayout(focus_row); // three per row: x y z (a b c d, min max)
    focus_layout->setContentsMargins(0, 0, 0, 0);
    for (int i = 0; i < 6; ++i) {
        auto *value = new QDoubleSpinBox;
        value->setRange(-1e6, 1e6);
        value->setDecimals(3);
        value->setSingleStep(0.05);
        value->setMaximumWidth(110);
        value->setMinimumWidth(48); // three in a narrow panel's row
        connect(value, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, [this, &s, i](double v) {
            if (!syncing()) {
                s.focus[i] = v;
                emit edited();
            }
        });
        on_sync([&s, value, i] {
            int used = s.focus_shape == OIT_FOCUS_POINT ? 3 : s.focus_shape == OIT_FOCUS_PLANE ? 4
                       : s.focus_shape == OIT_FOCUS_BOX ? 6 : 0;
            value->setValue(s.focus[i]);
            value->setVisible(i < used);
        });
        focus_layout->addWidget(value, i / 3, i % 3);
    }
    gform->addRow("focus (model units)", focus_row);
    // no shape: no numbers
    show_row_when(gform, focus_row, [&s](const QString &) { return s.focus_shape != OIT_FOCUS_NONE; });
    // shared: the focus shapes' fall-off (model units) and ib's distance modulation (eye space)
    gform->addRow("focus region",
                  log_length_row(
                      [this] {
                          const oit_model *model = settings_model().model();
                          double radius = model && model->radius > 0.0f ? double(model->radius) : 1.0;
                          return std::make_pair(radius * 1e-3, radius * 4.0);
                      },
                      [&m] { return m.focus_region; },
                      [&m, edit](float v) {
                          m.focus_region = v;
                          edit();
                      }));

    // Each row shown for the algorithms that render what it sets (the core's
    // capability tables: a modulation, a distance, the surface neighbours)
    auto renders = [&capabilities](const QStringList &keys) { return renders_any(capabilities, keys); };
    QGroupBox *modulation_box;
    QFormLayout *form = group(layout, "Modulation", &modulation_box);
    form->addRow("modulation", modulation_ = combo(words(OIT_SETTING_MODULATION), [&m] { return int(m.mode); },
                                                   [&m, edit](int i) {
                                                       m.mode = oit_modulation_mode(i);
                                                       edit();
                                                   }));
    QStringList modulations;
    for (int i = OIT_MODULATE_NONE + 1; i < OIT_MODULATION_COUNT; ++i)
        modulations << QString("modulation:") + oit_setting_word(OIT_SETTING_MODULATION, i);
    show_row_when(form, modulation_, renders(modulations));
    QWidget *curvature_effect = slider_row(0.1, 64, 2, [&m] { return oit_modulation_defaults(&m).curvature_effect; },
                                           [&m, edit](float v) {
                                               m.curvature_effect = v;
                                               edit();
                                           });
    form->addRow("curvature effect", curvature_effect);
    auto curvature = renders({"modulation:curvature", "modulation:dist-curv", "view:curvature"});
    show_row_when(form, curvature_effect, curvature);
    QComboBox *curvature_neighbours = combo({"4", "8"}, [&m] { return m.curvature_neighbours == 8 ? 1 : 0; },
                                            [&m, edit](int i) {
                                                m.curvature_neighbours = i ? 8 : 4;
                                                edit();
                                            });
    form->addRow("curvature neighbours", curvature_neighbours);
    show_row_when(form, curvature_neighbours, curvature);
    form->addRow("distance", distance_ = combo({"adjacent", "skip:K", "far"}, [&m] { return int(m.distance); },
                                               [&m, edit](int i) {
                                                   m.distance = oit_distance_mode(i);
                                                   edit();
                                               }));
    show_row_when(form, distance_, renders({"modulation:distance", "modulation:dist-curv"}));
    QSpinBox *skip = spin_box(1, 64, [&m] { return m.distance_skip > 0 ? m.distance_skip : 2; },
                              [&m, edit](int k) {
                                  m.distance_skip = k;
                                  edit();
                              });
    form->addRow("skip K", skip);
    show_row_when(form, skip, renders({"distance:skip"}));
    show_group_when_used(modulation_box);

    QGroupBox *fields_box;
    QFormLayout *fields_form = group(layout, "Transparency fields", &fields_box);
    auto fields_rendered = renders({"modulation:fields"});
    auto *fields = new QWidget;
    auto *fields_layout = new QHBoxLayout(fields);
    fields_layout->setContentsMargins(0, 0, 0, 0);
    const char *field_names[] = {"alpha", "beta", "gamma"};
    for (int f = 0; f < 3; ++f)
        fields_layout->addWidget(check_box(field_names[f], [&m, f] { return ((m.fields ? m.fields : 7) >> f) & 1; },
                                           [&m, f, edit](bool on) {
                                               int mask = m.fields ? m.fields : 7;
                                               mask = on ? mask | (1 << f) : mask & ~(1 << f);
                                               m.fields = mask == 7 || mask == 0 ? 0 : mask;
                                               edit();
                                           }));
    fields_form->addRow("fields", fields);
    show_row_when(fields_form, fields, fields_rendered);
    QSpinBox *diffusion = spin_box(0, 1000,
                                   [&m] { return std::max(0, oit_modulation_defaults(&m).diffusion_iterations); },
                                   [&m, edit](int n) {
                                       m.diffusion_iterations = n == 0 ? -1 : n;
                                       edit();
                                   });
    fields_form->addRow("diffusion iterations", diffusion);
    show_row_when(fields_form, diffusion, fields_rendered);
    QSpinBox *blur = spin_box(0, 1000, [&m] { return m.blur_iterations == 0 ? 1 : std::max(0, m.blur_iterations); },
                              [&m, edit](int n) {
                                  m.blur_iterations = n == 0 ? -1 : n;
                                  edit();
                              });
    fields_form->addRow("blur iterations", blur);
    show_row_when(fields_form, blur, fields_rendered);
    float *lambdas[] = {&m.lambda_alpha, &m.lambda_beta, &m.lambda_gamma};
    const char *lambda_names[] = {"lambda alpha", "lambda beta", "lambda gamma"};
    for (int l = 0; l < 3; ++l) {
        float *lambda = lambdas[l];
        QWidget *row = slider_row(0, 2, 3, [lambda] { return *lambda; },
                                  [lambda, edit](float v) {
                                      *lambda = v;
                                      edit();
                                  });
        fields_form->addRow(lambda_names[l], row);
        show_row_when(fields_form, row, fields_rendered);
    }
    auto *halo = new QPushButton;
    connect(halo, &QPushButton::clicked, this, [this, &m] {
        QColor start = m.has_halo_colour ? QColor::fromRgbF(m.halo_colour[0], m.halo_colour[1], m.halo_colour[2])
                                         : QColor(Qt::white);
        QColor c = QColorDialog::getColor(start, window(), "Halo colour (--halo-colour)");
        if (!c.isValid())
            return;
        m.has_halo_colour = true;
        m.halo_colour[0] = float(c.redF());
        m.halo_colour[1] = float(c.greenF());
        m.halo_colour[2] = float(c.blueF());
        emit this->changed();
    });
    on_sync([&m, halo] {
        float white[3] = {1, 1, 1};
        const float *c = m.has_halo_colour ? m.halo_colour : white;
        halo->setIcon(swatch(c));
        halo->setText(colour_text(c));
    });
    fields_form->addRow("halo colour", halo);
    show_row_when(fields_form, halo, fields_rendered);
    show_group_when_used(fields_box);

    // the search for surface neighbours and the compose that uses them: the
    // algorithms that can show the neighbours found (view:neighbours) have them
    QGroupBox *neighbours_box;
    QFormLayout *neighbours_form = group(layout, "Surface neighbours", &neighbours_box);
    auto searches = renders({"view:neighbours"});
    QComboBox *neighbours =
        combo(QStringList{"default (welded)"} + words(OIT_SETTING_NEIGHBOURS), [&m] { return int(m.neighbours); },
              [&m, edit](int i) {
                  m.neighbours = oit_neighbour_search(i);
                  edit();
              });
    neighbours_form->addRow("neighbours", neighbours);
    show_row_when(neighbours_form, neighbours, searches);
    QWidget *epsilon = slider_row(0.001, 1, 3, [&m] { return oit_modulation_defaults(&m).epsilon_max; },
                                  [&m, edit](float v) {
                                      m.epsilon_max = v;
                                      edit();
                                  });
    neighbours_form->addRow("epsilon max", epsilon);
    show_row_when(neighbours_form, epsilon, searches);
    QCheckBox *last_opaque = check_box("last layer opaque", [&m] { return m.last_layer_opaque; },
                                       [&m, edit](bool on) {
                                           m.last_layer_opaque = on;
                                           edit();
                                       });
    neighbours_form->addRow(last_opaque);
    show_row_when(neighbours_form, last_opaque, searches);
    show_group_when_used(neighbours_box);
    layout->addStretch(1);

    // what the algorithm cannot express is hidden and disabled (the settings keep it)
    on_sync([this, &s, &capabilities] {
        QString algorithm = QString::fromStdString(s.algorithm);
        hide_items_not_rendered(modulation_, {{1, "modulation:curvature"},
                                     {2, "modulation:distance"},
                                     {3, "modulation:dist-curv"},
                                     {4, "modulation:fields"},
                                     {5, "modulation:edges"}},
                       capabilities, algorithm);
        hide_items_not_rendered(distance_, {{1, "distance:skip"}, {2, "distance:far"}}, capabilities, algorithm);
    });
}
