// compare_panel.cpp: see compare_panel.h.
#include "compare_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFontDatabase>
#include <QFormLayout>
#include <QLabel>

#include <algorithm>

ComparePanel::ComparePanel(RenderSettings &settings, QWidget *parent) : QWidget(parent), settings_(settings)
{
    auto *form = new QFormLayout(this);
    form->setRowWrapPolicy(QFormLayout::WrapLongRows); // narrow panels put fields under labels

    error_ = new QCheckBox("error against reference");
    error_->setObjectName("error_view");
    error_->setToolTip("error against reference (--error-vs-reference): show each pixel's largest channel difference against the CPU reference's image of "
                       "the same frame (black: exact; blue to red: 1 to 64+, logarithmic), with rmse, psnr, "
                       "ssim, max, the share over 2 and the mean FLIP in the status line. The reference renders on the "
                       "worker after each full frame (cached per camera, size and settings); coarse frames "
                       "show the plain image. View ▸ Error against reference (R)");
    form->addRow(error_);

    split_ = new QComboBox;
    split_->setObjectName("split_mode");
    split_->addItems({"off", "wipe line", "side by side"});
    split_->setToolTip("two algorithms, same camera: A (the Algorithm tab's) left of a wipe line you drag, B "
                       "right of it; or side by side, each at half the view's width. View ▸ Split view (X), "
                       "Side by side");
    form->addRow("split view", split_);

    algorithm_b_ = new QComboBox;
    algorithm_b_->setObjectName("split_algorithm");
    size_t count = 0;
    const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
    for (size_t i = 0; i < count; ++i) {
        algorithm_b_->addItem(list[i]->name);
        algorithm_b_->setItemData(int(i), QString(list[i]->summary), Qt::ToolTipRole);
    }
    algorithm_b_->setToolTip("side B's algorithm (right of the line); its options are the shared settings, "
                             "and what it cannot express it leaves out (the Messages say so)");
    form->addRow("algorithm B", algorithm_b_);

    wipe_ = new QDoubleSpinBox;
    wipe_->setObjectName("wipe");
    wipe_->setRange(0.0, 1.0);
    wipe_->setDecimals(3);
    wipe_->setSingleStep(0.05);
    wipe_->setToolTip("where the wipe line is, as a share of the view's width (drag the line in the view)");
    form->addRow("wipe line", wipe_);

    figures_ = new QLabel;
    figures_->setObjectName("error_figures");
    figures_->setWordWrap(true);
    figures_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    figures_->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
    form->addRow(figures_);
    auto *note = new QLabel("Export PNG and Copy as command render side A; the command line has no "
                            "split view. With the error view the command adds --error-vs-reference and "
                            "--error-map.");
    note->setWordWrap(true);
    form->addRow(note);

    connect(error_, &QCheckBox::toggled, this, [this](bool on) {
        if (syncing_)
            return;
        settings_.error_view = on;
        emit changed();
    });
    connect(split_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this](int i) {
        if (syncing_ || i < 0)
            return;
        settings_.split = SplitMode(i);
        emit changed();
    });
    connect(algorithm_b_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this](int i) {
        if (syncing_ || i < 0)
            return;
        settings_.split_algorithm = algorithm_b_->itemText(i).toStdString();
        emit changed();
    });
    connect(wipe_, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, [this](double v) {
        if (syncing_)
            return;
        settings_.wipe = float(v);
        emit wipe_changed();
    });
    sync();
}

void ComparePanel::sync()
{
    syncing_ = true;
    error_->setChecked(settings_.error_view);
    split_->setCurrentIndex(int(settings_.split));
    int b = algorithm_b_->findText(QString::fromStdString(settings_.split_algorithm));
    algorithm_b_->setCurrentIndex(std::max(0, b));
    algorithm_b_->setEnabled(settings_.split != SplitMode::Off);
    wipe_->setValue(double(settings_.wipe));
    wipe_->setEnabled(settings_.split == SplitMode::Wipe);
    if (!settings_.error_view)
        figures_->clear();
    syncing_ = false;
}

void ComparePanel::set_figures(const QString &text)
{
    figures_->setText(text);
}
