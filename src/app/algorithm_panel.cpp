// algorithm_panel.cpp: see algorithm_panel.h.
#include "algorithm_panel.h"

#include <QColorDialog>
#include <QComboBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

#include <algorithm>

AlgorithmPanel::AlgorithmPanel(SettingsModel &model, QWidget *parent) : SettingsPanel(model, parent)
{
    RenderSettings &s = settings();
    auto *layout = new QVBoxLayout(this);
    auto *form = new QFormLayout;
    form->setRowWrapPolicy(QFormLayout::WrapLongRows); // narrow panels put fields under labels
    layout->addLayout(form);
    size_t count;
    const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
    QStringList names;
    for (size_t i = 0; i < count; ++i)
        names << list[i]->name;
    auto *summary = new QLabel;
    summary->setWordWrap(true);
    QComboBox *algorithm = combo(
        names, [&s, names] { return std::max(0, int(names.indexOf(QString::fromStdString(s.algorithm)))); },
        [this, &s, names](int i) {
            s.algorithm = names[i].toStdString();
            emit changed();
        });
    for (size_t i = 0; i < count; ++i)
        algorithm->setItemData(int(i), QString(list[i]->summary), Qt::ToolTipRole);
    on_sync([&s, summary] {
        const oit_algorithm_ops *ops = oit_algorithm_find(s.algorithm.c_str());
        summary->setText(ops ? QString::fromStdString(algorithm_summary(*ops)) : "");
    });
    form->addRow("algorithm", algorithm);
    form->addRow(summary);
    // the options only some algorithms read (the core's capabilities: oit_algorithm_reads), shown for those
    QGroupBox *layers_box;
    QFormLayout *layers = group(layout, "Layers and memory", &layers_box);
    auto reads = [](unsigned option) {
        return [option](const QString &algorithm) { return algorithm_reads(algorithm, option); };
    };
    QComboBox *sort = combo(words(OIT_SETTING_SORT), [&s] { return int(s.config.ll_sort); },
                            [this, &s](int i) {
                                s.config.ll_sort = oit_ll_sort(i);
                                emit edited();
                            });
    layers->addRow("sort", sort);
    show_row_when(layers, sort, reads(OIT_OPTION_SORT));
    auto *memory = spin_box(1, 1 << 22, [&s] { return int(s.config.max_memory_bytes / (1024 * 1024)); },
                            [this, &s](int mb) {
                                s.config.max_memory_bytes = uint64_t(mb) * 1024 * 1024;
                                emit edited();
                            });
    memory->setSuffix(" MB");
    // 0 is "no cap" (peel until nothing is left), shown as "none"
    auto *layer_cap = spin_box(0, OIT_PEEL_LAYER_CAP_MAX, [&s] { return s.config.max_layers; },
                               [this, &s](int n) {
                                   s.config.max_layers = n;
                                   emit edited();
                               });
    layer_cap->setSpecialValueText("none");
    layers->addRow("layer cap", layer_cap);
    show_row_when(layers, layer_cap, reads(OIT_OPTION_MAX_LAYERS));
    // the approximations' parameters (OIT_OPTION_LAYERS / _MOMENTS / _WAVELET_RANK in their capabilities)
    auto *approx_layers = spin_box(1, OIT_LAYERS_MAX,
                                   [&s] { return s.config.layers == 0 ? OIT_LAYERS_DEFAULT : s.config.layers; },
                                   [this, &s](int n) {
                                       s.config.layers = n;
                                       emit edited();
                                   });
    layers->addRow("layers", approx_layers);
    show_row_when(layers, approx_layers, reads(OIT_OPTION_LAYERS));
    auto *moments = combo(words(OIT_SETTING_MOMENTS),
                          [&s] {
                              return s.config.moments == OIT_MOMENTS_DEFAULT ? 0
                                                                             : int(s.config.moments) - OIT_MOMENTS_POWER4;
                          },
                          [this, &s](int i) {
                              s.config.moments = oit_moments(i + OIT_MOMENTS_POWER4);
                              emit edited();
                          });
    layers->addRow("moments", moments);
    show_row_when(layers, moments, reads(OIT_OPTION_MOMENTS));
    auto *wavelet_rank = spin_box(1, OIT_WAVELET_RANK_MAX,
                                  [&s] { return s.config.wavelet_rank == 0 ? OIT_WAVELET_RANK_DEFAULT : s.config.wavelet_rank; },
                                  [this, &s](int r) {
                                      s.config.wavelet_rank = r;
                                      emit edited();
                                  });
    layers->addRow("wavelet rank", wavelet_rank);
    show_row_when(layers, wavelet_rank, reads(OIT_OPTION_WAVELET_RANK));
    layers->addRow("memory budget", memory);
    show_row_when(layers, memory, reads(OIT_OPTION_MAX_MEMORY));
    show_group_when_used(layers_box);

    // what every algorithm does
    QFormLayout *look = group(layout, "Shading and import");
    look->addRow("shading", combo(words(OIT_SETTING_SHADING), [&s] { return int(s.shading); },
                                  [this, &s](int i) {
                                      s.shading = oit_shading_mode(i);
                                      emit edited();
                                  }));
    auto *background = new QPushButton;
    connect(background, &QPushButton::clicked, this, [this, &s] {
        QColor c = QColorDialog::getColor(QColor::fromRgbF(s.background[0], s.background[1], s.background[2]),
                                          window(), "Background (--background)");
        if (!c.isValid())
            return;
        s.background[0] = float(c.redF());
        s.background[1] = float(c.greenF());
        s.background[2] = float(c.blueF());
        emit changed();
    });
    on_sync([&s, background] {
        background->setIcon(swatch(s.background));
        background->setText(colour_text(s.background));
    });
    look->addRow("background", background);
    // anti-aliasing (--samples; render_worker.h has Auto's rule)
    static const int sample_values[] = {0, 1, 4, 8, 16};
    auto *samples = combo({"auto (4 once the view is still)", "off", "4 samples", "8 samples", "16 samples"},
                          [&s] {
                              for (int i = 0; i < 5; ++i)
                                  if (sample_values[i] == s.samples)
                                      return i;
                              return 0;
                          },
                          [this, &s](int i) {
                              s.samples = sample_values[i];
                              emit edited();
                          });
    samples->setObjectName("samples");
    look->addRow("anti-aliasing", samples);
    // items in oit_tessellation_level's order, then a deflection in millimetres a preset gave
    auto *tessellation = combo({"normal", "coarse", "fine", "the preset's (millimetres)"},
                               [&s] { return s.import.linear_deflection_mm > 0 ? 3 : int(s.import.tessellation); },
                               [this, &s](int i) {
                                   if (i >= OIT_TESSELLATION_LEVEL_COUNT)
                                       return; // (a number comes from a preset only)
                                   s.import.tessellation = oit_tessellation_level(i);
                                   s.import.linear_deflection_mm = 0.0;
                                   emit tessellation_changed();
                               });
    tessellation->setObjectName("tessellation");
    on_sync([&s, tessellation] {
        tessellation->setItemText(3, s.import.linear_deflection_mm > 0
                                         ? QString("%1 mm (the preset's)").arg(s.import.linear_deflection_mm)
                                         : QString("the preset's (millimetres)"));
    });
    look->addRow("tessellation", tessellation);
    // the workbench's own: what renders while the camera or a slider moves (render_worker.h)
    QStringList previews{"auto (ll coarse, or wboit)", "same as chosen"};
    QStringList preview_values{"auto", "same"};
    for (const QString &name : names)
        previews << name, preview_values << name;
    auto *preview = combo(previews,
                          [&s, preview_values] {
                              return std::max(0, int(preview_values.indexOf(QString::fromStdString(s.preview_algorithm))));
                          },
                          [this, &s, preview_values](int i) {
                              s.preview_algorithm = preview_values[i].toStdString();
                              emit edited();
                          });
    preview->setObjectName("preview_algorithm");
    preview->setToolTip("While the camera or a slider moves and the chosen algorithm's full frames are slow, "
                        "frames come from this fast stand-in at a coarse scale, and the chosen algorithm "
                        "refines when the input rests. auto: ll, or wboit where ll's fill is too slow; same as "
                        "chosen: the chosen algorithm, coarse");
    look->addRow("preview while moving", preview);
    layout->addStretch(1);
}
