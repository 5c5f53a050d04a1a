// main_window_measure.cpp: Measure ▸ Measure distance (issue 28, part 3): the
// mode, its menu and what a click does in it. The click's pick is pick_at's
// (main_window.cpp): the same model, frame, opacities (and so hidden parts and
// sections) and rank; only what it does with the part differs. The state, the
// text and the overlay are MeasureTool's (measure_tool.h).
#include "main_window.h"
#include "measure_tool.h"
#include "pick.h"
#include "render_view.h"

#include <QAction>
#include <QApplication>
#include <QClipboard>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>

void MainWindow::build_measure_menu()
{
    measure_ = std::make_unique<MeasureTool>();
    view_->set_measure(measure_.get());
    QMenu *menu = menuBar()->addMenu("&Measure");
    measure_action_ = menu->addAction("&Measure distance");
    measure_action_->setObjectName("measure_distance");
    measure_action_->setCheckable(true);
    measure_action_->setShortcut(QKeySequence("M"));
    measure_action_->setToolTip("click two points on surfaces (the part a click would pick): their distance "
                                "in the view; Esc leaves");
    connect(measure_action_, &QAction::toggled, this, [this](bool on) { measuring_toggled(on); });
    copy_measure_action_ = menu->addAction("&Copy measurement");
    copy_measure_action_->setObjectName("copy_measurement");
    copy_measure_action_->setShortcut(QKeySequence::Copy);
    copy_measure_action_->setToolTip("the distance, both points and their parts as one line of text");
    copy_measure_action_->setEnabled(false);
    connect(copy_measure_action_, &QAction::triggered, this, [this] { copy_measurement(); });
    QAction *clear = menu->addAction("C&lear measurement");
    connect(clear, &QAction::triggered, this, [this] {
        measure_->clear();
        copy_measure_action_->setEnabled(false);
        view_->update();
    });
    menu->setToolTipsVisible(true);
    // a new model: its units, no points
    connect(this, &MainWindow::model_loaded, this, [this] {
        measure_->set_model(model_.get());
        copy_measure_action_->setEnabled(false);
        view_->update();
    });
}

void MainWindow::set_measuring(bool on)
{
    if (measure_action_)
        measure_action_->setChecked(on); // toggled: measuring_toggled when it changes
}

void MainWindow::measuring_toggled(bool on)
{
    if (on) {
        view_->setCursor(Qt::CrossCursor);
        status_label_->setText("measure: click the first point (Esc leaves)");
    } else {
        // the line stays in the Messages; the view drops the markers
        const QString last = measure_->text();
        measure_->clear();
        copy_measure_action_->setEnabled(false);
        view_->unsetCursor();
        view_->update();
        status_label_->setText(last.isEmpty() ? "left measure mode" : "left measure mode: " + last);
    }
}

bool MainWindow::measuring() const
{
    return measure_action_ && measure_action_->isChecked();
}

void MainWindow::measure_pick(const ContributorPick &hit, const std::string &error)
{
    if (!error.empty()) {
        status_label_->setText(QString::fromStdString("measure: " + error));
        return;
    }
    if (hit.component < 0) {
        status_label_->setText("measure: nothing under the pointer (no point set)");
        return;
    }
    char path[1024];
    oit_model_component_path(model_.get(), uint32_t(hit.component), path, sizeof path);
    const QString line = measure_->add_point(hit.component, QString::fromUtf8(path), hit.point);
    status_label_->setText(line);
    if (measure_->complete())
        log_message("measure", line);
    copy_measure_action_->setEnabled(measure_->complete());
    view_->update();
}

QString MainWindow::copy_measurement()
{
    const QString line = measure_->text();
    if (line.isEmpty()) {
        status_label_->setText("measure: pick two points first (Measure ▸ Measure distance, M)");
        return line;
    }
    QApplication::clipboard()->setText(line);
    status_label_->setText("copied: " + line);
    log_message("copied", line);
    return line;
}
