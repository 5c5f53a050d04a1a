// test_parts_panel.cpp: Qt Test cases for the Parts tab (src/app/parts_panel.*)
// at 10,000 parts and for picking (src/app/pick.*), on models built in memory.
// Run under Xvfb by CTest (tests/app/parts_panel.cmake). Timings are printed
// (qInfo), never asserted: the machine is shared.

// Mouse events go through the window like real input, so a move carries the
// held button (Qt 5's widget QTest::mouseMove only moves the cursor).
#define QTEST_QPA_MOUSE_HANDLING

#include <QCheckBox>
#include <QDir>
#include <QElapsedTimer>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QScrollBar>
#include <QSignalSpy>
#include <QSlider>
#include <QStyleOptionViewItem>
#include <QTreeView>
#include <QtTest/QtTest>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "oit.h"
#include "parts_panel.h"
#include "parts_test_model.h"
#include "pick.h"

namespace {

using parts_test::build;
using parts_test::Model;
using parts_test::Part;
using parts_test::square;

QString part_name(int i) { return QString::asprintf("part_%05d", i); }

// ------------------------------------------------ matrices, written by hand

struct Matrices {
    double modelview[16];
    double projection[16];
};

void identity(double m[16])
{
    std::fill(m, m + 16, 0.0);
    m[0] = m[5] = m[10] = m[15] = 1.0;
}

// Eye at (0, 0, z) looking down -z (from_below: at (0, 0, -z) looking up +z).
void look_along_z(double m[16], double z, bool from_below)
{
    identity(m);
    if (from_below) { // a half turn about y: (x, y, z) -> (-x, y, -z), then back off
        m[0] = -1.0;
        m[10] = -1.0;
    }
    m[14] = -z;
}

const double fovy_degrees = 40.0, near_plane = 1.0, far_plane = 100.0, ortho_half_height = 3.0;
const double pi = 3.14159265358979323846;

void perspective(double p[16], double aspect)
{
    const double f = 1.0 / std::tan(fovy_degrees * pi / 360.0);
    std::fill(p, p + 16, 0.0);
    p[0] = f / aspect;
    p[5] = f;
    p[10] = (far_plane + near_plane) / (near_plane - far_plane);
    p[11] = -1.0;
    p[14] = 2.0 * far_plane * near_plane / (near_plane - far_plane);
}

void orthographic(double p[16], double aspect)
{
    std::fill(p, p + 16, 0.0);
    p[0] = 1.0 / (ortho_half_height * aspect);
    p[5] = 1.0 / ortho_half_height;
    p[10] = -2.0 / (far_plane - near_plane);
    p[14] = -(far_plane + near_plane) / (far_plane - near_plane);
    p[15] = 1.0;
}

// Where the pixel's ray (camera at (0, 0, 5) looking down -z) meets the plane
// z = plane_z, worked out from the camera's own parameters, not from its matrices.
void expected_point(bool ortho, int width, int height, double x, double y, double plane_z, double &px, double &py)
{
    const double aspect = double(width) / double(height);
    const double ndc_x = 2.0 * x / width - 1.0, ndc_y = 1.0 - 2.0 * y / height;
    const double depth = 5.0 - plane_z;
    if (ortho) {
        px = ndc_x * ortho_half_height * aspect;
        py = ndc_y * ortho_half_height;
    } else {
        const double t = std::tan(fovy_degrees * pi / 360.0);
        px = ndc_x * t * aspect * depth;
        py = ndc_y * t * depth;
    }
}

// Keep a screenshot in $OIT_TEST_WORK (when set) for a look by eye.
void keep(const QImage &image, const QString &name)
{
    const QString work = qEnvironmentVariable("OIT_TEST_WORK");
    if (work.isEmpty() || !QDir().mkpath(work))
        return;
    image.save(QDir(work).filePath(name));
}

QImage grab_timed(QWidget &widget, double &ms)
{
    QElapsedTimer timer;
    timer.start();
    QImage image = widget.grab().toImage();
    ms = double(timer.nsecsElapsed()) / 1e6;
    return image;
}

} // namespace

class PartsPanelTest : public QObject {
    Q_OBJECT

private:
    Model many_; // 10,000 one-square parts, part_00000 ...
    static constexpr int many_count = 10000;

    // A shown panel on many_, big enough for the buttons and some rows.
    void show_panel(PartsPanel &panel)
    {
        panel.resize(520, 600);
        panel.set_model(&many_.m, {}, {});
        panel.show();
        QVERIFY(QTest::qWaitForWindowExposed(&panel));
    }

    QModelIndex row_index(PartsPanel &panel, int row, int column)
    {
        return panel.view()->model()->index(row, column);
    }

    QPoint slider_point(PartsPanel &panel, int row, double fraction)
    {
        const QRect cell = panel.view()->visualRect(row_index(panel, row, PartsModel::OpacityColumn));
        return QPoint(cell.left() + int(std::lround(fraction * (cell.width() - 1))), cell.center().y());
    }

