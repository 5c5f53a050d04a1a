// test_selection.cpp (app_selection): the selection made visible (issue 27) on
// the real window at 160x120 under Xvfb: the selected parts highlighted in the
// view and left out of an export unless asked; ghosting (Fade others) and bulk
// opacity as one undo step each; a pick reveals its row; a click again at the
// same pixel steps to the contributor behind.
#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QDialog>
#include <QTimer>
#include <QItemSelectionModel>
#include <QSignalSpy>
#include <QSpinBox>
#include <QStandardPaths>
#include <QTreeView>
#include <QtTest/QtTest>

#include <cstring>
#include <vector>

#include "main_window.h"
#include "parts_panel.h"
#include "pick.h"
#include "render_view.h"
#include "settings_model.h"
#include "window_test_main.h"

namespace {

const QSize view_size(160, 120);

// pixels whose colour differs (any channel)
int differing_pixels(const QImage &a, const QImage &b)
{
    QImage x = a.convertToFormat(QImage::Format_RGBA8888), y = b.convertToFormat(QImage::Format_RGBA8888);
    if (x.size() != y.size())
        return -1;
    int count = 0;
    for (int row = 0; row < x.height(); ++row)
        for (int col = 0; col < x.width(); ++col)
            count += std::memcmp(x.constScanLine(row) + 4 * col, y.constScanLine(row) + 4 * col, 3) != 0;
    return count;
}

} // namespace

class SelectionTest : public QObject {
    Q_OBJECT
private:
    MainWindow *window = nullptr;
    QString work;
    RenderSettings &settings() { return window->settings_model()->render_settings(); }
    PartsPanel *parts() { return window->parts_panel(); }
    QImage frame()
    {
        if (!QTest::qWaitFor([this] { return window->view()->settled(); }, 120000))
            qWarning("the view did not settle: %s", qPrintable(window->status_text()));
        return window->view()->last_image().convertToFormat(QImage::Format_RGBA8888);
    }
    // select these rows of the flat list (the gearbox has no tree), the first current
    void select(const std::vector<int> &rows)
    {
        QAbstractItemView *view = parts()->view();
        QItemSelectionModel *selection = view->selectionModel();
        selection->clearSelection();
        for (int row : rows)
            selection->select(view->model()->index(row, 0),
                              QItemSelectionModel::Select | QItemSelectionModel::Rows);
        selection->setCurrentIndex(view->model()->index(rows.front(), 0), QItemSelectionModel::NoUpdate);
    }
    int part_named(const char *name)
    {
        for (uint32_t i = 0; i < window->model()->component_count; ++i)
            if (QString(window->model()->components[i].name) == name)
                return int(i);
        return -1;
    }

private slots:
    void initTestCase()
    {
        open_test_window(window, work, view_size, "/selection");
        if (QTest::currentTestFailed())
            return;
        QVERIFY(window->show_tab("Parts")); // the list's rows have their geometry
    }
    void cleanupTestCase() { delete window; }
    void init()
    {
        parts()->view()->selectionModel()->clearSelection();
        settings() = RenderSettings();
        settings().reset_parts(*window->model());
        window->view()->reset_camera();
        window->settings_changed();
        window->set_highlight_selection(true);
        frame();
        window->reset_settings_history();
    }

    // Fade others: every part not selected to the fade opacity, the selected
    // ones keep theirs; one undo restores every part, redo fades again.
    void fade_others_is_one_undo_step()
    {
        const int count = int(window->model()->component_count);
        // a selected part keeps its own opacity; set just before the fade (the
        // undo history still coalescing), which stays a step of its own
        window->set_part_alpha(2, 0.5f);
        window->settings_changed();
        select({1, 2});
        parts()->findChild<QSpinBox *>("parts_fade_percent")->setValue(20);
        QAction *fade = window->findChild<QAction *>("fade_others");
        QVERIFY(fade);
        QCOMPARE(fade->shortcut(), QKeySequence("G"));
        fade->trigger();
        std::vector<float> expected(size_t(count), 0.2f);
        expected[1] = 1.0f;
        expected[2] = 0.5f;
        QCOMPARE(parts()->alpha(), expected);
        QCOMPARE(settings().part_alpha, expected);
        QVERIFY(window->undo_settings());
        std::vector<float> before(size_t(count), 1.0f);
        before[2] = 0.5f;
        QCOMPARE(settings().part_alpha, before);
        QCOMPARE(parts()->alpha(), before);
        QVERIFY(window->undo_settings()); // the 50% before it
        QCOMPARE(settings().part_alpha, std::vector<float>(size_t(count), 1.0f));
        QVERIFY(window->redo_settings());
        QVERIFY(window->redo_settings());
        QCOMPARE(settings().part_alpha, expected);
        // the default is 10%, and nothing selected fades nothing
        parts()->set_fade_percent(10);
        parts()->view()->selectionModel()->clearSelection();
        QVERIFY(!window->fade_others());
        QCOMPARE(settings().part_alpha, expected);
    }

