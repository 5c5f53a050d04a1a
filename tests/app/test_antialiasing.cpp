// test_antialiasing.cpp: anti-aliasing in the workbench (issue 29; render_worker.h
// has the rule). Auto (the default): full frames at 1 sample while the view
// changes, the same frame again at 4 samples once it is still; Off: 1 sample
// and nothing more; a chosen count renders every full frame at it, previews
// at 1; exports always anti-alias (at least 4, or the chosen count) and the
// command of an export says --samples. A RenderView on its own over a
// three-square model at 160x120 (as test_preview.cpp). Frames are counted,
// never timed.
#include <QApplication>
#include <QMouseEvent>
#include <QSignalSpy>
#include <QtTest/QtTest>

#include <memory>

#include "render_view_test.h"
#include "render_view.h"
#include "settings_model.h"

using render_view_test::mouse;
using render_view_test::three_squares;

class AntialiasingTest : public QObject {
    Q_OBJECT
    std::unique_ptr<SettingsModel> settings_;
    std::unique_ptr<RenderView> view_;
    std::vector<int> full_samples_; // the samples of every full frame shown, in order

    void open(int samples)
    {
        view_.reset();
        full_samples_.clear();
        settings_.reset(new SettingsModel);
        settings_->render_settings().algorithm = "ll";
        settings_->render_settings().samples = samples;
        view_.reset(new RenderView(*settings_));
        QVERIFY2(view_->gl_ready(), view_->gl_error().c_str());
        connect(view_.get(), &RenderView::frame_rendered, this,
                [this] { full_samples_.push_back(view_->last_result()->samples); });
        view_->setFixedSize(160, 120);
        view_->show();
        auto model = three_squares();
        QVERIFY(model);
        settings_->render_settings().reset_parts(*model);
        settings_->camera().frame(*model, 160, 120);
        view_->set_model(model);
        QVERIFY(QTest::qWaitFor([this] { return view_->settled(); }, 60000));
    }

    QString shown() const
    {
        QStringList out;
        for (int n : full_samples_)
            out << QString::number(n);
        return out.join(", ");
    }

private slots:
    void cleanup()
    {
        view_.reset();
        settings_.reset();
    }

    // Auto: the first full frame at 1 sample, then the still view at 4; a drag
    // renders at 1 sample, and once released and still, at 4 again
    void auto_renders_again_at_4_samples_once_still()
    {
        open(0);
        QVERIFY2(full_samples_.size() == 2 && full_samples_[0] == 1 && full_samples_[1] == 4, qPrintable(shown()));
        QCOMPARE(view_->last_result()->samples, 4);
        QImage still = view_->last_result()->image;
        full_samples_.clear();
        QSignalSpy coarse(view_.get(), &RenderView::coarse_frame_rendered);
        std::vector<int> during;
        connect(view_.get(), &RenderView::coarse_frame_rendered, this,
                [this, &during] { during.push_back(view_->last_result()->samples); });
        QPoint at(60, 60);
        mouse(view_.get(), QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::LeftButton);
        for (int i = 0; i < 4; ++i) {
            at += QPoint(6, 3);
            mouse(view_.get(), QEvent::MouseMove, at, Qt::NoButton, Qt::LeftButton);
            QTest::qWait(30);
            // while the button is down, never a frame at 4 samples
            for (int n : full_samples_)
                QCOMPARE(n, 1);
        }
        mouse(view_.get(), QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton);
        QVERIFY(QTest::qWaitFor([this] { return view_->settled(); }, 60000));
        for (int n : during)
            QCOMPARE(n, 1);
        QVERIFY2(!full_samples_.empty() && full_samples_.back() == 4, qPrintable(shown()));
        for (size_t i = 0; i + 1 < full_samples_.size(); ++i)
            QVERIFY2(full_samples_[i] == 1, qPrintable(shown()));
        QVERIFY(view_->last_result()->image != still); // the camera turned
    }

    // Off: one frame at 1 sample, no second; a chosen count: every full frame at it
    void off_and_a_chosen_count()
    {
        open(1);
        QVERIFY2(full_samples_.size() == 1 && full_samples_[0] == 1, qPrintable(shown()));
        int jobs = view_->jobs_submitted();
        QTest::qWait(200);
        QCOMPARE(view_->jobs_submitted(), jobs);
        open(8);
        QVERIFY2(full_samples_.size() == 1 && full_samples_[0] == 8, qPrintable(shown()));
    }

    // exports always anti-alias: Auto and Off at 4, a chosen 16 at 16; the
    // frame an export returns (whose command Copy as command writes) says so
    void export_uses_samples()
    {
        struct Case {
            int setting, expected;
        } cases[] = {{0, 4}, {1, 4}, {16, 16}};
        for (const Case &c : cases) {
            open(c.setting);
            QImage image;
            oit_frame_settings frame{};
            std::string error;
            QVERIFY2(view_->render_offscreen(64, 48, image, frame, error, false), error.c_str());
            QCOMPARE(image.size(), QSize(64, 48));
            QCOMPARE(frame.samples, c.expected);
            std::string command = render_command("oit", "m.obj", settings_->render_settings(), frame, "x.png");
            QVERIFY2(command.find(" --samples " + std::to_string(c.expected)) != std::string::npos, command.c_str());
        }
    }
};

QTEST_MAIN(AntialiasingTest)
#include "test_antialiasing.moc"