    // the check box of a row's part cell, where the style puts it
    QPoint check_point(PartsPanel &panel, int row)
    {
        QAbstractItemView *view = panel.view();
        QStyleOptionViewItem option;
        option.initFrom(view);
        option.widget = view;
        option.rect = view->visualRect(row_index(panel, row, PartsModel::PartColumn));
        option.features = QStyleOptionViewItem::HasCheckIndicator | QStyleOptionViewItem::HasDisplay |
                          QStyleOptionViewItem::HasDecoration;
        option.decorationSize = view->iconSize().isValid() ? view->iconSize() : QSize(16, 16);
        option.text = part_name(row);
        return view->style()->subElementRect(QStyle::SE_ItemViewItemCheckIndicator, &option, view).center();
    }

private slots:
    void initTestCase()
    {
        std::vector<Part> parts;
        parts.reserve(many_count);
        for (int i = 0; i < many_count; ++i) {
            Part p = square(part_name(i).toStdString(), float(i % 100), float(i / 100), 0.0f, 0.4f);
            p.colour[0] = float(i % 7) / 6.0f;
            p.colour[1] = float(i % 3) / 2.0f;
            parts.push_back(std::move(p));
        }
        QString message;
        QVERIFY2(build(many_, parts, &message), qPrintable(message));
        QCOMPARE(many_.m.component_count, uint32_t(many_count));
    }

    void ten_thousand_parts()
    {
        PartsPanel panel;
        panel.resize(520, 600);
        panel.show();
        QVERIFY(QTest::qWaitForWindowExposed(&panel));
        QElapsedTimer timer;
        timer.start();
        panel.set_model(&many_.m, {}, {});
        const double set_model_ms = double(timer.nsecsElapsed()) / 1e6;
        // the layout the reset posted (rows, scroll bars, the note's lines), as the event loop would
        timer.restart();
        QCoreApplication::processEvents();
        const double layout_ms = double(timer.nsecsElapsed()) / 1e6;
        double paint_ms = 0;
        QImage first = grab_timed(panel, paint_ms);
        qInfo("10,000 parts: set_model %.1f ms, then its posted layout %.1f ms, first full paint (grab) %.1f ms",
              set_model_ms, layout_ms, paint_ms);
        QVERIFY(!first.isNull());
        keep(first, "parts_panel_top.png");

        QCOMPARE(panel.view()->model()->rowCount(), many_count);
        QCOMPARE(panel.shown_row_count(), many_count);
        QCOMPARE(int(panel.alpha().size()), many_count);
        QCOMPARE(int(panel.visible().size()), many_count);
        // no widget per row
        QCOMPARE(panel.findChildren<QSlider *>().size(), 0);
        QCOMPARE(panel.findChildren<QCheckBox *>().size(), 0);
        QVERIFY2(panel.findChildren<QWidget *>().size() < 40,
                 qPrintable(QString::number(panel.findChildren<QWidget *>().size())));
        auto *tree = qobject_cast<QTreeView *>(panel.view());
        QVERIFY(tree && tree->uniformRowHeights());
        QCOMPARE(panel.view()->selectionMode(), QAbstractItemView::ExtendedSelection);
        QCOMPARE(panel.view()->selectionBehavior(), QAbstractItemView::SelectRows);

        // the note (per-part opacity has no limit: every part has its slider)
        QString note;
        for (QLabel *label : panel.findChildren<QLabel *>())
            note += label->text();
        QVERIFY2(note.contains("10000 parts; checkbox: visible, slider: opacity"), qPrintable(note));
        QVERIFY2(!note.contains("1024"), qPrintable(note));

        // every control has a tooltip; the named ones are there
        for (const char *name : {"parts_filter", "parts_view", "parts_reset", "parts_isolate", "parts_show_all",
                                 "parts_frame"}) {
            auto *widget = panel.findChild<QWidget *>(name);
            QVERIFY2(widget, name);
            QVERIFY2(!widget->toolTip().isEmpty(), name);
        }
        QCOMPARE(panel.findChild<QWidget *>("parts_filter"), static_cast<QWidget *>(panel.filter()));
        QCOMPARE(panel.findChild<QWidget *>("parts_view"), static_cast<QWidget *>(panel.view()));
        QCOMPARE(panel.filter()->placeholderText(), QString("filter parts by name"));
        QVERIFY(panel.filter()->isClearButtonEnabled());

        // a row's data: name, checkbox, tooltip, percent
        QAbstractItemModel *rows = panel.view()->model();
        QCOMPARE(rows->data(rows->index(1234, 0)).toString(), QString("part_01234"));
        QCOMPARE(rows->data(rows->index(1234, 0), Qt::CheckStateRole).toInt(), int(Qt::Checked));
        QCOMPARE(rows->data(rows->index(1234, 2)).toString(), QString("100%"));
        const QString tip = rows->data(rows->index(1234, 0), Qt::ToolTipRole).toString();
        QVERIFY2(tip.startsWith("part_01234: colour ") && tip.contains("material opacity 1") &&
                     tip.endsWith(", 2 triangles"),
                 qPrintable(tip));
        QVERIFY(!rows->data(rows->index(1234, 1), Qt::ToolTipRole).toString().isEmpty());
        QVERIFY(!rows->headerData(1, Qt::Horizontal, Qt::ToolTipRole).toString().isEmpty());

        // scrolled to the bottom, the last part is on screen and paints
        panel.view()->scrollToBottom();
        panel.view()->verticalScrollBar()->setValue(panel.view()->verticalScrollBar()->maximum());
        QCoreApplication::processEvents();
        QImage bottom = grab_timed(panel, paint_ms);
        qInfo("10,000 parts: full paint scrolled to the bottom %.1f ms", paint_ms);
        QVERIFY(!bottom.isNull());
        keep(bottom, "parts_panel_bottom.png");
        const QRect last = panel.view()->visualRect(rows->index(many_count - 1, 0));
        QVERIFY2(panel.view()->viewport()->rect().contains(last.center()), "the last row is not on screen");
        QCOMPARE(panel.view()->indexAt(last.center()).row(), many_count - 1);

        // filtering: case-insensitive substring, through the proxy
        timer.restart();
        panel.filter()->setText("part_09999");
        QCOMPARE(panel.shown_row_count(), 1);
        panel.filter()->setText("PART_0999");
        QCOMPARE(panel.shown_row_count(), 10);
        panel.filter()->clear();
        QCOMPARE(panel.shown_row_count(), many_count);
        const double narrow_ms = double(timer.nsecsElapsed()) / 1e6;
        // a filter that keeps rows scattered all over the list
        int with_five = 0;
        for (int i = 0; i < many_count; ++i)
            with_five += part_name(i).contains('5');
        timer.restart();
        panel.filter()->setText("5");
        QCOMPARE(panel.shown_row_count(), with_five);
        grab_timed(panel, paint_ms);
        panel.filter()->clear();
        QCOMPARE(panel.shown_row_count(), many_count);
        qInfo("10,000 parts: three narrow filters and a clear %.1f ms; a scattered filter (%d rows), paint, "
              "clear %.1f ms",
              narrow_ms, with_five, double(timer.nsecsElapsed()) / 1e6);
        QVERIFY(!panel.grab().isNull());
    }

