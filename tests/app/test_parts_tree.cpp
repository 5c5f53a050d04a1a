// test_parts_tree.cpp: Qt Test cases for the Parts tab as a tree (src/app/parts_panel.*):
// a model with assembly nodes (oit_model.nodes) built in memory: expand and
// collapse, an assembly's check box and slider reaching every part under it,
// a pick revealing its part, the filter, Isolate / Frame on assemblies, and
// 10,000 leaves. Run under Xvfb by CTest (tests/app/parts_panel.cmake).
// Timings are printed (qInfo), never asserted: the machine is shared.

// Also a glTF written by tests/assembly_gltf.py and imported by Assimp: the
// tree the import makes, shown row for row as oit_model_component_path says.

// Mouse events go through the window like real input (as test_parts_panel.cpp).
#define QTEST_QPA_MOUSE_HANDLING

#include <QCheckBox>
#include <QDir>
#include <QElapsedTimer>
#include <QJsonArray>
#include <QJsonDocument>
#include <QProcess>
#include <QTemporaryDir>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalSpy>
#include <QSlider>
#include <QStyleOptionViewItem>
#include <QTreeView>
#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "oit.h"
#include "parts_panel.h"
#include "parts_test_model.h"
#include "pick.h"

using parts_test::build;
using parts_test::Model;
using parts_test::Node;
using parts_test::Part;
using parts_test::square;

namespace {

// The gearbox: nodes first (parents before children), then its parts.
//   gearbox/                      node 0
//     input_shaft/                node 1: shaft (1), gear (2)
//     output_shaft/               node 2: shaft (3)
//       bearings/                 node 3: bearing_1 (4), bearing_2 (5)
//     empty/                      node 4: nothing under it
//     housing                     part 0
//   loose_bolt                    part 6 (at the top, under no node)
const std::vector<Node> gearbox_nodes = {{"gearbox", OIT_NO_NODE},
                                         {"input_shaft", 0},
                                         {"output_shaft", 0},
                                         {"bearings", 2},
                                         {"empty", 0}};

std::vector<Part> gearbox_parts()
{
    // side by side in z = 0, bearing_2 at the centre (for the pick)
    return {square("housing", -6, 0, 0, 0.8f, 0), square("shaft", -4, 0, 0, 0.8f, 1),
            square("gear", -2, 0, 0, 0.8f, 1),    square("shaft", 2, 0, 0, 0.8f, 2),
            square("bearing_1", 4, 0, 0, 0.8f, 3), square("bearing_2", 0, 0, 0, 0.8f, 3),
            square("loose_bolt", 6, 0, 0, 0.8f)};
}

QString leaf_name(int i) { return QString::asprintf("part_%05d", i); }

// Keep a screenshot in $OIT_TEST_WORK (when set) for a look by eye.
void keep(QWidget &widget, const QString &name)
{
    const QString work = qEnvironmentVariable("OIT_TEST_WORK");
    if (!work.isEmpty() && QDir().mkpath(work))
        widget.grab().save(QDir(work).filePath(name));
}

} // namespace

class PartsTreeTest : public QObject {
    Q_OBJECT

private:
    Model gearbox_;
    Model many_; // 10 assemblies x 10 subassemblies x 100 parts
    static constexpr int many_count = 10000;

    void show_panel(PartsPanel &panel, const Model &model)
    {
        panel.resize(520, 600);
        panel.set_model(&model.m, {}, {});
        panel.show();
        QVERIFY(QTest::qWaitForWindowExposed(&panel));
    }

    // the view's row for a path of names from the top ("gearbox", "output_shaft"); invalid if not shown
    QModelIndex row_of(PartsPanel &panel, const QStringList &path, int column = 0)
    {
        QAbstractItemModel *rows = panel.view()->model();
        QModelIndex parent;
        for (const QString &name : path) {
            QModelIndex found;
            for (int r = 0; r < rows->rowCount(parent) && !found.isValid(); ++r)
                if (rows->index(r, 0, parent).data().toString() == name)
                    found = rows->index(r, 0, parent);
            if (!found.isValid())
                return {};
            parent = found;
        }
        return parent.siblingAtColumn(column);
    }

    QStringList child_names(PartsPanel &panel, const QModelIndex &parent)
    {
        QStringList names;
        QAbstractItemModel *rows = panel.view()->model();
        for (int r = 0; r < rows->rowCount(parent); ++r)
            names << rows->index(r, 0, parent).data().toString();
        return names;
    }

