// sections_panel.cpp: see sections_panel.h.
#include "sections_panel.h"
#include "section_overlay.h"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>

namespace {

// Six decimals: a normal from the view is not noise in the command's numbers.
double tidy(double value)
{
    double rounded = std::round(value * 1e6) / 1e6;
    return rounded == 0.0 ? 0.0 : rounded; // no -0
}

QString plane_text(int index, const SectionPlane &plane)
{
    return QString("%1: n (%2, %3, %4), d %5")
        .arg(index + 1)
        .arg(plane.normal[0], 0, 'g', 4)
        .arg(plane.normal[1], 0, 'g', 4)
        .arg(plane.normal[2], 0, 'g', 4)
        .arg(plane.d, 0, 'g', 5);
}

QPushButton *small_button(const QString &text, const QString &tip)
{
    auto *button = new QPushButton(text);
    button->setMinimumWidth(24); // below the style's 80 px: the panel is narrow
    button->setToolTip(tip);
    return button;
}

} // namespace

SectionsPanel::SectionsPanel(SettingsModel &model, QWidget *parent) : SettingsPanel(model, parent)
{
    RenderSettings &s = settings();
    auto *layout = new QVBoxLayout(this);

    // --- the planes
    QFormLayout *planes = group(layout, "Section planes");
    list_ = new QListWidget;
    list_->setObjectName("section_planes");
    list_->setMaximumHeight(110);
    list_->setToolTip("section planes (--section NX,NY,NZ,D, up to 6): each keeps the points p with n·p <= d; "
                      "the check box turns one off; the selected one is edited below and drawn in the view");
    planes->addRow(list_);
    auto *buttons = new QWidget;
    auto *buttons_layout = new QHBoxLayout(buttons);
    buttons_layout->setContentsMargins(0, 0, 0, 0);
    QPushButton *add = small_button("Add", "a plane through the model's centre, facing you (--section)");
    remove_ = small_button("Remove", "remove the selected plane");
    flip_ = small_button("Flip", "keep the other side: n and d negated");
    add->setObjectName("section_add");
    remove_->setObjectName("section_remove");
    flip_->setObjectName("section_flip");
    buttons_layout->addWidget(add);
    buttons_layout->addWidget(remove_);
    buttons_layout->addWidget(flip_);
    planes->addRow(buttons);
    connect(add, &QPushButton::clicked, this, [this] { add_plane(); });
    connect(remove_, &QPushButton::clicked, this, [this] { remove_plane(); });
    connect(flip_, &QPushButton::clicked, this, [this] { flip_plane(); });
    connect(list_, &QListWidget::currentRowChanged, this, [this](int row) {
        if (!syncing())
            set_active(row);
    });
    connect(list_, &QListWidget::itemChanged, this, [this, &s](QListWidgetItem *item) {
        int row = list_->row(item);
        if (syncing() || row < 0 || size_t(row) >= s.sections.size())
            return;
        bool on = item->checkState() == Qt::Checked;
        if (s.sections[size_t(row)].enabled != on) {
            s.sections[size_t(row)].enabled = on;
            emit changed();
        }
    });

    // --- the active plane
    QGroupBox *plane_group = nullptr;
    QFormLayout *plane = group(layout, "Plane", &plane_group);
    plane_box_ = plane_group;
    auto *normal_row = new QWidget;
    auto *normal_layout = new QHBoxLayout(normal_row);
    normal_layout->setContentsMargins(0, 0, 0, 0);
    for (int k = 0; k < 3; ++k) {
        auto *box = normal_[k] = new QDoubleSpinBox;
        box->setRange(-1e6, 1e6);
        box->setDecimals(4);
        box->setSingleStep(0.1);
        box->setMinimumWidth(48);
        box->setToolTip(QString("the normal's %1 (--section NX,NY,NZ,D); never all zero").arg("xyz"[k]));
        normal_layout->addWidget(box);
        connect(box, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, [this, &s, k](double v) {
            if (syncing() || active_ < 0 || size_t(active_) >= s.sections.size())
                return;
            SectionPlane &p = s.sections[size_t(active_)];
            double n[3] = {p.normal[0], p.normal[1], p.normal[2]};
            n[k] = v;
            if (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0)
                return; // refused: the box shows the last good value at the next sync
            std::copy(n, n + 3, p.normal);
            emit changed();
        });
    }
    plane->addRow("normal", normal_row);
    // the offset: a slider over the model's extent along the normal, and the number
    auto *offset_row = new QWidget;
    auto *offset_layout = new QHBoxLayout(offset_row);
    offset_layout->setContentsMargins(0, 0, 0, 0);
    offset_slider_ = new QSlider(Qt::Horizontal);
    offset_slider_->setObjectName("section_offset");
    offset_slider_->setRange(0, 1000);
    offset_slider_->setMinimumWidth(64);
    offset_slider_->setToolTip("the plane's offset d along its normal, across the model (--section's D)");
    offset_ = new QDoubleSpinBox;
    offset_->setRange(-1e12, 1e12);
    offset_->setDecimals(4);
    offset_->setMinimumWidth(56);
    offset_->setMaximumWidth(88);
    offset_->setToolTip("the plane's offset d: it keeps n·p <= d (--section's D)");
    offset_layout->addWidget(offset_slider_, 1);
    offset_layout->addWidget(offset_);
    plane->addRow("offset", offset_row);
    connect(offset_slider_, &QSlider::valueChanged, this, [this](int position) {
        if (!syncing())
            set_offset_fraction(position / 1000.0);
    });
    connect(offset_, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, [this, &s](double v) {
        if (syncing() || active_ < 0 || size_t(active_) >= s.sections.size())
            return;
        s.sections[size_t(active_)].d = v;
        emit changed();
    });
    // align to a standard view, the view direction, or a picked face
    auto *align_row = new QWidget;
    auto *align_layout = new QGridLayout(align_row);
    align_layout->setContentsMargins(0, 0, 0, 0);
    align_layout->setSpacing(2);
    const char *names[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    for (int i = 0; i < 6; ++i) {
        QPushButton *b = small_button(names[i], QString("the normal along %1: the plane removes the %2 side")
                                                    .arg(names[i], names[i]));
        b->setObjectName(QString("section_align_") + names[i]);
        align_layout->addWidget(b, 0, i);
        connect(b, &QPushButton::clicked, this, [this, i] {
            double n[3] = {0.0, 0.0, 0.0};
            n[i / 2] = i % 2 ? -1.0 : 1.0;
            align(n);
        });
    }
    QPushButton *view = small_button("View", "the normal towards the eye: the half facing you is removed");
    view->setObjectName("section_align_view");
    pick_face_ = small_button("Pick face", "then click a face in the view: the plane lies on it, facing you");
    pick_face_->setObjectName("section_pick_face");
    pick_face_->setCheckable(true);
    align_layout->addWidget(view, 1, 0, 1, 2);
    align_layout->addWidget(pick_face_, 1, 2, 1, 4);
    connect(view, &QPushButton::clicked, this, [this] { align_to_view(); });
    plane->addRow("align", align_row);

    // --- what is cut
    QFormLayout *cut = group(layout, "Cut");
    QCheckBox *caps = check_box("caps", [&s] { return s.caps; },
                                [this, &s](bool on) {
                                    s.caps = on;
                                    emit changed();
                                });
    caps->setObjectName("section_caps");
    caps->setToolTip("caps (--caps on|off): where a plane cuts a closed part, the cut face is drawn in the "
                     "part's colour and opacity; open parts get none (the Messages name them)");
    cut->addRow(caps);
    selected_only_ = new QCheckBox("cut only the selected parts");
    selected_only_->setObjectName("section_selected_only");
    selected_only_->setToolTip("--section-parts: the planes cut the parts selected in the Parts tab (at the "
                               "time of checking; check again to take a new selection); the others stay whole");
    connect(selected_only_, &QCheckBox::toggled, this, [this](bool on) {
        if (!syncing())
            cut_selected_only(on);
    });
    cut->addRow(selected_only_);
    parts_label_ = new QLabel;
    parts_label_->setWordWrap(true);
    cut->addRow(parts_label_);

    // --- the exploded view
    QFormLayout *explode = group(layout, "Exploded view");
    explode->addRow("explode", slider_row(0.0, OIT_EXPLODE_MAX, 2, [&s] { return float(s.explode); },
                                           [this, &s](float v) {
                                               s.explode = std::round(double(v) * 100.0) / 100.0;
                                               emit edited();
                                           },
                                           &explode_slider_));
    explode_slider_->setObjectName("explode");
    layout->addStretch(1);

    on_sync([this, &s] {
        if (active_ >= int(s.sections.size()))
            active_ = int(s.sections.size()) - 1;
        if (active_ < 0 && !s.sections.empty())
            active_ = 0;
        refresh_list();
        bool has = active_ >= 0;
        plane_box_->setEnabled(has);
        remove_->setEnabled(has);
        flip_->setEnabled(has);
        if (has) {
            const SectionPlane &p = s.sections[size_t(active_)];
            for (int k = 0; k < 3; ++k)
                normal_[k]->setValue(p.normal[k]);
            double low, high;
            offset_range(p, low, high);
            offset_->setSingleStep(std::max(1e-6, (high - low) / 100.0));
            offset_->setValue(p.d);
            offset_slider_->setValue(
                high > low ? int(std::lround(std::min(1.0, std::max(0.0, (p.d - low) / (high - low))) * 1000.0))
                           : 500);
        }
        selected_only_->setChecked(!s.section_parts.empty());
        if (s.section_parts.empty()) {
            parts_label_->setText("every part is cut");
        } else {
            long count = std::count_if(s.section_parts.begin(), s.section_parts.end(), [](char c) { return c != 0; });
            parts_label_->setText(count == 0 ? QString("no part selected: nothing is cut")
                                             : QString("%1 of %2 parts are cut").arg(count).arg(s.section_parts.size()));
        }
        emit active_changed(active_);
    });
}

void SectionsPanel::refresh_list()
{
    const RenderSettings &s = settings();
    QSignalBlocker block(list_);
    while (list_->count() > int(s.sections.size()))
        delete list_->takeItem(list_->count() - 1);
    for (size_t i = 0; i < s.sections.size(); ++i) {
        if (int(i) >= list_->count()) {
            auto *item = new QListWidgetItem;
            item->setFlags(item->flags() | Qt::ItemIsUserCheckable);
            list_->addItem(item);
        }
        QListWidgetItem *item = list_->item(int(i));
        item->setText(plane_text(int(i), s.sections[i]));
        item->setCheckState(s.sections[i].enabled ? Qt::Checked : Qt::Unchecked);
    }
    list_->setCurrentRow(active_);
}

void SectionsPanel::set_active(int index)
{
    if (index < -1 || index >= int(settings().sections.size()) || index == active_)
        return;
    active_ = index;
    sync(); // the controls show the plane (no setting changed)
}

void SectionsPanel::box_centre(double centre[3]) const
{
    const oit_model *model = drawn_model ? drawn_model() : nullptr;
    for (int a = 0; a < 3; ++a)
        centre[a] = 0.0;
    if (!model)
        return;
    double box_min[3], box_max[3];
    section_overlay::model_box(*model, box_min, box_max);
    for (int a = 0; a < 3; ++a)
        centre[a] = 0.5 * (box_min[a] + box_max[a]);
}

void SectionsPanel::offset_range(const SectionPlane &plane, double &low, double &high) const
{
    const oit_model *model = drawn_model ? drawn_model() : nullptr;
    if (!model) {
        low = -1.0;
        high = 1.0;
        return;
    }
    double box_min[3], box_max[3];
    section_overlay::model_box(*model, box_min, box_max);
    section_overlay::offset_range(plane.normal, box_min, box_max, low, high);
}

void SectionsPanel::add_plane()
{
    RenderSettings &s = settings();
    if (s.sections.size() >= OIT_SECTION_PLANES_MAX)
        return;
    SectionPlane plane;
    const oit_model *model = drawn_model ? drawn_model() : nullptr;
    if (model) {
        glm::dvec3 towards_eye = camera().orientation * glm::dvec3(0.0, 0.0, 1.0);
        double n[3] = {tidy(towards_eye.x), tidy(towards_eye.y), tidy(towards_eye.z)};
        if (!(n[0] != 0.0 || n[1] != 0.0 || n[2] != 0.0))
            n[0] = 1.0;
        std::copy(n, n + 3, plane.normal);
        double c[3];
        box_centre(c);
        plane.d = n[0] * c[0] + n[1] * c[1] + n[2] * c[2];
    }
    s.sections.push_back(plane);
    active_ = int(s.sections.size()) - 1;
    discrete_step();
}

void SectionsPanel::remove_plane()
{
    RenderSettings &s = settings();
    if (active_ < 0 || size_t(active_) >= s.sections.size())
        return;
    s.sections.erase(s.sections.begin() + active_);
    active_ = std::min(active_, int(s.sections.size()) - 1);
    discrete_step();
}

void SectionsPanel::flip_plane()
{
    RenderSettings &s = settings();
    if (active_ < 0 || size_t(active_) >= s.sections.size())
        return;
    SectionPlane &p = s.sections[size_t(active_)];
    for (double &n : p.normal)
        n = n == 0.0 ? 0.0 : -n;
    p.d = -p.d;
    discrete_step();
}

void SectionsPanel::align(const double n[3])
{
    RenderSettings &s = settings();
    if (active_ < 0 || size_t(active_) >= s.sections.size() || (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0))
        return;
    SectionPlane &p = s.sections[size_t(active_)];
    double c[3];
    box_centre(c);
    glm::dvec3 on = section_overlay::nearest_on_plane(p.normal, p.d, glm::dvec3(c[0], c[1], c[2]));
    std::copy(n, n + 3, p.normal);
    p.d = n[0] * on.x + n[1] * on.y + n[2] * on.z;
    discrete_step();
}

void SectionsPanel::align_to_view()
{
    glm::dvec3 towards_eye = camera().orientation * glm::dvec3(0.0, 0.0, 1.0);
    double n[3] = {tidy(towards_eye.x), tidy(towards_eye.y), tidy(towards_eye.z)};
    align(n);
}

void SectionsPanel::set_offset_fraction(double t)
{
    RenderSettings &s = settings();
    if (active_ < 0 || size_t(active_) >= s.sections.size())
        return;
    SectionPlane &p = s.sections[size_t(active_)];
    double low, high;
    offset_range(p, low, high);
    double d = low + (high - low) * std::min(1.0, std::max(0.0, t));
    // a few digits are plenty: a slider position is not a measurement
    double step = (high - low) / 1000.0;
    if (step > 0.0) {
        double unit = std::pow(10.0, std::floor(std::log10(step)) - 1.0);
        d = std::round(d / unit) * unit;
    }
    p.d = d;
    emit changed();
}

void SectionsPanel::set_plane(const double point[3], const double normal[3])
{
    RenderSettings &s = settings();
    if (active_ < 0 || size_t(active_) >= s.sections.size()) {
        if (s.sections.size() >= OIT_SECTION_PLANES_MAX)
            return;
        s.sections.push_back(SectionPlane());
        active_ = int(s.sections.size()) - 1;
    }
    if (normal[0] == 0.0 && normal[1] == 0.0 && normal[2] == 0.0)
        return;
    SectionPlane &p = s.sections[size_t(active_)];
    std::copy(normal, normal + 3, p.normal);
    p.d = normal[0] * point[0] + normal[1] * point[1] + normal[2] * point[2];
    p.enabled = true;
    discrete_step();
}

void SectionsPanel::cut_selected_only(bool on)
{
    RenderSettings &s = settings();
    const oit_model *model = drawn_model ? drawn_model() : nullptr;
    if (on && model) {
        s.section_parts.assign(model->component_count, 0);
        for (int part : selected_parts ? selected_parts() : std::vector<int>())
            if (part >= 0 && uint32_t(part) < model->component_count)
                s.section_parts[size_t(part)] = 1;
    } else {
        s.section_parts.clear();
    }
    discrete_step();
}

void SectionsPanel::discrete_step()
{
    // a step of its own: neither merged with a slider moved just before nor with one just after
    settings_model().close_step();
    emit changed();
    settings_model().close_step();
}

bool SectionsPanel::picking_face() const
{
    return pick_face_->isChecked();
}

void SectionsPanel::stop_picking_face()
{
    pick_face_->setChecked(false);
}
