// main_window_selection.cpp: the selection made visible (issue 27): the Parts
// menu's Highlight selection (the selected parts tinted in the view through
// the core's highlight, oit_local_modulation.component_highlight, which the
// reference reproduces) and Fade others (ghosting, one undo step). Picks
// select in the list (MainWindow::pick_at); the list's keys and sliders reach
// every selected row (parts_panel.cpp).
#include "main_window.h"
#include "parts_panel.h"
#include "render_view.h"
#include "settings_model.h"

#include <QAction>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>

#include <algorithm>
#include <memory>

void MainWindow::build_parts_menu()
{
    QMenu *parts = menuBar()->addMenu("&Parts");
    highlight_action_ = parts->addAction("&Highlight selection");
    highlight_action_->setObjectName("highlight_selection");
    highlight_action_->setCheckable(true);
    highlight_action_->setChecked(true);
    highlight_action_->setToolTip("tint the selected parts in the view (exports leave it out unless asked)");
    connect(highlight_action_, &QAction::toggled, this, [this] { update_highlight(); });
    fade_action_ = parts->addAction("&Fade others");
    fade_action_->setObjectName("fade_others");
    fade_action_->setShortcut(QKeySequence("G"));
    fade_action_->setToolTip("ghosting: every part not selected to the opacity beside the parts list (default "
                             "10%), in one undo step");
    connect(fade_action_, &QAction::triggered, this, [this] { fade_others(); });
    parts->setToolTipsVisible(true);
    parts_panel_->add_context_action(fade_action_);
    parts_panel_->add_context_action(highlight_action_);
    connect(parts_panel_, &PartsPanel::fade_requested, this, [this] { fade_others(); });
    connect(parts_panel_, &PartsPanel::selection_changed, this, [this] { update_highlight(); });
}

void MainWindow::update_highlight()
{
    view_->set_highlight(highlight_selection() ? parts_panel_->selected_parts() : std::vector<int>());
}

void MainWindow::set_highlight_selection(bool on)
{
    highlight_action_->setChecked(on);
}

bool MainWindow::highlight_selection() const
{
    return highlight_action_ && highlight_action_->isChecked();
}

bool MainWindow::fade_others()
{
    const float alpha = float(parts_panel_->fade_percent()) / 100.0f;
    // one undo step of its own: not merged with a slider moved just before, nor with what follows
    settings_->close_step();
    const bool changed = parts_panel_->fade_others(alpha); // parts_changed: the settings and a frame
    settings_->close_step();
    if (parts_panel_->selected_parts().empty())
        status_label_->setText("Fade others: select the parts to keep first");
    else if (changed)
        status_label_->setText(QString("faded the parts not selected to %1%").arg(parts_panel_->fade_percent()));
    return changed;
}

bool MainWindow::select_parts_named(const QStringList &names, QString &error)
{
    if (!model_) {
        error = "no model is loaded";
        return false;
    }
    std::vector<bool> chosen(model_->component_count, false);
    std::unique_ptr<bool[]> matched(new bool[model_->component_count]);
    for (const QString &name : names) {
        std::fill(matched.get(), matched.get() + model_->component_count, false);
        if (oit_model_match_parts(model_.get(), name.toUtf8().constData(), matched.get()) == 0) {
            error = "no part or assembly named '" + name + "'";
            return false;
        }
        for (uint32_t i = 0; i < model_->component_count; ++i)
            chosen[i] = chosen[i] || matched[i];
    }
    std::vector<int> parts;
    for (uint32_t i = 0; i < model_->component_count; ++i)
        if (chosen[i])
            parts.push_back(int(i));
    parts_panel_->select_parts(parts); // selection_changed: the highlight follows
    return true;
}