    // The opacity keys and a selected row's slider set every selected row; one undo restores them.
    void opacity_keys_and_slider_reach_every_selected_row()
    {
        const int count = int(window->model()->component_count);
        select({3, 4, 5, 6});
        QAbstractItemView *view = parts()->view();
        view->setFocus();
        QTest::keyClick(view, Qt::Key_Minus);
        QTest::keyClick(view, Qt::Key_Minus);
        std::vector<float> expected(size_t(count), 1.0f);
        for (int part : {3, 4, 5, 6})
            expected[size_t(part)] = 0.9f;
        QCOMPARE(parts()->alpha(), expected);
        QCOMPARE(settings().part_alpha, expected);
        QVERIFY(window->undo_settings()); // the two presses coalesce into one step
        QCOMPARE(settings().part_alpha, std::vector<float>(size_t(count), 1.0f));
        QVERIFY(!window->settings_model()->can_undo());
        // the slider of a selected row: a press at its left end sets all four to 0
        window->settings_model()->close_step();
        const QModelIndex cell = view->model()->index(5, PartsModel::OpacityColumn);
        view->scrollTo(cell);
        const QRect rect = view->visualRect(cell);
        QTest::mouseClick(view->viewport(), Qt::LeftButton, Qt::NoModifier, QPoint(rect.left() + 2, rect.center().y()));
        for (int part = 0; part < count; ++part)
            QCOMPARE(parts()->alpha()[size_t(part)], part >= 3 && part <= 6 ? 0.0f : 1.0f);
        // a row outside the selection: only itself
        const QModelIndex other = view->model()->index(8, PartsModel::OpacityColumn);
        view->scrollTo(other);
        const QRect other_rect = view->visualRect(other);
        QTest::mouseClick(view->viewport(), Qt::LeftButton, Qt::NoModifier,
                          QPoint(other_rect.left() + 2, other_rect.center().y()));
        QCOMPARE(parts()->alpha()[8], 0.0f);
        QCOMPARE(parts()->alpha()[7], 1.0f);
        QCOMPARE(parts()->alpha()[5], 0.0f);
    }

