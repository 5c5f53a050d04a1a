// test_measure.cpp (app_measure): Measure ▸ Measure distance (issue 28, part 3)
// on the real window at 160x120 under Xvfb. Two unit cubes whose centres are
// 6 units apart along x (a gap of 5), seen from the front in an orthographic
// view: clicks on their front faces (z = 1, facing the camera, so the pick's
// point is exact) give the distance between the pixel centres' points on that
// plane, which the test computes itself; a background click and a hidden part
// set nothing; a third click starts again; the markers follow the camera;
// Copy measurement (Ctrl+C) puts the line on the clipboard; Esc leaves. A STEP
// file (in millimetres) says mm; the units' text for an inch file and for a
// format without units.
#include <QAction>
#include <QApplication>
#include <QClipboard>
#include <QFile>
#include <QSignalSpy>
#include <QtTest/QtTest>

#include <cmath>
#include <cstring>
#include <vector>

#include "main_window.h"
#include "measure_tool.h"
#include "render_view.h"
#include "settings_model.h"
#include "window_test_main.h"

namespace {

const QSize view_size(160, 120);

// an axis-aligned box as OBJ faces, outward (counter-clockwise seen from outside)
QString obj_box(const QString &name, double x0, double y0, double z0, double x1, double y1, double z1, int first)
{
    QString text = "o " + name + "\n";
    const double x[2] = {x0, x1}, y[2] = {y0, y1}, z[2] = {z0, z1};
    for (int i = 0; i < 8; ++i)
        text += QString("v %1 %2 %3\n").arg(x[i & 1]).arg(y[(i >> 1) & 1]).arg(z[(i >> 2) & 1]);
    // vertex i: x bit 0, y bit 1, z bit 2 (1-based + first)
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto &q : quads)
        text += QString("f %1 %2 %3 %4\n").arg(first + q[0]).arg(first + q[1]).arg(first + q[2]).arg(first + q[3]);
    return text;
}

// inverse * (ndc, 1) divided by w
bool unproject(const double inverse[16], double nx, double ny, double nz, double out[3])
{
    double v[4];
    for (int row = 0; row < 4; ++row)
        v[row] = inverse[row] * nx + inverse[4 + row] * ny + inverse[8 + row] * nz + inverse[12 + row];
    if (std::fabs(v[3]) < 1e-300)
        return false;
    for (int k = 0; k < 3; ++k)
        out[k] = v[k] / v[3];
    return true;
}

} // namespace

class MeasureTest : public QObject {
    Q_OBJECT
private:
    MainWindow *window = nullptr;
    QString work;
    RenderView *view() { return window->view(); }
    const MeasureTool &tool() { return window->measure_tool(); }

    bool load(const QString &path)
    {
        QSignalSpy loaded(window, &MainWindow::model_loaded);
        window->load_model(path);
        return loaded.wait(60000);
    }
    // the front view, orthographic, the whole model framed
    void front_view()
    {
        window->set_camera_mode(Camera::Mode::Orbit, true);
        QSize size = view()->pixel_size();
        window->settings_model()->camera().set_view_direction(0.0f, 0.0f, size.width(), size.height());
        window->settings_model()->camera_edited();
        view()->request_frame(false);
    }
    oit_frame_settings frame()
    {
        std::vector<float> storage;
        return view()->current_frame(storage);
    }
    // the pixel where a file-coordinate point projects (floored: the pixel containing it)
    QPoint pixel_of(const double p[3])
    {
        oit_frame_settings f = frame();
        double mvp[16];
        oit_mat4_multiply(f.projection, f.modelview, mvp);
        double clip[4];
        for (int row = 0; row < 4; ++row)
            clip[row] = mvp[row] * p[0] + mvp[4 + row] * p[1] + mvp[8 + row] * p[2] + mvp[12 + row];
        return QPoint(int(std::floor((clip[0] / clip[3] + 1.0) * 0.5 * f.width)),
                      int(std::floor((1.0 - clip[1] / clip[3]) * 0.5 * f.height)));
    }
    // where the pixel centre's ray meets the plane z = plane_z (file coordinates)
    bool point_at(QPoint pixel, double plane_z, double out[3])
    {
        oit_frame_settings f = frame();
        double mvp[16], inverse[16];
        oit_mat4_multiply(f.projection, f.modelview, mvp);
        if (!oit_mat4_inverse_double(mvp, inverse))
            return false;
        const double nx = 2.0 * (pixel.x() + 0.5) / f.width - 1.0, ny = 1.0 - 2.0 * (pixel.y() + 0.5) / f.height;
        double near_point[3], far_point[3];
        if (!unproject(inverse, nx, ny, -1.0, near_point) || !unproject(inverse, nx, ny, 1.0, far_point))
            return false;
        const double t = (plane_z - near_point[2]) / (far_point[2] - near_point[2]);
        for (int k = 0; k < 3; ++k)
            out[k] = near_point[k] + t * (far_point[k] - near_point[k]);
        return true;
    }
    void click(QPoint pixel) { QTest::mouseClick(view(), Qt::LeftButton, Qt::NoModifier, pixel); }
    // the view as it shows on screen, overlay included
    QColor shown_at(QPoint pixel) { return view()->grab().toImage().pixelColor(pixel); }
    static bool is_ink(const QColor &c) { return c.red() > 200 && c.green() > 170 && c.blue() < 80; }

private slots:
    void initTestCase()
    {
        QStandardPaths::setTestModeEnabled(true);
        work = qEnvironmentVariable("OIT_TEST_WORK", QDir::tempPath() + "/oit-workbench-test") + "/measure";
        QDir().mkpath(work);
        QFile obj(work + "/two_cubes.obj");
        QVERIFY(obj.open(QIODevice::WriteOnly | QIODevice::Truncate));
        obj.write((obj_box("cube_a", 0, 0, 0, 1, 1, 1, 1) + obj_box("cube_b", 6, 0, 0, 7, 1, 1, 9)).toUtf8());
        obj.close();
        window = new MainWindow(MainWindow::Start::Fresh);
        window->show();
        QVERIFY(QTest::qWaitForWindowExposed(window));
        view()->setFixedSize(view_size);
        QTRY_COMPARE(view()->size(), view_size);
        QVERIFY2(load(work + "/two_cubes.obj"), qPrintable(window->last_error()));
        QCOMPARE(window->model()->component_count, 2u);
    }
    void cleanupTestCase() { delete window; }

