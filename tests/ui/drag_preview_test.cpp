// A drag as a hand makes it (a mouse move every 16 ms for 3 s) is answered by a stream of
// preview frames, the last showing the object where the hand stopped; the previews and the
// first refinement passes leave the refined picture as it was away from the edit.
#include <QElapsedTimer>
#include <QTemporaryDir>
#include <QTest>

#include "denoise_worker.h"
#include "document.h"
#include "render_controller.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class DragPreviewTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void aThreeSecondDragShowsThirtyFramesAndTheLastShowsTheObjectWhereTheHandStopped();
    void previewsReplaceOnlyThePixelsTheEditCanChange();
    void theDenoiseKeyShowsDenoisedRefinedFrames();
    void aDenoisedPictureOfTheNewStateComesBeforeItsRefinementCatchesUp();
};

namespace {

/// Centre of the pixels an object covers (alpha above a half) in `alpha` within `window`
/// full-render pixels of `around`, in full-render pixels; false if it covers fewer than `least`.
bool coverage_centre(const Image& alpha, double scale, QPointF around, double window, double least,
                     QPointF& out) {
    double sx = 0, sy = 0, n = 0;
    for (int y = 0; y < alpha.height(); ++y)
        for (int x = 0; x < alpha.width(); ++x) {
            const QPointF p((x + 0.5) * scale, (y + 0.5) * scale);
            if (QLineF(p, around).length() > window || alpha[size_t(y) * alpha.width() + x].x <= 0.5f) continue;
            sx += p.x();
            sy += p.y();
            n += scale * scale;
        }
    if (n < least) return false;
    out = QPointF(sx / n * scale * scale, sy / n * scale * scale);
    return true;
}

}  // namespace

void DragPreviewTest::aThreeSecondDragShowsThirtyFramesAndTheLastShowsTheObjectWhereTheHandStopped() {
    QTemporaryDir dir;
    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery"), 1280, 720));
    w.resize(1400, 860);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY(w.openProject(test::write_small_sample(dir.path(), 100000, 4)));
    QVERIFY(test::wait_refined(w, 60000));

    std::vector<std::shared_ptr<const RenderFrame>> previews;
    bool dragging = false;
    connect(w.renderer(), &RenderController::frameReady, &w, [&](std::shared_ptr<const RenderFrame> f) {
        if (dragging && f->preview) previews.push_back(f);
    });
    // The clay ball, dragged 1.2 m to the left on the ground.
    const vec3 from = w.document()->project().objects[0].transform.translation;
    const vec3 to = from + vec3(-1.2f, 0, 0.3f);
    QPointF a, b;
    QVERIFY(w.viewport()->widgetPosition(from, a));
    QVERIFY(w.viewport()->widgetPosition(to, b));
    dragging = true;
    QTest::mousePress(w.viewport(), Qt::LeftButton, {}, a.toPoint());
    QCOMPARE(w.document()->selected(), 0);
    QElapsedTimer t;
    t.start();
    int moves = 0;
    while (t.elapsed() < 3000) {
        const double k = std::min(1.0, double(t.elapsed()) / 2900.0);
        QTest::mouseMove(w.viewport(), (a + (b - a) * k).toPoint());
        ++moves;
        QTest::qWait(16);
    }
    // The hand rests: the preview of the last move arrives (the button is still down).
    const uint64_t last = w.renderer()->generation();
    QVERIFY(QTest::qWaitFor([&] { return !previews.empty() && previews.back()->generation == last; }, 5000));
    const std::shared_ptr<const RenderFrame> final = previews.back();
    QTest::mouseRelease(w.viewport(), Qt::LeftButton, {}, b.toPoint());
    dragging = false;
    qInfo("%d mouse moves in %lld ms, %zu preview frames; preview %dx%d", moves, t.elapsed(), previews.size(),
          final->update.alpha.width(), final->update.alpha.height());
    const RenderController::Timings tm = w.renderer()->timings();
    qInfo("last drag frame: %.1f ms (stop %.1f, build %.1f, region %.1f, first pass %.1f), size level %d", tm.dragFrame,
          tm.cancel, tm.buildQuick, tm.region, tm.firstQuick, tm.dragLevel);
    const RenderStats& st = final->update.stats;
    qInfo("its pass: trace %.1f ms, maps %.1f, mark %.1f, shade %.1f, accumulate %.1f; %llu photons", st.trace_s * 1e3,
          st.maps_s * 1e3, st.mark_s * 1e3, st.shade_s * 1e3, st.accumulate_s * 1e3,
          static_cast<unsigned long long>(st.photons_emitted));
    QVERIFY2(previews.size() >= 30, qPrintable(QString("only %1 preview frames").arg(previews.size())));

    // The last preview shows the ball where the document has it now.
    const vec3 moved = w.document()->project().objects[0].transform.translation;
    QVERIFY(glm::length(moved - from) > 1.0f);
    const Camera cam = view_camera(w.document()->project(), 1024, 512, 1280, 720);
    vec2 expected;
    QVERIFY(cam.project(moved, expected));
    // Its disk on screen: the radius from the camera's focal length and the ball's distance.
    const float r = w.document()->project().objects[0].shape.radius;
    const double disk = cam.fy() * r / glm::length(moved - cam.position());
    const QPointF there(expected.x + 0.5, expected.y + 0.5);
    QPointF seen;
    QVERIFY2(coverage_centre(final->update.alpha, 1280.0 / final->update.alpha.width(), there, 1.5 * disk,
                             0.5 * M_PI * disk * disk, seen),
             "the last preview does not show the ball where it is");
    const double off = QLineF(seen, there).length();
    QVERIFY2(off < 0.25 * disk, qPrintable(QString("the ball shows %1 px from its place (radius %2 px)").arg(off).arg(disk)));
    // And the frames answered the moves as they came, not only at the end.
    int distinct = 0;
    for (size_t i = 1; i < previews.size(); ++i) distinct += previews[i]->generation != previews[i - 1]->generation;
    QVERIFY(distinct >= 29);
}