    QPoint slider_point(PartsPanel &panel, const QModelIndex &row, double fraction)
    {
        const QRect cell = panel.view()->visualRect(row.siblingAtColumn(PartsModel::OpacityColumn));
        return QPoint(cell.left() + int(std::lround(fraction * (cell.width() - 1))), cell.center().y());
    }

    // the check box of a row's name cell, where the style puts it
    QPoint check_point(PartsPanel &panel, const QModelIndex &row)
    {
        QAbstractItemView *view = panel.view();
        QStyleOptionViewItem option;
        option.initFrom(view);
        option.widget = view;
        option.rect = view->visualRect(row.siblingAtColumn(0));
        option.features = QStyleOptionViewItem::HasCheckIndicator | QStyleOptionViewItem::HasDisplay;
        option.text = row.siblingAtColumn(0).data().toString();
        return view->style()->subElementRect(QStyle::SE_ItemViewItemCheckIndicator, &option, view).center();
    }

    bool on_screen(PartsPanel &panel, const QModelIndex &row)
    {
        const QRect rect = panel.view()->visualRect(row);
        return rect.isValid() && panel.view()->viewport()->rect().contains(rect.center());
    }

    int check_state(const QModelIndex &row) { return row.siblingAtColumn(0).data(Qt::CheckStateRole).toInt(); }

private slots:
    void initTestCase()
    {
        QString message;
        QVERIFY2(build(gearbox_, gearbox_parts(), &message, gearbox_nodes), qPrintable(message));
        QCOMPARE(gearbox_.m.node_count, 5u);

        std::vector<Node> nodes;
        std::vector<Part> parts;
        parts.reserve(many_count);
        for (int a = 0; a < 10; ++a) {
            const uint32_t assembly = uint32_t(nodes.size());
            nodes.push_back({"assembly_" + std::to_string(a), OIT_NO_NODE});
            for (int s = 0; s < 10; ++s) {
                const uint32_t sub = uint32_t(nodes.size());
                nodes.push_back({"sub_" + std::to_string(a) + "_" + std::to_string(s), assembly});
                for (int k = 0; k < 100; ++k) {
                    const int i = int(parts.size());
                    parts.push_back(square(leaf_name(i).toStdString(), float(i % 100), float(i / 100), 0.0f, 0.4f, sub));
                }
            }
        }
        QVERIFY2(build(many_, parts, &message, nodes), qPrintable(message));
        QCOMPARE(many_.m.component_count, uint32_t(many_count));
        QCOMPARE(many_.m.node_count, 110u);
    }

    // The filter's clear button fades in and out with an animation that has no
    // parent and deletes itself when it ends: let it end (else LeakSanitizer
    // reports it at exit).
    void cleanup() { QTest::qWait(250); }