    // Two clicks on the cubes' front faces: the distance between the points
    // the pixel centres' rays meet z = 1, within 1e-4 (float positions), and
    // within two pixels of the 6 units between the faces' centres.
    void distance_between_two_faces()
    {
        front_view();
        window->activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(window));
        QAction *measure = window->findChild<QAction *>("measure_distance");
        QVERIFY(measure);
        QCOMPARE(measure->shortcut(), QKeySequence("M"));
        QTest::keyClick(view(), Qt::Key_M);
        QVERIFY(window->measuring());
        QVERIFY(tool().empty());

        const double centre_a[3] = {0.5, 0.5, 1.0}, centre_b[3] = {6.5, 0.5, 1.0};
        const QPoint pa = pixel_of(centre_a), pb = pixel_of(centre_b);
        double expect_a[3], expect_b[3];
        QVERIFY(point_at(pa, 1.0, expect_a) && point_at(pb, 1.0, expect_b));

        // the background sets nothing
        click(QPoint(2, 2));
        QVERIFY(tool().empty());
        QVERIFY2(window->status_text().contains("nothing under the pointer"), qPrintable(window->status_text()));

        click(pa);
        QVERIFY(tool().a().set && !tool().b().set);
        QCOMPARE(tool().a().part, QString("cube_a"));
        for (int k = 0; k < 3; ++k)
            QVERIFY2(std::fabs(tool().a().point[k] - expect_a[k]) < 1e-4,
                     qPrintable(QString("A[%1] %2, expected %3").arg(k).arg(tool().a().point[k]).arg(expect_a[k])));
        click(pb);
        QVERIFY(tool().complete());
        QCOMPARE(tool().b().part, QString("cube_b"));
        for (int k = 0; k < 3; ++k)
            QVERIFY(std::fabs(tool().b().point[k] - expect_b[k]) < 1e-4);
        const double expected = std::hypot(expect_b[0] - expect_a[0], expect_b[1] - expect_a[1],
                                           expect_b[2] - expect_a[2]);
        QVERIFY2(std::fabs(tool().distance() - expected) < 1e-4,
                 qPrintable(QString("distance %1, expected %2").arg(tool().distance(), 0, 'g', 9).arg(expected)));
        const double pixel = 2.0 * window->settings_model()->camera().scene_radius / view_size.height();
        QVERIFY2(std::fabs(tool().distance() - 6.0) < 2.0 * pixel, qPrintable(QString::number(tool().distance())));

        // the text: model units (OBJ has none), 5 decimals for a model 7.1 across
        const QString line = tool().text();
        QVERIFY2(line.startsWith(QString("distance %1 units from cube_a (").arg(tool().distance(), 0, 'f', 5)),
                 qPrintable(line));
        QVERIFY(line.contains(" to cube_b ("));
        QVERIFY(window->status_text().contains(line));
        QVERIFY(window->messages().last().contains(line));