void DragPreviewTest::previewsReplaceOnlyThePixelsTheEditCanChange() {
    QTemporaryDir dir;
    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery"), 512, 256));
    w.resize(1200, 700);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY(w.openProject(test::write_small_sample(dir.path(), 30000, 12)));
    QVERIFY(test::wait_refined(w));
    const std::shared_ptr<const RenderFrame> refined = w.renderer()->lastFullFrame();
    QVERIFY(refined && !refined->composited());
    const QImage refinedShown = w.viewport()->shownImage();

    // What the viewer shows at each frame (connected after the window: the viewport has it).
    std::vector<std::shared_ptr<const RenderFrame>> frames;
    std::vector<QImage> shown;
    connect(w.renderer(), &RenderController::frameReady, &w, [&](std::shared_ptr<const RenderFrame> f) {
        frames.push_back(f);
        shown.push_back(w.viewport()->shownImage());
    });
    // Nudge the clay ball with a short drag.
    const vec3 from = w.document()->project().objects[0].transform.translation;
    QPointF a, b;
    QVERIFY(w.viewport()->widgetPosition(from, a));
    QVERIFY(w.viewport()->widgetPosition(from + vec3(0.25f, 0, 0), b));
    test::drag(w.viewport(), a, b, 5);
    QVERIFY(test::wait_refined(w));

    // Every preview and early refinement frame was laid over the refined picture: far from the
    // ball (the crate's side of the frame) its pixels are the refined ones to the bit, near it
    // they are the edit's.
    const Project& p = w.document()->project();
    const Camera cam = view_camera(p, 1024, 512, 512, 256);
    vec2 ball, crate;
    QVERIFY(cam.project(p.objects[0].transform.translation, ball));
    QVERIFY(cam.project(p.real[1].transform.translation + vec3(0, 0.35f, 0), crate));
    int composited = 0;
    for (size_t k = 0; k < frames.size(); ++k) {
        const auto& f = frames[k];
        // Every preview, the drag's frames among them, replaces only its region.
        if (f->preview) QVERIFY2(f->composited(), qPrintable(QString("preview %1 replaces the whole picture").arg(k)));
        if (!f->composited()) continue;
        ++composited;
        QCOMPARE(f->image().width(), 512);
        // The shown pixels outside the edit's region are the refined picture's, to the bit.
        QCOMPARE(shown[k].size(), refinedShown.size());
        int changed = 0;
        for (int y = 0; y < shown[k].height(); ++y)
            for (int x = 0; x < shown[k].width(); ++x)
                changed += !(*f->shown_from_edit)[size_t(y) * 512 + x] && shown[k].pixel(x, y) != refinedShown.pixel(x, y);
        QVERIFY2(changed == 0, qPrintable(QString("frame %1: %2 pixels outside the edit changed").arg(k).arg(changed)));
        const size_t far = size_t(std::lround(crate.y)) * 512 + size_t(std::lround(crate.x));
        QCOMPARE(f->image()[far], refined->image()[far]);
        const size_t near = size_t(std::lround(ball.y)) * 512 + size_t(std::lround(ball.x));
        QVERIFY(f->image()[near] != refined->image()[near]);
    }
    QVERIFY2(composited >= 2, qPrintable(QString("%1 composited frames").arg(composited)));
    // The last frame is the new state's own render, not a composite.
    QVERIFY(!frames.back()->composited());
}