    void slider_click_and_drag()
    {
        PartsPanel panel;
        show_panel(panel);
        QSignalSpy changed(&panel, &PartsPanel::parts_changed);
        QWidget *viewport = panel.view()->viewport();
        const int row = 3;
        panel.select_part(0);
        const std::vector<int> selected = panel.selected_parts();

        // a click sets the value under the pointer: the ends and the middle
        QTest::mouseClick(viewport, Qt::LeftButton, Qt::NoModifier, slider_point(panel, row, 0.0));
        QCOMPARE(panel.alpha()[row], 0.0f);
        QCOMPARE(changed.count(), 1);
        QTest::mouseClick(viewport, Qt::LeftButton, Qt::NoModifier, slider_point(panel, row, 1.0));
        QCOMPARE(panel.alpha()[row], 1.0f);
        QCOMPARE(changed.count(), 2);
        QTest::mouseClick(viewport, Qt::LeftButton, Qt::NoModifier, slider_point(panel, row, 0.5));
        QVERIFY2(std::fabs(panel.alpha()[row] - 0.5f) <= 0.02f, qPrintable(QString::number(panel.alpha()[row])));
        QCOMPARE(changed.count(), 3);
        // whole percent steps, and the percent column says so
        const int percent = int(std::lround(panel.alpha()[row] * 100.0f));
        QCOMPARE(panel.alpha()[row], float(percent) / 100.0f);
        QCOMPARE(panel.view()->model()->data(row_index(panel, row, 2)).toString(), QString("%1%").arg(percent));
        // the slider does not touch the selection, but its row becomes current
        QCOMPARE(panel.selected_parts(), selected);
        QCOMPARE(panel.view()->currentIndex().row(), row);
        QCOMPARE(panel.alpha()[row - 1], 1.0f);
        QCOMPARE(panel.alpha()[row + 1], 1.0f);

        // a drag changes the value live, before the release
        QTest::mousePress(viewport, Qt::LeftButton, Qt::NoModifier, slider_point(panel, row, 0.5));
        const int before_moves = changed.count();
        QTest::mouseMove(viewport, slider_point(panel, row, 0.75));
        const float at_three_quarters = panel.alpha()[row];
        QVERIFY2(at_three_quarters > 0.6f && at_three_quarters < 0.9f, qPrintable(QString::number(at_three_quarters)));
        QVERIFY(changed.count() > before_moves);
        // onto another row and out of the list: still this row's slider
        QPoint below = slider_point(panel, row + 2, 0.25);
        QTest::mouseMove(viewport, below);
        QVERIFY2(panel.alpha()[row] > 0.15f && panel.alpha()[row] < 0.35f, qPrintable(QString::number(panel.alpha()[row])));
        QCOMPARE(panel.alpha()[row + 2], 1.0f);
        QTest::mouseMove(viewport, QPoint(-30, below.y()));
        QCOMPARE(panel.alpha()[row], 0.0f);
        const int before_release = changed.count();
        QTest::mouseRelease(viewport, Qt::LeftButton, Qt::NoModifier, QPoint(-30, below.y()));
        QCOMPARE(panel.alpha()[row], 0.0f);
        QCOMPARE(changed.count(), before_release);
        // after the release a move changes nothing
        QTest::mouseMove(viewport, slider_point(panel, row, 0.9));
        QCOMPARE(panel.alpha()[row], 0.0f);
        QCOMPARE(panel.selected_parts(), selected);
        // a few values to look at: row 3 at 0%, rows 5..9 at 10%..90%
        std::vector<float> alpha = panel.alpha();
        for (int i = 5; i < 10; ++i)
            alpha[size_t(i)] = float(i - 4) * 0.2f - 0.1f;
        std::vector<char> visible = panel.visible();
        visible[7] = 0;
        panel.set_values(alpha, visible);
        const QImage image = panel.grab().toImage();
        QVERIFY(!image.isNull());
        keep(image, "parts_panel_sliders.png");
    }