        // drawn: the markers at A and B and the line between them (background there)
        view()->repaint();
        QVERIFY(is_ink(shown_at(pa)));
        QVERIFY(is_ink(shown_at(pb)));
        const QPoint middle((pa.x() + pb.x()) / 2, pa.y());
        QVERIFY(is_ink(shown_at(middle)));
        // the markers follow the camera at once (reprojected, not the last frame's)
        window->settings_model()->camera().pan(glm::vec2(0.0f, 20.0f), view_size.width(), view_size.height());
        window->settings_model()->camera_edited();
        view()->repaint();
        const QPoint moved = pixel_of(tool().a().point);
        QVERIFY(std::abs(moved.y() - pa.y()) >= 15);
        QVERIFY(is_ink(shown_at(moved)));

        // Copy measurement (Ctrl+C): the line on the clipboard, and in the Messages
        QApplication::clipboard()->clear();
        QTest::keyClick(view(), Qt::Key_C, Qt::ControlModifier);
        QCOMPARE(QApplication::clipboard()->text(), line);
        QVERIFY(window->messages().last().contains("copied: " + line));

        // a third click starts again
        front_view();
        click(pb);
        QVERIFY(tool().a().set && !tool().b().set);
        QCOMPARE(tool().a().part, QString("cube_b"));

        // Esc leaves: the markers go, a click selects again
        QTest::keyClick(view(), Qt::Key_Escape);
        QVERIFY(!window->measuring());
        QVERIFY(tool().empty());
    }

    // The pick is the click's: a hidden part is not measured (nothing behind it: no point).
    void hidden_part_is_not_measured()
    {
        front_view();
        window->set_measuring(false); // a fresh start, whatever the test before left
        window->set_measuring(true);
        window->set_part_visible(0, false);
        const double centre_a[3] = {0.5, 0.5, 1.0};
        click(pixel_of(centre_a));
        QVERIFY(tool().empty());
        window->set_part_visible(0, true);
        click(pixel_of(centre_a));
        QVERIFY(tool().a().set);
        window->set_measuring(false);
    }

    // The text's units: a format without units, a STEP file in inches (mm first,
    // then the file's unit with the same relative precision), one in millimetres.
    void units()
    {
        oit_model model;
        std::memset(&model, 0, sizeof model);
        model.bounds_max[0] = 100.0f; // 100 across: 3 decimals
        MeasureUnits plain = MeasureUnits::of(model);
        QVERIFY(!plain.millimetres);
        QCOMPARE(plain.length(25.4), QString("25.400 units"));
        std::strcpy(model.unit_name, "inch");
        model.unit_to_mm = 25.4;
        MeasureUnits inch = MeasureUnits::of(model);
        QCOMPARE(inch.length(25.4), QString("25.400 mm (1.0000 in)"));
        QCOMPARE(inch.number(-0.0001), QString("0.000")); // no "-0.000"
        std::strcpy(model.unit_name, "millimetre");
        model.unit_to_mm = 1.0;
        QCOMPARE(MeasureUnits::of(model).length(2.5), QString("2.500 mm"));
        std::strcpy(model.unit_name, "");
        model.unit_to_mm = 0.0;
        model.tessellation_linear_mm = 0.01; // a STEP file naming no unit: read as mm
        QCOMPARE(MeasureUnits::of(model).length(2.5), QString("2.500 mm"));
    }

    // A STEP file (KiCad's, in millimetres): two points on the part, the line in mm.
    void step_file_says_millimetres()
    {
        QVERIFY2(load(MainWindow::source_root() + "/tests/data/kicad/R_0603_1608Metric.step"),
                 qPrintable(window->last_error()));
        QCOMPARE(QString(window->model()->unit_name), QString("millimetre"));
        front_view();
        window->set_measuring(true);
        const QPoint centre(view_size.width() / 2, view_size.height() / 2);
        click(centre);
        click(centre + QPoint(10, 0));
        QVERIFY2(tool().complete(), qPrintable(window->status_text()));
        const QString line = tool().text();
        QVERIFY2(line.startsWith("distance ") && line.contains(" mm from ") && !line.contains("units"),
                 qPrintable(line));
        // 10 pixels of a view framing the part's bounding sphere, in mm (the part is 1.6 mm long)
        QVERIFY2(tool().distance() > 0.05 && tool().distance() < 2.0, qPrintable(line));
        window->set_measuring(false);
    }
};

OIT_WINDOW_TEST_MAIN(MeasureTest, "oit-workbench-test-measure")
#include "test_measure.moc"
