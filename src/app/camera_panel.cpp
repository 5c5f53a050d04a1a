// camera_panel.cpp: see camera_panel.h.
#include "camera_panel.h"

#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QListWidget>
#include <QPushButton>

CameraPanel::CameraPanel(SettingsModel &model, QWidget *parent) : SettingsPanel(model, parent)
{
    Camera &c = camera();
    auto *form = new QFormLayout(this);
    form->setRowWrapPolicy(QFormLayout::WrapLongRows); // narrow panels put fields under labels
    form->addRow("mode", combo({"orbit (trackball, wheel zoom, right-drag pan)", "walk (W/A/S/D, Q/E, mouse look)"},
                               [&c] { return c.mode() == Camera::Mode::Walk ? 1 : 0; },
                               [this, &c](int i) {
                                   c.set_mode(i ? Camera::Mode::Walk : Camera::Mode::Orbit);
                                   emit changed();
                               }));
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
    saved_views_ = new QListWidget;
    auto *save = new QPushButton("Save view");
    save->setToolTip("keep the camera's pose in the list below");
    auto *restore = new QPushButton("Go to view");
    restore->setToolTip("return to the pose selected in the list");
    connect(save, &QPushButton::clicked, this, [this, &c] {
        saved_cameras_.push_back(c);
        saved_views_->addItem(QString("view %1").arg(saved_cameras_.size()));
    });
    auto go = [this, &c] {
        int row = saved_views_->currentRow();
        if (row >= 0 && size_t(row) < saved_cameras_.size()) {
            c = saved_cameras_[size_t(row)];
            emit changed();
        }
    };
    connect(restore, &QPushButton::clicked, this, go);
    connect(saved_views_, &QListWidget::itemDoubleClicked, this, go);
    auto *row = new QHBoxLayout;
    row->addWidget(save);
    row->addWidget(restore);
    form->addRow("saved views", row);
    form->addRow(saved_views_);
}

void CameraPanel::clear_saved_views()
{
    saved_cameras_.clear();
    saved_views_->clear();
}