    void checkbox_toggles_visible()
    {
        PartsPanel panel;
        show_panel(panel);
        QSignalSpy changed(&panel, &PartsPanel::parts_changed);
        QWidget *viewport = panel.view()->viewport();
        QTest::mouseClick(viewport, Qt::LeftButton, Qt::NoModifier, check_point(panel, 6));
        QCOMPARE(int(panel.visible()[6]), 0);
        QCOMPARE(changed.count(), 1);
        QCOMPARE(panel.view()->model()->data(row_index(panel, 6, 0), Qt::CheckStateRole).toInt(), int(Qt::Unchecked));
        QCOMPARE(int(panel.visible()[5]) + int(panel.visible()[7]), 2);
        QTest::mouseClick(viewport, Qt::LeftButton, Qt::NoModifier, check_point(panel, 6));
        QCOMPARE(int(panel.visible()[6]), 1);
        QCOMPARE(changed.count(), 2);
    }

    void keyboard_steps_current_row()
    {
        PartsPanel panel;
        show_panel(panel);
        QSignalSpy changed(&panel, &PartsPanel::parts_changed);
        panel.select_part(42);
        panel.view()->setFocus();
        QTest::keyClick(panel.view(), Qt::Key_Minus);
        QCOMPARE(panel.alpha()[42], 0.95f);
        QTest::keyClick(panel.view(), Qt::Key_Minus);
        QCOMPARE(panel.alpha()[42], 0.9f);
        QTest::keyClick(panel.view(), Qt::Key_Plus);
        QCOMPARE(panel.alpha()[42], 0.95f);
        QTest::keyClick(panel.view(), Qt::Key_Left);
        QCOMPARE(panel.alpha()[42], 0.9f);
        QTest::keyClick(panel.view(), Qt::Key_Right);
        QTest::keyClick(panel.view(), Qt::Key_Right);
        QCOMPARE(panel.alpha()[42], 1.0f);
        QCOMPARE(changed.count(), 6);
        // at 100%, + changes nothing and says nothing
        QTest::keyClick(panel.view(), Qt::Key_Plus);
        QCOMPARE(panel.alpha()[42], 1.0f);
        QCOMPARE(changed.count(), 6);
        // down to 0 and no further
        for (int i = 0; i < 25; ++i)
            QTest::keyClick(panel.view(), Qt::Key_Minus);
        QCOMPARE(panel.alpha()[42], 0.0f);
        QCOMPARE(changed.count(), 26);
        // only the current row moved; Space shows and hides it
        QCOMPARE(panel.alpha()[41], 1.0f);
        QCOMPARE(panel.alpha()[43], 1.0f);
        QTest::keyClick(panel.view(), Qt::Key_Space);
        QCOMPARE(int(panel.visible()[42]), 0);
        QTest::keyClick(panel.view(), Qt::Key_Space);
        QCOMPARE(int(panel.visible()[42]), 1);
        // Down moves the current row as usual, and the keys follow it
        QTest::keyClick(panel.view(), Qt::Key_Down);
        QTest::keyClick(panel.view(), Qt::Key_Minus);
        QCOMPARE(panel.alpha()[43], 0.95f);
    }

