// test_settings_model.cpp: the settings model's undo history on its own (no
// window, no GL): a slider drag is one step however long it lasts, as long as
// its changes come less than SettingsModel::kUndoCoalesceMs apart; a pause
// starts a new step; undo and redo end the coalescing; the wipe line and the
// camera are not steps. About 3 s (the waits let the coalescing window close).
#include <QSignalSpy>
#include <QUndoStack>
#include <QtTest/QtTest>

#include "settings_model.h"

class SettingsModelTest : public QObject {
    Q_OBJECT
private:
    // a change as a control makes it: the setting, then the record
    static void set_alpha(SettingsModel &model, float alpha)
    {
        model.render_settings().alpha = alpha;
        model.record_change();
    }
    // long enough for the coalescing window to close (the event loop runs its timer)
    static void pause() { QTest::qWait(SettingsModel::kUndoCoalesceMs + 150); }

private slots:
    void changes_in_quick_succession_are_one_step()
    {
        SettingsModel model;
        QVERIFY(!model.can_undo());
        set_alpha(model, 0.2f);
        set_alpha(model, 0.3f);
        set_alpha(model, 0.4f);
        QCOMPARE(model.undo_stack()->count(), 1);
        QVERIFY(model.undo());
        QCOMPARE(model.render_settings().alpha, 0.5f); // before the first of them
        QVERIFY(!model.undo());
        QVERIFY(model.redo());
        QCOMPARE(model.render_settings().alpha, 0.4f); // after the last
        QVERIFY(!model.redo());
    }

    void a_drag_longer_than_the_window_is_still_one_step()
    {
        // the window runs from the last change, not the first
        SettingsModel model;
        QElapsedTimer clock;
        clock.start();
        float alpha = 0.5f;
        while (clock.elapsed() < 2 * SettingsModel::kUndoCoalesceMs) {
            set_alpha(model, alpha -= 0.01f);
            QTest::qWait(SettingsModel::kUndoCoalesceMs / 4);
        }
        QCOMPARE(model.undo_stack()->count(), 1);
        QVERIFY(model.undo());
        QCOMPARE(model.render_settings().alpha, 0.5f);
    }

    void a_pause_starts_a_new_step()
    {
        SettingsModel model;
        set_alpha(model, 0.2f);
        pause();
        set_alpha(model, 0.3f);
        model.render_settings().algorithm = "dp"; // with it: the same step
        model.record_change();
        QCOMPARE(model.undo_stack()->count(), 2);
        QVERIFY(model.undo());
        QCOMPARE(model.render_settings().alpha, 0.2f);
        QCOMPARE(QString::fromStdString(model.render_settings().algorithm), QString("ll"));
        QVERIFY(model.undo());
        QCOMPARE(model.render_settings().alpha, 0.5f);
    }

    void undo_and_redo_end_the_coalescing()
    {
        SettingsModel model;
        set_alpha(model, 0.2f);
        pause();
        set_alpha(model, 0.3f);
        QVERIFY(model.undo()); // 0.2
        QVERIFY(model.redo()); // 0.3, and at once a new change:
        set_alpha(model, 0.4f);
        QVERIFY(model.undo()); // a step of its own, not part of the redone one
        QCOMPARE(model.render_settings().alpha, 0.3f);
        QVERIFY(model.undo());
        QCOMPARE(model.render_settings().alpha, 0.2f);
        // a change right after an undo is a new step too, and ends the redo history
        set_alpha(model, 0.6f);
        QVERIFY(!model.can_redo());
        QVERIFY(model.undo());
        QCOMPARE(model.render_settings().alpha, 0.2f);
    }

    void undo_takes_a_change_not_yet_recorded()
    {
        // settings changed by code without a record (a preset's parts, a test):
        // undo records it first, so redo returns to it
        SettingsModel model;
        set_alpha(model, 0.2f);
        model.render_settings().alpha = 0.3f;
        QVERIFY(model.undo());
        QCOMPARE(model.render_settings().alpha, 0.5f);
        QVERIFY(model.redo());
        QCOMPARE(model.render_settings().alpha, 0.3f);
    }

    void the_wipe_line_and_the_camera_are_not_steps()
    {
        SettingsModel model;
        QSignalSpy restored(&model, &SettingsModel::restored);
        model.render_settings().wipe = 0.25f;
        model.camera().fov_degrees = 30.0f;
        model.record_change();
        QVERIFY(!model.can_undo());
        set_alpha(model, 0.2f);
        model.render_settings().wipe = 0.75f;
        QVERIFY(model.undo());
        QCOMPARE(restored.count(), 1);
        QCOMPARE(model.render_settings().alpha, 0.5f);
        QCOMPARE(model.render_settings().wipe, 0.75f); // where it is, not where it was
        QCOMPARE(model.camera().fov_degrees, 30.0f);
    }

    void reset_forgets_the_history()
    {
        SettingsModel model;
        set_alpha(model, 0.2f);
        model.reset_history();
        QVERIFY(!model.can_undo() && !model.undo());
        set_alpha(model, 0.3f); // the window closed with the reset: a step of its own
        QVERIFY(model.undo());
        QCOMPARE(model.render_settings().alpha, 0.2f);
    }
};

QTEST_GUILESS_MAIN(SettingsModelTest)
#include "test_settings_model.moc"