    void expand_and_collapse()
    {
        PartsPanel panel;
        show_panel(panel, gearbox_);
        auto *tree = qobject_cast<QTreeView *>(panel.view());
        QVERIFY(tree && tree->rootIsDecorated() && tree->itemsExpandable());
        QAbstractItemModel *rows = panel.view()->model();
        // the top: the assembly and the part under no node; children: nodes first, then parts
        QCOMPARE(child_names(panel, {}), (QStringList{"gearbox", "loose_bolt"}));
        const QModelIndex gearbox = row_of(panel, {"gearbox"});
        QCOMPARE(child_names(panel, gearbox), (QStringList{"input_shaft", "output_shaft", "empty", "housing"}));
        QCOMPARE(child_names(panel, row_of(panel, {"gearbox", "output_shaft"})), (QStringList{"bearings", "shaft"}));
        QCOMPARE(rows->rowCount(row_of(panel, {"gearbox", "empty"})), 0);
        QVERIFY(!rows->hasChildren(row_of(panel, {"loose_bolt"})));
        QVERIFY(rows->flags(row_of(panel, {"loose_bolt"})) & Qt::ItemNeverHasChildren);
        QVERIFY(!(rows->flags(gearbox) & Qt::ItemNeverHasChildren));
        QString note;
        for (QLabel *label : panel.findChildren<QLabel *>())
            note += label->text();
        QVERIFY2(note.contains("7 parts in 5 assemblies"), qPrintable(note));

        // opened one level: gearbox's children in sight, input_shaft's not
        const QModelIndex input = row_of(panel, {"gearbox", "input_shaft"});
        const QModelIndex gear = row_of(panel, {"gearbox", "input_shaft", "gear"});
        QVERIFY(tree->isExpanded(gearbox));
        QVERIFY(!tree->isExpanded(input));
        QVERIFY(on_screen(panel, input));
        QVERIFY(!on_screen(panel, gear));

        // the branch arrow opens it
        const QRect input_rect = tree->visualRect(input);
        const QPoint arrow(input_rect.left() - tree->indentation() / 2, input_rect.center().y());
        QTest::mouseClick(tree->viewport(), Qt::LeftButton, Qt::NoModifier, arrow);
        QVERIFY(tree->isExpanded(input));
        QVERIFY(on_screen(panel, gear));
        // Shift+Left closes the current assembly, Shift+Right opens it; Shift+Left on a part goes up
        tree->setFocus();
        tree->selectionModel()->setCurrentIndex(input, QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
        QTest::keyClick(tree, Qt::Key_Left, Qt::ShiftModifier);
        QVERIFY(!tree->isExpanded(input));
        QVERIFY(!on_screen(panel, gear));
        QTest::keyClick(tree, Qt::Key_Right, Qt::ShiftModifier);
        QVERIFY(tree->isExpanded(input));
        tree->selectionModel()->setCurrentIndex(gear, QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
        QTest::keyClick(tree, Qt::Key_Left, Qt::ShiftModifier);
        QCOMPARE(tree->currentIndex().siblingAtColumn(0), input);
        // collapsing the top hides everything under it
        tree->collapse(gearbox);
        QVERIFY(!on_screen(panel, input) && !on_screen(panel, gear));
        QVERIFY(on_screen(panel, row_of(panel, {"loose_bolt"})));
        // double-click on an assembly's name opens it and frames nothing
        QSignalSpy frame(&panel, &PartsPanel::frame_selected_requested);
        const QRect gearbox_rect = tree->visualRect(gearbox);
        QTest::mouseDClick(tree->viewport(), Qt::LeftButton, Qt::NoModifier,
                           QPoint(gearbox_rect.left() + 40, gearbox_rect.center().y()));
        QVERIFY(tree->isExpanded(gearbox));
        QCOMPARE(frame.count(), 0);

        // a model without nodes is the flat list
        Model flat;
        QString message;
        QVERIFY2(build(flat, {square("A", 0, 0, 0, 1), square("B", 3, 0, 0, 1)}, &message), qPrintable(message));
        panel.set_model(&flat.m, {}, {});
        QVERIFY(!tree->rootIsDecorated() && !tree->itemsExpandable());
        QCOMPARE(child_names(panel, {}), (QStringList{"A", "B"}));
        panel.set_model(nullptr, {}, {}); // before flat is freed
    }

    void assembly_opacity_and_visibility()
    {
        PartsPanel panel;
        show_panel(panel, gearbox_);
        auto *tree = qobject_cast<QTreeView *>(panel.view());
        tree->expandAll();
        QSignalSpy changed(&panel, &PartsPanel::parts_changed);
        QWidget *viewport = tree->viewport();
        const QModelIndex output = row_of(panel, {"gearbox", "output_shaft"});
        const QModelIndex gearbox = row_of(panel, {"gearbox"});
        const std::vector<int> under_output{3, 4, 5};

        // a click on output_shaft's slider at a quarter: every part under it, nothing else, one change
        QTest::mouseClick(viewport, Qt::LeftButton, Qt::NoModifier, slider_point(panel, output, 0.25));
        QCOMPARE(changed.count(), 1); // one parts_changed: one undo step in the window
        const float quarter = panel.alpha()[3];
        QVERIFY2(quarter > 0.1f && quarter < 0.4f, qPrintable(QString::number(quarter)));
        for (int part : under_output)
            QCOMPARE(panel.alpha()[size_t(part)], quarter);
        for (int part : {0, 1, 2, 6})
            QCOMPARE(panel.alpha()[size_t(part)], 1.0f);
        // the rows sum it up: output_shaft one value, gearbox mixed
        QCOMPARE(output.siblingAtColumn(PartsModel::PercentColumn).data().toString(),
                 QString("%1%").arg(PartsModel::percent(quarter)));
        QVERIFY(!output.siblingAtColumn(PartsModel::OpacityColumn).data(PartsModel::MixedAlphaRole).toBool());
        QVERIFY(gearbox.siblingAtColumn(PartsModel::OpacityColumn).data(PartsModel::MixedAlphaRole).toBool());
        QCOMPARE(gearbox.siblingAtColumn(PartsModel::PercentColumn).data().toString(),
                 QString("%1-100%").arg(PartsModel::percent(quarter)));
        // the gearbox's slider stands at its six parts' mean
        const double mean = (3 * double(quarter) + 3.0) / 6.0;
        QVERIFY(std::fabs(gearbox.siblingAtColumn(PartsModel::OpacityColumn).data(PartsModel::AlphaRole).toDouble() -
                          mean) < 1e-6);
        // dragging gearbox's slider sets all six; loose_bolt (not under it) stays
        QTest::mousePress(viewport, Qt::LeftButton, Qt::NoModifier, slider_point(panel, gearbox, 0.5));
        QTest::mouseMove(viewport, slider_point(panel, gearbox, 0.75));
        QTest::mouseRelease(viewport, Qt::LeftButton, Qt::NoModifier, slider_point(panel, gearbox, 0.75));
        const float three_quarters = panel.alpha()[0];
        QVERIFY2(three_quarters > 0.6f && three_quarters < 0.9f, qPrintable(QString::number(three_quarters)));
        for (int part = 0; part < 6; ++part)
            QCOMPARE(panel.alpha()[size_t(part)], three_quarters);
        QCOMPARE(panel.alpha()[6], 1.0f);
        QVERIFY(!gearbox.siblingAtColumn(PartsModel::OpacityColumn).data(PartsModel::MixedAlphaRole).toBool());

        // the check box: output_shaft hides its three parts; gearbox is partly checked
        const int before = changed.count();
        QTest::mouseClick(viewport, Qt::LeftButton, Qt::NoModifier, check_point(panel, output));
        QCOMPARE(changed.count(), before + 1);
        for (int part = 0; part < 7; ++part)
            QCOMPARE(int(panel.visible()[size_t(part)]), part >= 3 && part <= 5 ? 0 : 1);
        QCOMPARE(check_state(output), int(Qt::Unchecked));
        QCOMPARE(check_state(row_of(panel, {"gearbox", "output_shaft", "bearings"})), int(Qt::Unchecked));
        QCOMPARE(check_state(gearbox), int(Qt::PartiallyChecked));
        QCOMPARE(check_state(row_of(panel, {"gearbox", "empty"})), int(Qt::Checked));
        // clicking the partly checked gearbox shows everything under it
        QTest::mouseClick(viewport, Qt::LeftButton, Qt::NoModifier, check_point(panel, gearbox));
        QCOMPARE(changed.count(), before + 2);
        QCOMPARE(int(std::count(panel.visible().begin(), panel.visible().end(), char(1))), 7);
        QCOMPARE(check_state(gearbox), int(Qt::Checked));

        // the keys on an assembly's row: every part under it
        tree->setFocus();
        tree->selectionModel()->setCurrentIndex(output, QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
        const int percent = PartsModel::percent(three_quarters);
        QTest::keyClick(tree, Qt::Key_Minus);
        for (int part : under_output)
            QCOMPARE(PartsModel::percent(panel.alpha()[size_t(part)]), percent - 5);
        QCOMPARE(panel.alpha()[0], three_quarters);
        QTest::keyClick(tree, Qt::Key_Space);
        for (int part : under_output)
            QCOMPARE(int(panel.visible()[size_t(part)]), 0);
        QTest::keyClick(tree, Qt::Key_Space);
        for (int part : under_output)
            QCOMPARE(int(panel.visible()[size_t(part)]), 1);
        QCOMPARE(changed.count(), before + 5);

        keep(panel, "parts_tree_gearbox.png"); // output_shaft at 70%, gearbox mixed
        // an outside change (undo, preset) reaches the assemblies' rows
        std::vector<char> visible(7, 1);
        visible[4] = 0;
        panel.set_values(std::vector<float>(7, 1.0f), visible);
        QCOMPARE(check_state(row_of(panel, {"gearbox", "output_shaft", "bearings"})), int(Qt::PartiallyChecked));
        QCOMPARE(gearbox.siblingAtColumn(PartsModel::PercentColumn).data().toString(), QString("100%"));
        QCOMPARE(changed.count(), before + 5);
    }

    void pick_reveals_part()
    {
        PartsPanel panel;
        show_panel(panel, gearbox_);
        auto *tree = qobject_cast<QTreeView *>(panel.view());
        QSignalSpy selection(&panel, &PartsPanel::selection_changed);
        const QModelIndex output = row_of(panel, {"gearbox", "output_shaft"});
        QVERIFY(!tree->isExpanded(output));

        // a pixel near the centre of a camera on the z axis hits bearing_2, as the window's pick_at does
        double modelview[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -10, 1};
        const double f = 1.0 / std::tan(20.0 * 3.14159265358979323846 / 180.0);
        double projection[16] = {f, 0, 0, 0, 0, f, 0, 0, 0, 0, -101.0 / 99.0, -1, 0, 0, -200.0 / 99.0, 0};
        const PickResult hit = pick(gearbox_.m, modelview, projection, 96, 96, 50.0, 45.0, {}, {});
        QCOMPARE(hit.component, 5);
        panel.select_part(hit.component);

        // its assemblies opened, it is selected, current and on screen
        const QModelIndex bearing = row_of(panel, {"gearbox", "output_shaft", "bearings", "bearing_2"});
        QVERIFY(bearing.isValid());
        QVERIFY(tree->isExpanded(output) && tree->isExpanded(bearing.parent()));
        QVERIFY(!tree->isExpanded(row_of(panel, {"gearbox", "input_shaft"})));
        QCOMPARE(panel.selected_parts(), std::vector<int>{5});
        QCOMPARE(selection.last().at(0).value<std::vector<int>>(), std::vector<int>{5});
        QCOMPARE(tree->currentIndex().siblingAtColumn(0), bearing);
        QVERIFY(on_screen(panel, bearing));

        // a filter that hides it is cleared; one that shows it stays
        panel.filter()->setText("housing");
        panel.select_part(4);
        QVERIFY(panel.filter()->text().isEmpty());
        QCOMPARE(panel.selected_parts(), std::vector<int>{4});
        panel.filter()->setText("BEAR"); // the node "bearings": everything under it
        panel.select_part(5);
        QCOMPARE(panel.filter()->text(), QString("BEAR"));
        QCOMPARE(panel.selected_parts(), std::vector<int>{5});
        QVERIFY(on_screen(panel, tree->currentIndex()));

        // on a panel not shown yet (the Parts tab in the background): revealed when shown
        PartsPanel hidden;
        hidden.resize(520, 600);
        hidden.set_model(&gearbox_.m, {}, {});
        hidden.select_part(5);
        hidden.show();
        QVERIFY(QTest::qWaitForWindowExposed(&hidden));
        QCOMPARE(hidden.selected_parts(), std::vector<int>{5});
        QVERIFY(on_screen(hidden, row_of(hidden, {"gearbox", "output_shaft", "bearings", "bearing_2"})));
    }

    void filter_keeps_ancestors_and_subtrees()
    {
        PartsPanel panel;
        show_panel(panel, gearbox_);
        auto *tree = qobject_cast<QTreeView *>(panel.view());
        // a part's name: it and the way down to it
        panel.filter()->setText("bearing_");
        QCOMPARE(child_names(panel, {}), QStringList{"gearbox"});
        QCOMPARE(child_names(panel, row_of(panel, {"gearbox"})), QStringList{"output_shaft"});
        QCOMPARE(child_names(panel, row_of(panel, {"gearbox", "output_shaft"})), QStringList{"bearings"});
        QCOMPARE(child_names(panel, row_of(panel, {"gearbox", "output_shaft", "bearings"})),
                 (QStringList{"bearing_1", "bearing_2"}));
        // opened to show them
        QVERIFY(on_screen(panel, row_of(panel, {"gearbox", "output_shaft", "bearings", "bearing_1"})));
        // an assembly's name: everything under it, whatever its name
        panel.filter()->setText("INPUT");
        QCOMPARE(child_names(panel, row_of(panel, {"gearbox"})), QStringList{"input_shaft"});
        QCOMPARE(child_names(panel, row_of(panel, {"gearbox", "input_shaft"})), (QStringList{"shaft", "gear"}));
        // a name in two places: both, with their ways
        panel.filter()->setText("shaft");
        QCOMPARE(child_names(panel, row_of(panel, {"gearbox"})), (QStringList{"input_shaft", "output_shaft"}));
        QCOMPARE(child_names(panel, row_of(panel, {"gearbox", "output_shaft"})), (QStringList{"bearings", "shaft"}));
        // a new model (the same file loaded again) keeps the filter, opened
        panel.set_model(&gearbox_.m, {}, {});
        QCOMPARE(child_names(panel, row_of(panel, {"gearbox"})), (QStringList{"input_shaft", "output_shaft"}));
        QVERIFY(on_screen(panel, row_of(panel, {"gearbox", "output_shaft", "shaft"})));
        // an assembly's percent range is not cut short
        QAbstractItemModel *rows = panel.view()->model();
        QVERIFY(rows->setData(row_of(panel, {"gearbox", "input_shaft"}, PartsModel::OpacityColumn), 0.2,
                              PartsModel::AlphaRole));
        const QModelIndex range = row_of(panel, {"gearbox"}, PartsModel::PercentColumn);
        QCOMPARE(range.data().toString(), QString("20-100%"));
        QVERIFY(tree->fontMetrics().horizontalAdvance(range.data().toString()) < tree->visualRect(range).width());
        // nothing matches: nothing shown
        panel.filter()->setText("no such part");
        QCOMPARE(panel.shown_row_count(), 0);
        // cleared: everything back, closed to the first level again
        panel.filter()->clear();
        QCOMPARE(child_names(panel, {}), (QStringList{"gearbox", "loose_bolt"}));
        QCOMPARE(child_names(panel, row_of(panel, {"gearbox"})).size(), 4);
        QVERIFY(!tree->isExpanded(row_of(panel, {"gearbox", "output_shaft"})));
    }

    void isolate_and_frame_assemblies()
    {
        PartsPanel panel;
        show_panel(panel, gearbox_);
        auto *tree = qobject_cast<QTreeView *>(panel.view());
        QSignalSpy changed(&panel, &PartsPanel::parts_changed);
        QSignalSpy frame(&panel, &PartsPanel::frame_selected_requested);
        auto *isolate = panel.findChild<QPushButton *>("parts_isolate");
        auto *frame_button = panel.findChild<QPushButton *>("parts_frame");
        auto *show_all = panel.findChild<QPushButton *>("parts_show_all");
        QVERIFY(isolate && frame_button && show_all);

        // output_shaft's row stands for its three parts
        const QModelIndex output = row_of(panel, {"gearbox", "output_shaft"});
        const QRect rect = tree->visualRect(output);
        QTest::mouseClick(tree->viewport(), Qt::LeftButton, Qt::NoModifier, QPoint(rect.left() + 60, rect.center().y()));
        QCOMPARE(panel.selected_parts(), (std::vector<int>{3, 4, 5}));
        QVERIFY(isolate->isEnabled() && frame_button->isEnabled());
        QTest::mouseClick(frame_button, Qt::LeftButton);
        QCOMPARE(frame.count(), 1);
        QCOMPARE(frame.last().at(0).value<std::vector<int>>(), (std::vector<int>{3, 4, 5}));
        QTest::mouseClick(isolate, Qt::LeftButton);
        QCOMPARE(changed.count(), 1);
        for (int part = 0; part < 7; ++part)
            QCOMPARE(int(panel.visible()[size_t(part)]), part >= 3 && part <= 5 ? 1 : 0);
        // an assembly and a part under it, and one outside it: each part once
        const QModelIndex housing = row_of(panel, {"gearbox", "housing"});
        tree->expand(output);
        const QModelIndex shaft = row_of(panel, {"gearbox", "output_shaft", "shaft"});
        tree->selectionModel()->select(shaft, QItemSelectionModel::Select | QItemSelectionModel::Rows);
        tree->selectionModel()->select(housing, QItemSelectionModel::Select | QItemSelectionModel::Rows);
        QCOMPARE(panel.selected_parts(), (std::vector<int>{0, 3, 4, 5}));
        // double-click on a part's name frames that part
        tree->expand(row_of(panel, {"gearbox", "output_shaft", "bearings"}));
        const QRect bearing = tree->visualRect(row_of(panel, {"gearbox", "output_shaft", "bearings", "bearing_1"}));
        QTest::mouseDClick(tree->viewport(), Qt::LeftButton, Qt::NoModifier,
                           QPoint(bearing.left() + 40, bearing.center().y()));
        QCOMPARE(frame.last().at(0).value<std::vector<int>>(), std::vector<int>{4});
        QTest::mouseClick(show_all, Qt::LeftButton);
        QCOMPARE(int(std::count(panel.visible().begin(), panel.visible().end(), char(1))), 7);
    }

    void generated_gltf_assembly()
    {
        // the file and, per part in order, its name and path (tests/assembly_gltf.py)
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const QString file = dir.filePath("gearbox.gltf");
        QProcess python;
        python.start("python3", {QStringLiteral(OIT_SOURCE_DIR "/tests/assembly_gltf.py"), file});
        QVERIFY(python.waitForFinished(30000));
        QCOMPARE(python.exitCode(), 0);
        const QJsonArray expected = QJsonDocument::fromJson(python.readAllStandardOutput()).array();
        QVERIFY(expected.size() >= 5);
        Model model;
        oit_error err{};
        QVERIFY2(oit_model_load(file.toUtf8().constData(), &model.m, &err) == OIT_OK, err.message);
        QCOMPARE(int(model.m.component_count), expected.size());
        QVERIFY(model.m.node_count > 0);

        PartsPanel panel;
        show_panel(panel, model);
        auto *tree = qobject_cast<QTreeView *>(panel.view());
        tree->expandAll();
        // every row: a part's path from its row's ancestors, each part once
        QAbstractItemModel *rows = panel.view()->model();
        QHash<QString, QString> shown_path; // part name -> path through the rows
        std::vector<std::pair<QModelIndex, QString>> stack{{QModelIndex(), QString()}};
        while (!stack.empty()) {
            const auto [parent, prefix] = stack.back();
            stack.pop_back();
            for (int r = 0; r < rows->rowCount(parent); ++r) {
                const QModelIndex row = rows->index(r, 0, parent);
                const QString path = prefix + row.data().toString();
                if (rows->flags(row) & Qt::ItemNeverHasChildren) {
                    QVERIFY2(!shown_path.contains(row.data().toString()), qPrintable(path));
                    shown_path.insert(row.data().toString(), path);
                } else {
                    stack.push_back({row, path + '/'});
                }
            }
        }
        QCOMPARE(shown_path.size(), expected.size());
        for (int c = 0; c < expected.size(); ++c) {
            const QString name = expected[c].toArray()[0].toString(), path = expected[c].toArray()[1].toString();
            QCOMPARE(shown_path.value(name), path);
            char core_path[1024];
            oit_model_component_path(&model.m, uint32_t(c), core_path, sizeof core_path);
            QCOMPARE(QString::fromUtf8(core_path), path);
        }

        // the deepest part revealed from a closed tree, as a pick does
        tree->collapseAll();
        const int last = expected.size() - 1;
        panel.select_part(last);
        QCOMPARE(panel.selected_parts(), std::vector<int>{last});
        QVERIFY(on_screen(panel, tree->currentIndex()));
        QCOMPARE(tree->currentIndex().siblingAtColumn(0).data().toString(), expected[last].toArray()[0].toString());

        // output_shaft's slider reaches exactly the parts whose path is under it
        const QModelIndex output = row_of(panel, {"gearbox", "output_shaft"});
        QVERIFY(output.isValid());
        QVERIFY(rows->setData(output.siblingAtColumn(PartsModel::OpacityColumn), 0.3, PartsModel::AlphaRole));
        int under = 0;
        for (int c = 0; c < expected.size(); ++c) {
            const bool in = expected[c].toArray()[1].toString().startsWith("gearbox/output_shaft/");
            QCOMPARE(panel.alpha()[size_t(c)], in ? 0.3f : 1.0f);
            under += in;
        }
        QVERIFY(under >= 2);
        panel.set_model(nullptr, {}, {});
    }

    void ten_thousand_leaves()
    {
        PartsPanel panel;
        panel.resize(520, 600);
        panel.show();
        QVERIFY(QTest::qWaitForWindowExposed(&panel));
        auto *tree = qobject_cast<QTreeView *>(panel.view());
        QElapsedTimer timer;
        timer.start();
        panel.set_model(&many_.m, {}, {});
        const double set_model_ms = double(timer.nsecsElapsed()) / 1e6;
        timer.restart();
        QCoreApplication::processEvents();
        QImage first = panel.grab().toImage();
        const double first_paint_ms = double(timer.nsecsElapsed()) / 1e6;
        QVERIFY(!first.isNull());
        QAbstractItemModel *rows = panel.view()->model();
        QCOMPARE(rows->rowCount(), 10);
        QCOMPARE(rows->rowCount(rows->index(9, 0)), 10);
        // no widget per row
        QCOMPARE(panel.findChildren<QSlider *>().size(), 0);
        QCOMPARE(panel.findChildren<QCheckBox *>().size(), 0);
        QVERIFY(panel.findChildren<QWidget *>().size() < 40);
        QVERIFY(tree->uniformRowHeights());

        // everything open, and the last part painted at the bottom
        timer.restart();
        tree->expandAll();
        QCoreApplication::processEvents();
        const double expand_ms = double(timer.nsecsElapsed()) / 1e6;
        timer.restart();
        tree->scrollToBottom();
        QCoreApplication::processEvents();
        QImage bottom = panel.grab().toImage();
        const double bottom_paint_ms = double(timer.nsecsElapsed()) / 1e6;
        QVERIFY(!bottom.isNull());
        const QModelIndex last = row_of(panel, {"assembly_9", "sub_9_9", leaf_name(many_count - 1)});
        QVERIFY(on_screen(panel, last));

        // an assembly's slider: its 1,000 parts in one change
        QSignalSpy changed(&panel, &PartsPanel::parts_changed);
        timer.restart();
        QVERIFY(rows->setData(rows->index(3, PartsModel::OpacityColumn), 0.4, PartsModel::AlphaRole));
        QCoreApplication::processEvents();
        const double assembly_alpha_ms = double(timer.nsecsElapsed()) / 1e6;
        QCOMPARE(changed.count(), 1);
        QCOMPARE(int(std::count(panel.alpha().begin(), panel.alpha().end(), 0.4f)), 1000);
        QCOMPARE(panel.alpha()[3000], 0.4f); // assembly_3: parts 3000..3999
        QCOMPARE(panel.alpha()[3999], 0.4f);
        QCOMPARE(panel.alpha()[2999], 1.0f);
        QCOMPARE(panel.alpha()[4000], 1.0f);

        // filter: one part among 10,000, then a subassembly's name
        timer.restart();
        panel.filter()->setText("part_09999");
        QCoreApplication::processEvents();
        const double filter_ms = double(timer.nsecsElapsed()) / 1e6;
        QCOMPARE(child_names(panel, {}), QStringList{"assembly_9"});
        QVERIFY(on_screen(panel, row_of(panel, {"assembly_9", "sub_9_9", "part_09999"})));
        panel.filter()->setText("sub_4_2");
        QCOMPARE(rows->rowCount(row_of(panel, {"assembly_4", "sub_4_2"})), 100);
        timer.restart();
        panel.filter()->clear();
        QCoreApplication::processEvents();
        const double clear_ms = double(timer.nsecsElapsed()) / 1e6;
        QCOMPARE(rows->rowCount(), 10);

        // a pick reveals a part deep down
        tree->collapseAll();
        timer.restart();
        panel.select_part(5678);
        QCoreApplication::processEvents();
        const double reveal_ms = double(timer.nsecsElapsed()) / 1e6;
        QCOMPARE(panel.selected_parts(), std::vector<int>{5678});
        QVERIFY(on_screen(panel, tree->currentIndex()));
        QCOMPARE(tree->currentIndex().siblingAtColumn(0).data().toString(), leaf_name(5678));
        qInfo("10,000 leaves under 110 assemblies: set_model %.1f ms, layout and first paint %.1f ms, expand all "
              "%.1f ms, scroll to the bottom and paint %.1f ms, an assembly's opacity (1,000 parts) %.1f ms, "
              "filter to one part %.1f ms, clear the filter %.1f ms, reveal a part %.1f ms",
              set_model_ms, first_paint_ms, expand_ms, bottom_paint_ms, assembly_alpha_ms, filter_ms, clear_ms,
              reveal_ms);
    }
};

QTEST_MAIN(PartsTreeTest)
#include "test_parts_tree.moc"