    // The selection is tinted in the view (only the part's pixels change), an
    // export leaves it out unless asked, and Copy as command names it.
    void highlight_in_the_view_not_in_exports()
    {
        const QImage plain = frame();
        const int gear = part_named("gear_1");
        QVERIFY(gear >= 0);
        select({gear});
        const QImage highlighted = frame();
        const int changed = differing_pixels(plain, highlighted);
        QVERIFY2(changed > 50, qPrintable(QString("the highlight changed %1 pixels").arg(changed)));
        QCOMPARE(window->view()->highlight().size(), size_t(window->model()->component_count));
        QVERIFY(window->render_command_for_view("x.png").contains(QString(" --highlight %1").arg(gear)));
        // only where gear_1 is: the pixels it covers when every other part is hidden
        std::vector<float> alone(window->model()->component_count, 0.0f);
        alone[size_t(gear)] = 1.0f;
        settings().part_alpha = alone;
        window->settings_changed();
        const QImage gear_alone = frame();
        const QRgb background = gear_alone.pixel(0, 0);
        int outside = 0;
        for (int y = 0; y < plain.height(); ++y)
            for (int x = 0; x < plain.width(); ++x)
                outside += plain.pixel(x, y) != highlighted.pixel(x, y) && gear_alone.pixel(x, y) == background;
        QCOMPARE(outside, 0);
        settings().reset_parts(*window->model());
        window->settings_changed();
        QCOMPARE(differing_pixels(frame(), highlighted), 0);

        QString error;
        const QString without = work + "/without.png", with = work + "/with.png";
        QVERIFY2(window->export_png(without, view_size.width(), view_size.height(), error), qPrintable(error));
        QVERIFY2(window->export_png(with, view_size.width(), view_size.height(), error, true), qPrintable(error));
        QCOMPARE(differing_pixels(QImage(without), plain), 0);
        QCOMPARE(differing_pixels(QImage(with), highlighted), 0);

        // Export PNG's dialog offers the highlight, unticked (then cancelled: no file dialog)
        QAction *export_action = nullptr;
        for (QAction *action : window->findChildren<QAction *>())
            if (action->text().startsWith("&Export PNG"))
                export_action = action;
        QVERIFY(export_action);
        bool offered = false, ticked = true;
        QTimer::singleShot(0, this, [&] {
            QWidget *dialog = QApplication::activeModalWidget();
            QCheckBox *box = dialog ? dialog->findChild<QCheckBox *>("export_highlight") : nullptr;
            offered = box && box->isEnabled();
            ticked = box && box->isChecked();
            if (dialog)
                static_cast<QDialog *>(dialog)->reject();
        });
        export_action->trigger();
        QVERIFY2(offered && !ticked, "Export PNG offers \"Include selection highlight\", unticked");

        // Highlight selection off: the plain image, and no --highlight in the command
        window->set_highlight_selection(false);
        QCOMPARE(differing_pixels(frame(), plain), 0);
        QVERIFY(!window->render_command_for_view("x.png").contains("--highlight"));
    }

    // A pick selects the part's row, makes it current and scrolls to it; a click
    // again at the same pixel selects the contributor behind it; a click
    // elsewhere starts at the front again.
    void a_pick_reveals_its_row_and_a_click_again_steps_deeper()
    {
        window->set_part_alpha(part_named("housing"), 0.3f);
        window->settings_changed();
        frame();
        std::vector<float> storage;
        const oit_frame_settings f = window->view()->current_frame(storage);
        std::string error;
        // a pixel with three contributors or more
        QPoint at(-1, -1);
        std::vector<int> ranks;
        for (int y = 10; y < view_size.height() && at.x() < 0; y += 7)
            for (int x = 10; x < view_size.width() && at.x() < 0; x += 7) {
                ContributorPick p = pick_contributor(*window->model(), f, x, y, 1, error);
                if (p.parts >= 3) {
                    at = QPoint(x, y);
                    for (int rank = 1; rank <= 3; ++rank)
                        ranks.push_back(pick_contributor(*window->model(), f, x, y, rank, error).component);
                }
            }
        QVERIFY2(at.x() >= 0, "a pixel of the gearbox with three parts behind each other");
        QTreeView *list = qobject_cast<QTreeView *>(parts()->view());
        list->scrollToTop();
        for (int rank = 0; rank < 3; ++rank) {
            QTest::mouseClick(window->view(), Qt::LeftButton, Qt::NoModifier, at);
            QCOMPARE(parts()->selected_parts(), std::vector<int>{ranks[size_t(rank)]});
            QVERIFY2(window->status_text().contains(QString("contributor %1 of").arg(rank + 1)),
                     qPrintable(window->status_text()));
            // revealed: current, selected and in sight
            const QModelIndex current = list->currentIndex();
            QCOMPARE(current.row(), ranks[size_t(rank)]);
            QVERIFY(list->viewport()->rect().intersects(list->visualRect(current)));
        }
        // elsewhere, then back: the front again
        QTest::mouseClick(window->view(), Qt::LeftButton, Qt::NoModifier, QPoint(1, 1));
        QTest::mouseClick(window->view(), Qt::LeftButton, Qt::NoModifier, at);
        QCOMPARE(parts()->selected_parts(), std::vector<int>{ranks[0]});
        // the picked part is highlighted in the view
        QCOMPARE(window->view()->highlight()[size_t(ranks[0])], 1.0f);
    }
};

OIT_WINDOW_TEST_MAIN(SelectionTest, "oit-workbench-test-selection")

#include "test_selection.moc"