    void buttons()
    {
        PartsPanel panel;
        show_panel(panel);
        QSignalSpy changed(&panel, &PartsPanel::parts_changed);
        QSignalSpy selection(&panel, &PartsPanel::selection_changed);
        QSignalSpy frame(&panel, &PartsPanel::frame_selected_requested);
        QVERIFY(changed.isValid() && selection.isValid() && frame.isValid());
        auto *isolate = panel.findChild<QPushButton *>("parts_isolate");
        auto *show_all = panel.findChild<QPushButton *>("parts_show_all");
        auto *reset = panel.findChild<QPushButton *>("parts_reset");
        auto *frame_button = panel.findChild<QPushButton *>("parts_frame");
        QVERIFY(isolate && show_all && reset && frame_button);
        QVERIFY(!isolate->isEnabled() && !frame_button->isEnabled()); // nothing selected yet

        // select parts 2 and 4 by clicking their names (Ctrl for the second)
        QWidget *viewport = panel.view()->viewport();
        auto name_point = [&](int row) {
            const QRect cell = panel.view()->visualRect(row_index(panel, row, 0));
            return QPoint(cell.left() + cell.width() / 2, cell.center().y());
        };
        QTest::mouseClick(viewport, Qt::LeftButton, Qt::NoModifier, name_point(2));
        QTest::mouseClick(viewport, Qt::LeftButton, Qt::ControlModifier, name_point(4));
        QCOMPARE(panel.selected_parts(), (std::vector<int>{2, 4}));
        QVERIFY(selection.count() >= 2);
        QCOMPARE(selection.last().at(0).value<std::vector<int>>(), (std::vector<int>{2, 4}));
        QVERIFY(isolate->isEnabled() && frame_button->isEnabled());
        QCOMPARE(changed.count(), 0);

        QTest::mouseClick(frame_button, Qt::LeftButton);
        QCOMPARE(frame.count(), 1);
        QCOMPARE(frame.last().at(0).value<std::vector<int>>(), (std::vector<int>{2, 4}));

        QTest::mouseClick(isolate, Qt::LeftButton);
        QCOMPARE(changed.count(), 1);
        QCOMPARE(int(std::count(panel.visible().begin(), panel.visible().end(), char(1))), 2);
        QVERIFY(panel.visible()[2] && panel.visible()[4]);

        // Show all keeps the opacities; Reset restores them too
        std::vector<float> alpha = panel.alpha();
        alpha[9] = 0.25f;
        panel.set_values(alpha, panel.visible());
        QCOMPARE(changed.count(), 1); // an outside change is not the user's
        QTest::mouseClick(show_all, Qt::LeftButton);
        QCOMPARE(changed.count(), 2);
        QCOMPARE(int(std::count(panel.visible().begin(), panel.visible().end(), char(1))), many_count);
        QCOMPARE(panel.alpha()[9], 0.25f);
        QTest::mouseClick(reset, Qt::LeftButton);
        QCOMPARE(changed.count(), 3);
        QCOMPARE(panel.alpha()[9], 1.0f);
        // nothing left to reset: no signal
        QTest::mouseClick(reset, Qt::LeftButton);
        QCOMPARE(changed.count(), 3);

        // double-clicking a name asks to frame that part
        QTest::mouseDClick(viewport, Qt::LeftButton, Qt::NoModifier, name_point(7));
        QCOMPARE(frame.count(), 2);
        QCOMPARE(frame.last().at(0).value<std::vector<int>>(), (std::vector<int>{7}));
    }

    void select_part_scrolls_to_it()
    {
        PartsPanel panel;
        show_panel(panel);
        QSignalSpy selection(&panel, &PartsPanel::selection_changed);
        panel.filter()->setText("part_0001");
        QCOMPARE(panel.shown_row_count(), 10);
        panel.select_part(7777);
        QVERIFY(panel.filter()->text().isEmpty()); // the filter hid it
        QCOMPARE(panel.shown_row_count(), many_count);
        QCOMPARE(panel.selected_parts(), std::vector<int>{7777});
        QCOMPARE(selection.last().at(0).value<std::vector<int>>(), std::vector<int>{7777});
        const QModelIndex current = panel.view()->currentIndex();
        QCOMPARE(current.row(), 7777);
        QCOMPARE(panel.view()->model()->data(current.siblingAtColumn(0)).toString(), QString("part_07777"));
        const QRect rect = panel.view()->visualRect(current);
        QVERIFY2(panel.view()->viewport()->rect().contains(rect), "the selected row is not on screen");
        // a filter that shows it stays
        panel.filter()->setText("7_");
        panel.filter()->setText("part_077");
        panel.select_part(7701);
        QCOMPARE(panel.filter()->text(), QString("part_077"));
        QCOMPARE(panel.selected_parts(), std::vector<int>{7701});
        // out of range: nothing happens
        panel.select_part(-1);
        panel.select_part(many_count);
        QCOMPARE(panel.selected_parts(), std::vector<int>{7701});
    }

    void set_values_without_rebuild()
    {
        PartsPanel panel;
        show_panel(panel);
        QAbstractItemModel *rows = panel.view()->model();
        QSignalSpy reset(rows, &QAbstractItemModel::modelReset);
        qRegisterMetaType<QList<QPersistentModelIndex>>();
        qRegisterMetaType<QAbstractItemModel::LayoutChangeHint>();
        QSignalSpy layout(rows, &QAbstractItemModel::layoutChanged);
        QSignalSpy removed(rows, &QAbstractItemModel::rowsRemoved);
        QSignalSpy data(rows, &QAbstractItemModel::dataChanged);
        QSignalSpy changed(&panel, &PartsPanel::parts_changed);
        panel.select_part(5000);
        const int scroll = panel.view()->verticalScrollBar()->value();
        QVERIFY(scroll > 0);

        std::vector<float> alpha(many_count, 1.0f);
        std::vector<char> visible(many_count, 1);
        alpha[5000] = 0.3f;
        visible[5001] = 0;
        alpha[17] = 7.0f;   // clamped
        alpha[18] = -1.0f;  // clamped
        panel.set_values(alpha, visible);
        QCOMPARE(reset.count(), 0);
        QCOMPARE(layout.count(), 0);
        QCOMPARE(removed.count(), 0);
        QVERIFY(data.count() >= 1);
        QCOMPARE(changed.count(), 0);
        QCOMPARE(panel.alpha()[5000], 0.3f);
        QCOMPARE(panel.alpha()[17], 1.0f);
        QCOMPARE(panel.alpha()[18], 0.0f);
        QCOMPARE(int(panel.visible()[5001]), 0);
        QCOMPARE(rows->data(rows->index(5000, 2)).toString(), QString("30%"));
        QCOMPARE(rows->data(rows->index(5001, 0), Qt::CheckStateRole).toInt(), int(Qt::Unchecked));
        QCOMPARE(panel.selected_parts(), std::vector<int>{5000});
        QCOMPARE(panel.view()->verticalScrollBar()->value(), scroll);

        // sizes that do not match: every part visible at full opacity
        panel.set_values({0.5f}, {0});
        QCOMPARE(int(panel.alpha().size()), many_count);
        QCOMPARE(panel.alpha()[5000], 1.0f);
        QCOMPARE(int(panel.visible()[5001]), 1);
        QCOMPARE(reset.count(), 0);
    }