void DragPreviewTest::theDenoiseKeyShowsDenoisedRefinedFrames() {
    QString why;
    if (!DenoiseWorker::available(&why)) QSKIP(qPrintable(why));
    QTemporaryDir dir;
    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery"), 512, 256));
    w.resize(1200, 700);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY(w.openProject(test::write_small_sample(dir.path(), 30000, 6)));
    QVERIFY(test::wait_refined(w));
    QVERIFY(!w.viewport()->showingDenoised());
    const QImage raw = w.viewport()->shownImage();

    // D with the focus in the viewport: the refined frame on screen is denoised and shown.
    w.viewport()->setFocus();
    QTest::keyClick(w.viewport(), Qt::Key_D);
    QVERIFY(w.action("denoise")->isChecked());
    QVERIFY(QTest::qWaitFor([&] { return w.viewport()->showingDenoised(); }, 30000));
    const QImage denoised = w.viewport()->shownImage();
    QCOMPARE(denoised.size(), raw.size());
    // Smoother where the shadows are, the same far from every change (the photo is never
    // denoised): count pixels that differ.
    int differ = 0;
    for (int y = 0; y < raw.height(); ++y)
        for (int x = 0; x < raw.width(); ++x) differ += raw.pixel(x, y) != denoised.pixel(x, y);
    QVERIFY2(differ > 100, qPrintable(QString("%1 pixels changed").arg(differ)));
    QVERIFY2(differ < raw.width() * raw.height() / 2, qPrintable(QString("%1 pixels changed").arg(differ)));

    // After an edit, the new state's refined frame is denoised in its turn.
    Project p = w.document()->project();
    p.objects[0].transform.translation.x += 0.2f;
    w.document()->edit("move", p);
    QVERIFY(test::wait_refined(w));
    QVERIFY(QTest::qWaitFor([&] { return w.viewport()->showingDenoised(); }, 30000));
    // And D again shows the raw render.
    QTest::keyClick(w.viewport(), Qt::Key_D);
    QVERIFY(!w.action("denoise")->isChecked());
    QVERIFY(!w.viewport()->showingDenoised());
}

void DragPreviewTest::aDenoisedPictureOfTheNewStateComesBeforeItsRefinementCatchesUp() {
    QString why;
    if (!DenoiseWorker::available(&why)) QSKIP(qPrintable(why));
    QTemporaryDir dir;
    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery"), 512, 256));
    QVERIFY(test::show_and_open(w, test::write_small_sample(dir.path(), 30000, 24)));
    w.viewport()->setFocus();
    QTest::keyClick(w.viewport(), Qt::Key_D);
    QVERIFY(w.action("denoise")->isChecked());
    QVERIFY(test::wait_refined(w, 90000));
    QVERIFY(QTest::qWaitFor([&] { return w.viewport()->showingDenoised() && w.viewport()->frame() &&
                                          w.viewport()->frame()->update.finished; }, 30000));
    const QImage before = w.viewport()->shownImage();

    // Nudge the clay ball with a drag; the hand rests and the refinement of the new state runs.
    const Project p0 = w.document()->project();
    const vec3 from = p0.objects[0].transform.translation;
    QPointF a, b;
    QVERIFY(w.viewport()->widgetPosition(from, a));
    QVERIFY(w.viewport()->widgetPosition(from + vec3(0.25f, 0, 0), b));
    test::drag(w.viewport(), a, b, 10);
    const uint64_t edit = w.renderer()->generation();
    QElapsedTimer t;
    t.start();
    // The first denoised picture of the new state comes while its frames are still laid over
    // the refined picture (before they have its 24 passes): its quick pass's, or a refinement
    // frame's if that came first.
    QVERIFY(QTest::qWaitFor([&] {
        const auto f = w.viewport()->frame();
        return f && f->generation == edit && w.viewport()->showingDenoised();
    }, 30000));
    const auto shown = w.viewport()->frame();
    qInfo("first denoised picture of the new state %lld ms after the drop, at its pass %d (quick pass: %d, "
          "composited: %d)",
          t.elapsed(), shown->update.stats.passes, int(shown->preview), int(shown->composited()));
    QVERIFY(shown->composited());
    const QImage after = w.viewport()->shownImage();
    QCOMPARE(after.size(), before.size());
    // Far from the ball (the crate) the picture is the denoised refined one to the bit; at the
    // ball's new place it is not.
    const Camera cam = view_camera(p0, 1024, 512, 512, 256);
    vec2 crate, ball;
    QVERIFY(cam.project(p0.real[1].transform.translation + vec3(0, 0.35f, 0), crate));
    QVERIFY(cam.project(w.document()->project().objects[0].transform.translation + vec3(0.1f, 0, 0), ball));
    const QPoint far(int(crate.x), int(crate.y)), near(int(ball.x), int(ball.y));
    QCOMPARE(after.pixel(far), before.pixel(far));
    QVERIFY(after.pixel(near) != before.pixel(near));
}

QTEST_MAIN(DragPreviewTest)
#include "drag_preview_test.moc"
