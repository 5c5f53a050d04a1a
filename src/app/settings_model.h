// settings_model.h: what the window edits, in one place: the render settings
// (settings.h) and the camera, with the settings' undo history. The panels,
// the menus and the render view read and change them here; undo and redo are
// Qt's QUndoStack, a slider drag or typed number coalescing into one step
// (QUndoCommand::mergeWith).
#pragma once

#include <QObject>

#include <string>

#include "camera.h"
#include "oit.h"
#include "settings.h"

class QTimer;
class QUndoStack;

class SettingsModel : public QObject {
    Q_OBJECT
public:
    // Changes within this many milliseconds of each other are one undo step.
    static constexpr int kUndoCoalesceMs = 600;
    // The undo steps kept (the oldest go first).
    static constexpr int kUndoLimit = 200;

    explicit SettingsModel(QObject *parent = nullptr);
    ~SettingsModel() override;

    // Changed in place; record_change() (the window's render_now) makes it an undo step.
    RenderSettings &render_settings() { return settings_; }
    const RenderSettings &render_settings() const { return settings_; }
    // Not part of the undo history: where one looks from, like the wipe line.
    Camera &camera() { return camera_; }
    const Camera &camera() const { return camera_; }
    // After the camera changed: its controls follow (camera_changed()).
    void camera_edited();

    // The loaded model (nullptr: none): the parts' settings are named by its
    // parts, and the focus controls start from its bounds.
    void set_model(const oit_model *model) { model_ = model; }
    const oit_model *model() const { return model_; }

    // The settings changed: one undo step, or part of the step still
    // coalescing (the previous change came less than kUndoCoalesceMs ago).
    void record_change();
    // Undo / redo a step; false when there is none. The settings are
    // replaced (the wipe line stays) and restored() follows.
    bool undo();
    bool redo();
    // Forget the history: the current settings are where undo stops.
    void reset_history();
    // The next change is an undo step of its own, not merged with the last
    // (a discrete action such as Fade others, right after a slider).
    void close_step();
    bool can_undo() const;
    bool can_redo() const;
    QUndoStack *undo_stack() const { return stack_; }

signals:
    // Undo or redo replaced the settings: the controls and the view follow.
    void restored();
    void camera_changed();

private:
    class Change;
    // The settings as their preset text (the camera and the wipe line are not settings here).
    std::string key(const RenderSettings &settings) const;
    void restore(const RenderSettings &settings);

    RenderSettings settings_;
    Camera camera_;
    const oit_model *model_ = nullptr;
    QUndoStack *stack_ = nullptr;
    QTimer *coalesce_timer_ = nullptr; // running: the next change joins the last step
    RenderSettings committed_;         // the settings the last step ended with
    std::string committed_key_;
    bool restoring_ = false;
};
