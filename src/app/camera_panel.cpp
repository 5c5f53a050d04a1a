// camera_panel.cpp: see camera_panel.h.
#include "camera_panel.h"

#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QListWidget>
#include <QPushButton>
#include <QShortcut>

#include <algorithm>

CameraPanel::CameraPanel(SettingsModel &model, QWidget *parent) : SettingsPanel(model, parent)
{
    Camera &c = camera();
    auto *form = new QFormLayout(this);
    form->setRowWrapPolicy(QFormLayout::WrapLongRows); // narrow panels put fields under labels
    form->addRow("mode", combo({"orbit (left drag turns, wheel zoom, right-drag pan)", "walk (W/A/S/D, Q/E, mouse look)"},
                               [&c] { return c.mode() == Camera::Mode::Walk ? 1 : 0; },
                               [this, &c](int i) {
                                   c.set_mode(i ? Camera::Mode::Walk : Camera::Mode::Orbit);
                                   emit changed();
                               }));
    QComboBox *orbit = combo({"turntable (about the up axis, no roll)", "trackball (free, rolls)"},
                             [&c] { return c.orbit_style == Camera::Orbit::Trackball ? 1 : 0; },
                             [this, &c](int i) {
                                 c.orbit_style = i ? Camera::Orbit::Trackball : Camera::Orbit::Turntable;
                                 emit changed();
                             });
    orbit->setObjectName("orbit_style");
    orbit->setToolTip("orbit: what a left drag does. Turntable: sideways turns about the up axis, up and down "
                      "tilts (short of the poles), the up axis stays up; trackball: turns freely, and rolls");
    form->addRow("orbit", orbit);
    QComboBox *up = combo({"Y", "Z"}, [&c] { return c.up == Camera::Up::Z ? 1 : 0; },
                          [this, &c](int i) {
                              c.up = i ? Camera::Up::Z : Camera::Up::Y;
                              emit changed();
                              emit reset_camera_requested(); // the default view, upright about the new axis
                          });
    up->setObjectName("up_axis");
    up->setToolTip("up axis: the model's vertical axis, for the turntable, the standard views, Reset and walk "
                   "(Y: glTF, OBJ; Z: most CAD and IFC files)");
    form->addRow("up axis", up);
    form->addRow("projection", combo({"perspective", "orthographic"}, [&c] { return c.orthographic ? 1 : 0; },
                                     [this, &c](int i) {
                                         c.orthographic = i == 1;
                                         emit changed();
                                     }));
    form->addRow("field of view (degrees)", slider_row(5, 120, 1, [&c] { return c.fov_degrees; },
                                                       [this, &c](float v) {
                                                           c.fov_degrees = v;
                                                           emit edited();
                                                       }));
    auto *reset = new QPushButton("Reset camera (Home)");
    reset->setToolTip("frame the whole model again from the default three-quarter view");
    connect(reset, &QPushButton::clicked, this, &CameraPanel::reset_camera_requested);
    form->addRow(reset);
    list_ = new QListWidget;
    list_->setObjectName("saved_views");
    list_->setToolTip("double-click goes to a view; F2 or a slow second click renames it; Delete removes it");
    auto *save = new QPushButton("Save view");
    save->setToolTip("keep the camera's pose in the list below, with the model");
    auto *restore = new QPushButton("Go to view");
    restore->setToolTip("return to the pose selected in the list");
    auto *remove = new QPushButton("Delete");
    remove->setObjectName("delete_view");
    remove->setToolTip("forget the view selected in the list");
    connect(save, &QPushButton::clicked, this, [this] { save_view(); });
    connect(restore, &QPushButton::clicked, this, [this] { go_to_view(list_->currentRow()); });
    connect(list_, &QListWidget::itemDoubleClicked, this, [this] { go_to_view(list_->currentRow()); });
    connect(remove, &QPushButton::clicked, this, [this] { delete_view(list_->currentRow()); });
    auto *delete_key = new QShortcut(QKeySequence::Delete, list_, nullptr, nullptr, Qt::WidgetShortcut);
    connect(delete_key, &QShortcut::activated, this, [this] { delete_view(list_->currentRow()); });
    connect(list_, &QListWidget::itemChanged, this, [this](QListWidgetItem *item) {
        if (filling_)
            return;
        int row = list_->row(item);
        if (!rename_view(row, item->text()))
            refill(); // an empty name: the old one comes back
    });
    auto *row = new QHBoxLayout;
    for (QPushButton *button : {save, restore, remove}) {
        // its text, not the style's 80 px: the narrow panel puts the row under its label
        button->setMinimumWidth(button->fontMetrics().horizontalAdvance(button->text()) + 12);
        row->addWidget(button);
    }
    form->addRow("saved views", row);
    form->addRow(list_);
}

void CameraPanel::refill()
{
    filling_ = true;
    int current = list_->currentRow();
    list_->clear();
    for (const SavedView &view : saved_) {
        auto *item = new QListWidgetItem(QString::fromStdString(view.name), list_);
        item->setFlags(item->flags() | Qt::ItemIsEditable);
    }
    list_->setCurrentRow(std::min(current, list_->count() - 1));
    filling_ = false;
}

void CameraPanel::set_saved_views(const std::vector<SavedView> &views)
{
    saved_ = views;
    refill();
}

void CameraPanel::save_view(const QString &name)
{
    std::string chosen = name.trimmed().toStdString();
    for (int n = 1; chosen.empty(); ++n) {
        std::string candidate = "view " + std::to_string(n);
        bool taken = false;
        for (const SavedView &view : saved_)
            taken = taken || view.name == candidate;
        if (!taken)
            chosen = candidate;
    }
    saved_.push_back({chosen, camera()});
    refill();
    list_->setCurrentRow(list_->count() - 1);
    emit saved_views_changed();
}

bool CameraPanel::rename_view(int row, const QString &name)
{
    if (row < 0 || size_t(row) >= saved_.size() || name.trimmed().isEmpty())
        return false;
    if (saved_[size_t(row)].name == name.trimmed().toStdString())
        return true;
    saved_[size_t(row)].name = name.trimmed().toStdString();
    refill();
    emit saved_views_changed();
    return true;
}

bool CameraPanel::delete_view(int row)
{
    if (row < 0 || size_t(row) >= saved_.size())
        return false;
    saved_.erase(saved_.begin() + row);
    refill();
    emit saved_views_changed();
    return true;
}

bool CameraPanel::go_to_view(int row)
{
    if (row < 0 || size_t(row) >= saved_.size())
        return false;
    // the pose, mode, projection and fov; the model's centre and radius stay
    const Camera &saved = saved_[size_t(row)].camera;
    Camera &c = camera();
    c.set_mode(saved.mode());
    c.orthographic = saved.orthographic;
    c.fov_degrees = saved.fov_degrees;
    c.eye = saved.eye;
    c.orientation = saved.orientation;
    c.target = saved.target;
    emit changed();
    return true;
}
