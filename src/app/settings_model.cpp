// settings_model.cpp: see settings_model.h.
#include "settings_model.h"

#include <QTimer>
#include <QUndoCommand>
#include <QUndoStack>

// One undo step: the settings before it. The change itself is already made
// when the step is pushed (the controls edit the settings in place), so the
// first redo() does nothing; undo() keeps the settings it replaces for redo().
class SettingsModel::Change : public QUndoCommand {
public:
    Change(SettingsModel &model, const RenderSettings &before, bool coalesces)
        : QUndoCommand("settings change"), model_(model), before_(before), coalesces_(coalesces)
    {
    }
    int id() const override { return 1; }
    // A change while the previous one still coalesces is part of its step:
    // the step keeps its "before" (the settings as they were before the drag).
    bool mergeWith(const QUndoCommand *other) override
    {
        return static_cast<const Change *>(other)->coalesces_;
    }
    void undo() override
    {
        after_ = model_.settings_;
        model_.restore(before_);
    }
    void redo() override
    {
        if (pushed_) {
            pushed_ = false;
            return;
        }
        before_ = model_.settings_;
        model_.restore(after_);
    }

private:
    SettingsModel &model_;
    RenderSettings before_, after_;
    bool coalesces_;
    bool pushed_ = true;
};

SettingsModel::SettingsModel(QObject *parent) : QObject(parent)
{
    stack_ = new QUndoStack(this);
    stack_->setUndoLimit(kUndoLimit);
    coalesce_timer_ = new QTimer(this);
    coalesce_timer_->setSingleShot(true);
    coalesce_timer_->setInterval(kUndoCoalesceMs);
    reset_history();
}

SettingsModel::~SettingsModel() = default;

void SettingsModel::camera_edited()
{
    emit camera_changed();
}

std::string SettingsModel::key(const RenderSettings &settings) const
{
    // the wipe line is where one looks, like the camera: not a step of its own
    RenderSettings s = settings;
    s.wipe = 0.5f;
    return preset_to_json(s, Camera(), model_);
}

void SettingsModel::record_change()
{
    if (restoring_)
        return;
    std::string now = key(settings_);
    if (now == committed_key_)
        return;
    // a merged step is deleted at once; a new one ends the redo history
    stack_->push(new Change(*this, committed_, coalesce_timer_->isActive()));
    committed_ = settings_;
    committed_key_ = now;
    coalesce_timer_->start();
}

void SettingsModel::close_step()
{
    coalesce_timer_->stop();
}

void SettingsModel::reset_history()
{
    stack_->clear();
    committed_ = settings_;
    committed_key_ = key(settings_);
    coalesce_timer_->stop();
}

bool SettingsModel::can_undo() const
{
    return stack_->canUndo();
}

bool SettingsModel::can_redo() const
{
    return stack_->canRedo();
}

bool SettingsModel::undo()
{
    record_change(); // a change still coalescing is a step of its own
    if (!stack_->canUndo())
        return false;
    stack_->undo();
    return true;
}

bool SettingsModel::redo()
{
    if (!stack_->canRedo())
        return false;
    stack_->redo();
    return true;
}

void SettingsModel::restore(const RenderSettings &settings)
{
    restoring_ = true;
    float wipe = settings_.wipe; // not a setting (key())
    settings_ = settings;
    settings_.wipe = wipe;
    committed_ = settings;
    committed_key_ = key(settings);
    coalesce_timer_->stop(); // the next change is a step of its own
    emit restored();
    restoring_ = false;
}