    void set_model_values_and_none()
    {
        PartsPanel panel;
        show_panel(panel);
        QSignalSpy selection(&panel, &PartsPanel::selection_changed);
        std::vector<float> alpha(many_count, 0.5f);
        std::vector<char> visible(many_count, 0);
        visible[3] = 1;
        panel.set_model(&many_.m, alpha, visible);
        QCOMPARE(panel.alpha()[9999], 0.5f);
        QCOMPARE(int(panel.visible()[3]), 1);
        QCOMPARE(int(panel.visible()[4]), 0);
        panel.select_part(3);
        const int before = selection.count();
        // wrong sizes: defaults
        panel.set_model(&many_.m, {0.1f}, {});
        QCOMPARE(panel.alpha()[3], 1.0f);
        QCOMPARE(int(panel.visible()[4]), 1);
        // the reset dropped the selection, and the panel says so
        QVERIFY(panel.selected_parts().empty());
        QCOMPARE(selection.count(), before + 1);
        QVERIFY(selection.last().at(0).value<std::vector<int>>().empty());
        // no model
        panel.set_model(nullptr, {}, {});
        QCOMPARE(panel.shown_row_count(), 0);
        QVERIFY(panel.alpha().empty() && panel.visible().empty());
        QTest::mouseClick(panel.findChild<QPushButton *>("parts_show_all"), Qt::LeftButton);
        QTest::keyClick(panel.view(), Qt::Key_Plus);
        QVERIFY(!panel.grab().isNull());
        // a small model: no GPU-limit sentence
        Model small;
        QString message;
        QVERIFY2(build(small, {square("A", 0, 0, 0, 1), square("B", 3, 0, 0, 1)}, &message), qPrintable(message));
        panel.set_model(&small.m, {}, {});
        QString note;
        for (QLabel *label : panel.findChildren<QLabel *>())
            note += label->text();
        QVERIFY2(note.contains("2 parts; checkbox: visible, slider: opacity"), qPrintable(note));
        QVERIFY2(!note.contains("1024"), qPrintable(note));
        panel.set_model(nullptr, {}, {}); // before small is freed
    }

    // ------------------------------------------------------------- picking

