// test_preview.cpp: preview-then-refine in the render view (render_worker.h has
// the rules): a stand-in renders while the camera moves and the chosen
// algorithm's full frame follows at rest; the status names both; nothing is
// rendered when nothing changed, and no coarse frame when only the algorithm
// did. A RenderView on its own (no window) over a three-square model at
// 160x120, every full frame counted as slow (set_slow_frame_ms(0)). Frames are
// counted, never timed (the speed goals are bat/interaction_latency.py's).
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

class PreviewTest : public QObject {
    Q_OBJECT
    std::unique_ptr<SettingsModel> settings_;
    std::unique_ptr<RenderView> view_;

    // A view showing the full frame of algorithm, every full frame "slow".
    void open(const std::string &algorithm, const std::string &preview = "auto")
    {
        view_.reset();
        settings_.reset(new SettingsModel);
        settings_->render_settings().algorithm = algorithm;
        settings_->render_settings().preview_algorithm = preview;
        // anti-aliasing off: these count the preview rule's jobs; Auto's still
        // frame at 4 samples is one more (tests/app/test_antialiasing.cpp)
        settings_->render_settings().samples = 1;
        view_.reset(new RenderView(*settings_));
        QVERIFY2(view_->gl_ready(), view_->gl_error().c_str());
        view_->setFixedSize(160, 120);
        view_->show();
        view_->set_slow_frame_ms(0.0);
        auto model = three_squares();
        QVERIFY(model);
        settings_->render_settings().reset_parts(*model);
        settings_->camera().frame(*model, 160, 120);
        view_->set_model(model);
        QVERIFY(QTest::qWaitFor([this] { return view_->settled(); }, 60000));
        QCOMPARE(view_->last_result()->algorithm, algorithm);
    }

    // A drag of a few moves: the frames it shows, then those after the release.
    void drag(std::vector<FrameResultPointer> &during, QStringList &statuses)
    {
        QSignalSpy status(view_.get(), &RenderView::status_changed);
        QMetaObject::Connection shown = connect(view_.get(), &RenderView::coarse_frame_rendered, this,
                                                [&] { during.push_back(view_->last_result()); });
        QPoint at(60, 60);
        mouse(view_.get(), QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::LeftButton);
        for (int i = 0; i < 6; ++i) {
            at += QPoint(5, 2);
            mouse(view_.get(), QEvent::MouseMove, at, Qt::NoButton, Qt::LeftButton);
            QTest::qWait(20);
        }
        // the button stays down: previews only, however long the previews take
        QVERIFY(QTest::qWaitFor([&] { return !during.empty() && !view_->rendering(); }, 60000));
        QTest::qWait(2 * RenderView::kRestMs);
        QVERIFY(!view_->settled());
        statuses << view_->frame_status();
        mouse(view_.get(), QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton);
        disconnect(shown);
        QVERIFY(QTest::qWaitFor([this] { return view_->settled(); }, 60000));
        for (const QList<QVariant> &args : status)
            statuses << args.at(0).toString();
    }

private slots:
    void cleanup()
    {
        view_.reset();
        settings_.reset();
    }

    // dp, previews by the stand-in ll (auto): ll frames at a coarse scale while
    // the button is down, dp's full frame once the input rests; the status
    // names what is shown and what renders
    void a_stand_in_previews_and_the_chosen_algorithm_refines()
    {
        open("dp");
        QCOMPARE(view_->preview_algorithm(), std::string("ll"));
        std::vector<FrameResultPointer> during;
        QStringList statuses;
        drag(during, statuses);
        if (QTest::currentTestFailed())
            return;
        for (const FrameResultPointer &r : during) {
            QCOMPARE(r->algorithm, std::string("ll"));
            QVERIFY(r->coarse_scale > 1);
        }
        QCOMPARE(view_->last_result()->algorithm, std::string("dp"));
        QCOMPARE(view_->last_result()->coarse_scale, 1);
        QVERIFY2(statuses.first().startsWith("dp refines when the input rests, showing ll preview (1/"),
                 qPrintable(statuses.join(" | ")));
        QVERIFY2(statuses.filter("dp refining…, showing ll preview (1/").size() >= 1, qPrintable(statuses.join(" | ")));
        QCOMPARE(view_->frame_status(), QString()); // the full frame is up: the stats say it
    }

    // "same as chosen": the chosen algorithm's own coarse frames, as before stand-ins
    void same_as_chosen_previews_with_the_chosen_algorithm()
    {
        open("dp", "same");
        std::vector<FrameResultPointer> during;
        QStringList statuses;
        drag(during, statuses);
        if (QTest::currentTestFailed())
            return;
        for (const FrameResultPointer &r : during) {
            QCOMPARE(r->algorithm, std::string("dp"));
            QVERIFY(r->coarse_scale > 1);
        }
        QVERIFY2(statuses.first().contains("showing dp coarse frame (1/"), qPrintable(statuses.join(" | ")));
        QCOMPARE(view_->last_result()->algorithm, std::string("dp"));
    }

    // nothing changed: no job; only the algorithm changed: one full frame, no
    // coarse one, and the status names the new algorithm and what is shown
    void no_coarse_frame_when_the_view_did_not_change()
    {
        open("ll");
        int jobs = view_->jobs_submitted();
        view_->request_frame(true); // as any settings edit that changed nothing
        QCOMPARE(view_->jobs_submitted(), jobs);
        QVERIFY(view_->settled());

        QSignalSpy coarse(view_.get(), &RenderView::coarse_frame_rendered);
        QSignalSpy status(view_.get(), &RenderView::status_changed);
        settings_->render_settings().algorithm = "dp";
        view_->request_frame(true); // as the algorithm combo does
        QCOMPARE(view_->jobs_submitted(), jobs + 1);
        QVERIFY(status.count() >= 1);
        QCOMPARE(status.first().at(0).toString(), QString("dp rendering…, showing ll (the previous algorithm)"));
        QVERIFY(QTest::qWaitFor([this] { return view_->settled(); }, 60000));
        QCOMPARE(coarse.count(), 0);
        QCOMPARE(view_->jobs_submitted(), jobs + 1);
        QCOMPARE(view_->last_result()->algorithm, std::string("dp"));

        // a change of view (the camera) does preview first
        settings_->camera().zoom(1.0f);
        view_->request_frame(true);
        QVERIFY(QTest::qWaitFor([this] { return view_->settled(); }, 60000));
        QCOMPARE(coarse.count(), 1);
        QCOMPARE(view_->jobs_submitted(), jobs + 3);
    }
};

QTEST_MAIN(PreviewTest)
#include "test_preview.moc"