    void pick_two_squares()
    {
        // A: z = 0, half size 1; B: z = -1, half size 2 (sticks out around A);
        // C: z = 10, behind the eye at z = 5, covering everything
        Model model;
        QString message;
        QVERIFY2(build(model, {square("A", 0, 0, 0, 1), square("B", 0, 0, -1, 2), square("C", 0, 0, 10, 50)}, &message),
                 qPrintable(message));
        const int width = 160, height = 120;
        const double aspect = double(width) / height;
        const std::vector<float> all_alpha;
        const std::vector<char> all_visible;

        for (bool ortho : {false, true}) {
            Matrices cam;
            look_along_z(cam.modelview, 5.0f, false);
            if (ortho)
                orthographic(cam.projection, aspect);
            else
                perspective(cam.projection, aspect);
            const char *kind = ortho ? "orthographic" : "perspective";

            // the centre pixel: A, 5 in front of the eye
            PickResult centre = pick(model.m, cam.modelview, cam.projection, width, height, width / 2.0,
                                     height / 2.0, all_alpha, all_visible);
            QVERIFY2(centre.component == 0, kind);
            QVERIFY(centre.triangle == 0 || centre.triangle == 1);
            QVERIFY(std::fabs(centre.eye_depth - 5.0) < 1e-9);
            // A hidden, or at opacity 0: B behind it
            PickResult hidden = pick(model.m, cam.modelview, cam.projection, width, height, width / 2.0,
                                     height / 2.0, {}, {0, 1, 1});
            QCOMPARE(hidden.component, 1);
            QVERIFY(hidden.triangle == 2 || hidden.triangle == 3);
            QVERIFY(std::fabs(hidden.eye_depth - 6.0) < 1e-9);
            PickResult transparent = pick(model.m, cam.modelview, cam.projection, width, height, width / 2.0,
                                          height / 2.0, {0.0f, 1.0f, 1.0f}, {});
            QCOMPARE(transparent.component, 1);
            // both hidden: nothing (C is behind the eye)
            QCOMPARE(pick(model.m, cam.modelview, cam.projection, width, height, width / 2.0, height / 2.0,
                          {0.0f, 1.0f, 1.0f}, {1, 0, 1})
                         .triangle,
                     -1);

            // every 4th pixel against the geometry worked out from the camera's parameters
            int hits_a = 0, hits_b = 0, misses = 0;
            for (int row = 0; row < height; row += 4)
                for (int col = 0; col < width; col += 4) {
                    const double x = col + 0.5, y = row + 0.5;
                    double ax, ay, bx, by;
                    expected_point(ortho, width, height, x, y, 0.0, ax, ay);
                    expected_point(ortho, width, height, x, y, -1.0, bx, by);
                    auto near_edge = [](double v, double half) { return std::fabs(std::fabs(v) - half) < 1e-6; };
                    if (near_edge(ax, 1) || near_edge(ay, 1) || near_edge(bx, 2) || near_edge(by, 2))
                        continue;
                    int expected = -1;
                    if (std::fabs(ax) < 1 && std::fabs(ay) < 1)
                        expected = 0;
                    else if (std::fabs(bx) < 2 && std::fabs(by) < 2)
                        expected = 1;
                    const PickResult r = pick(model.m, cam.modelview, cam.projection, width, height, x, y,
                                              all_alpha, all_visible);
                    QVERIFY2(r.component == expected,
                             qPrintable(QString("%1 pixel %2,%3: %4, expected %5").arg(kind).arg(x).arg(y)
                                            .arg(r.component).arg(expected)));
                    if (expected >= 0) {
                        QCOMPARE(component_of_triangle(model.m, uint32_t(r.triangle)), expected);
                        QVERIFY(std::fabs(r.eye_depth - (expected == 0 ? 5.0 : 6.0)) < 1e-9);
                    } else {
                        QCOMPARE(r.triangle, -1);
                    }
                    (expected == 0 ? hits_a : expected == 1 ? hits_b : misses) += 1;
                }
            // the scan saw all three cases
            QVERIFY2(hits_a > 0 && hits_b > 0 && misses > 0, kind);

            // a pixel off both squares (the corner)
            QCOMPARE(pick(model.m, cam.modelview, cam.projection, width, height, 0.5, 0.5, all_alpha, all_visible)
                         .triangle,
                     -1);
            // outside the frame, zero sizes: nothing
            QCOMPARE(pick(model.m, cam.modelview, cam.projection, 0, 0, 0.5, 0.5, all_alpha, all_visible).triangle, -1);

            // from below (looking up +z from z = -5): back faces count; B is nearest
            Matrices below = cam;
            look_along_z(below.modelview, 5.0f, true);
            PickResult up = pick(model.m, below.modelview, below.projection, width, height, width / 2.0,
                                 height / 2.0, all_alpha, all_visible);
            QCOMPARE(up.component, 1);
            QVERIFY(std::fabs(up.eye_depth - 4.0) < 1e-9);
        }
    }

    void pick_edge_on()
    {
        // one square in the plane x = 0: the centre column's rays lie in it
        Part wall{"wall", {1, 0, 0}, {0, -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1}, {0, 1, 2, 0, 2, 3}, OIT_NO_NODE};
        Model model;
        QString message;
        QVERIFY2(build(model, {wall}, &message), qPrintable(message));
        const int width = 160, height = 120;
        for (bool ortho : {false, true}) {
            Matrices cam;
            look_along_z(cam.modelview, 5.0f, false);
            if (ortho)
                orthographic(cam.projection, double(width) / height);
            else
                perspective(cam.projection, double(width) / height);
            for (int row = 0; row < height; row += 3)
                for (int col = 0; col < width; ++col) {
                    const PickResult r = pick(model.m, cam.modelview, cam.projection, width, height, col + 0.5,
                                              row + 0.5, {}, {});
                    QVERIFY(std::isfinite(r.eye_depth));
                    QCOMPARE(r.triangle, -1);
                }
            const PickResult centre =
                pick(model.m, cam.modelview, cam.projection, width, height, width / 2.0, height / 2.0, {}, {});
            QCOMPARE(centre.triangle, -1);
            QVERIFY(std::isfinite(centre.eye_depth));
        }
    }

    void component_of_triangle_bounds()
    {
        // an empty part between two others
        Part empty{"empty", {0, 0, 0}, {}, {}, OIT_NO_NODE};
        Model model;
        QString message;
        QVERIFY2(build(model, {square("A", 0, 0, 0, 1), empty, square("B", 3, 0, 0, 1), square("C", 6, 0, 0, 1)},
                       &message),
                 qPrintable(message));
        QCOMPARE(component_of_triangle(model.m, 0), 0);
        QCOMPARE(component_of_triangle(model.m, 1), 0);
        QCOMPARE(component_of_triangle(model.m, 2), 2);
        QCOMPARE(component_of_triangle(model.m, 3), 2);
        QCOMPARE(component_of_triangle(model.m, 4), 3);
        QCOMPARE(component_of_triangle(model.m, 5), 3);
        QCOMPARE(component_of_triangle(model.m, 6), -1);
        QCOMPARE(component_of_triangle(model.m, UINT32_MAX), -1);
        // on the 10,000 parts: the first and last triangle of some parts
        for (int c : {0, 1, 4999, 9998, 9999}) {
            const oit_component &comp = many_.m.components[c];
            QCOMPARE(component_of_triangle(many_.m, comp.first_triangle), c);
            QCOMPARE(component_of_triangle(many_.m, comp.first_triangle + comp.triangle_count - 1), c);
        }
    }

    void pick_large_model()
    {
        // an 806 x 806 grid of squares in z = 0 over [-1, 1]^2, two triangles each
        // (1,299,272 triangles), one part per grid row; a vertex belongs to one
        // part only, so each row has its own two rows of vertices
        const int n = 806;
        const double cell = 2.0 / n;
        const uint32_t row_vertices = uint32_t(2 * (n + 1));
        Model model;
        oit_model &m = model.m;
        m.vertex_count = uint32_t(n) * row_vertices;
        m.triangle_count = uint32_t(2 * n * n);
        m.component_count = uint32_t(n);
        m.positions = static_cast<float *>(malloc(size_t(m.vertex_count) * 3 * sizeof(float)));
        m.indices = static_cast<uint32_t *>(malloc(size_t(m.triangle_count) * 3 * sizeof(uint32_t)));
        m.components = static_cast<oit_component *>(calloc(size_t(n), sizeof(oit_component)));
        QVERIFY(m.positions && m.indices && m.components);
        for (int j = 0; j < n; ++j) {
            const uint32_t base = uint32_t(j) * row_vertices;
            for (int edge = 0; edge < 2; ++edge)
                for (int i = 0; i <= n; ++i) {
                    float *p = m.positions + (size_t(base) + size_t(edge) * (n + 1) + i) * 3;
                    p[0] = float(-1.0 + i * cell);
                    p[1] = float(-1.0 + (j + edge) * cell);
                    p[2] = 0.0f;
                }
            for (int i = 0; i < n; ++i) {
                const uint32_t v00 = base + uint32_t(i), v10 = v00 + 1, v01 = v00 + uint32_t(n + 1), v11 = v01 + 1;
                uint32_t *t = m.indices + (size_t(j) * n + i) * 6;
                const uint32_t quad[6] = {v00, v10, v11, v00, v11, v01};
                std::copy(quad, quad + 6, t);
            }
            oit_component &comp = m.components[j];
            snprintf(comp.name, sizeof comp.name, "row_%03d", j);
            comp.colour[0] = comp.colour[1] = comp.colour[2] = 0.5f;
            comp.opacity = 1.0f;
            comp.first_triangle = uint32_t(2 * n * j);
            comp.triangle_count = uint32_t(2 * n);
        }
        QElapsedTimer timer;
        timer.start();
        oit_error err{};
        QVERIFY2(oit_model_finish(&m, true, &err) == OIT_OK, err.message);
        const double finish_ms = double(timer.nsecsElapsed()) / 1e6;

        const int width = 640, height = 480;
        Matrices cam;
        look_along_z(cam.modelview, 5.0f, false);
        perspective(cam.projection, double(width) / height);
        // a pixel well inside one grid square and away from its diagonal
        double x = 0, y = 0, fx = 0, fy = 0;
        int qi = 0, qj = 0;
        bool found = false;
        for (int k = 0; k < 200 && !found; ++k) {
            x = 331.5 + 0.37 * k;
            y = 217.5 + 0.23 * k;
            double px, py;
            expected_point(false, width, height, x, y, 0.0, px, py);
            const double gx = (px + 1.0) / cell, gy = (py + 1.0) / cell;
            qi = int(std::floor(gx));
            qj = int(std::floor(gy));
            fx = gx - qi;
            fy = gy - qj;
            found = fx > 0.1 && fx < 0.9 && fy > 0.1 && fy < 0.9 && std::fabs(fx - fy) > 0.1;
        }
        QVERIFY(found);
        const int expected_triangle = 2 * (qj * n + qi) + (fx > fy ? 0 : 1);

        std::vector<double> times;
        PickResult r;
        for (int k = 0; k < 5; ++k) {
            const auto start = std::chrono::steady_clock::now();
            r = pick(m, cam.modelview, cam.projection, width, height, x, y, {}, {});
            times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
        std::sort(times.begin(), times.end());
        QCOMPARE(r.triangle, expected_triangle);
        QCOMPARE(r.component, qj);
        QCOMPARE(component_of_triangle(m, uint32_t(r.triangle)), qj);
        QVERIFY(std::fabs(r.eye_depth - 5.0) < 1e-6);
        // a miss (a corner pixel off the grid) still looks at every triangle
        const auto start = std::chrono::steady_clock::now();
        QCOMPARE(pick(m, cam.modelview, cam.projection, width, height, 0.5, 0.5, {}, {}).triangle, -1);
        const double miss_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        // that part hidden: the ray goes through the hole
        std::vector<char> visible(size_t(n), 1);
        visible[size_t(qj)] = 0;
        QCOMPARE(pick(m, cam.modelview, cam.projection, width, height, x, y, {}, visible).triangle, -1);
        qInfo("pick on %u triangles: fastest %.1f ms, median %.1f ms, a miss %.1f ms (oit_model_finish %.0f ms)",
              m.triangle_count, times.front(), times[times.size() / 2], miss_ms, finish_ms);
    }
};

QTEST_MAIN(PartsPanelTest)
#include "test_parts_panel.moc"
