// The Scene View dock: the sample seen from the front, its ball dragged up with the events a
// hand makes; the ball rises by what the drag spanned, one undo step, and the main viewport
// shows it higher (the floor under it where it was).
#include <QDockWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>

#include "document.h"
#include "scene_view.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class SceneViewTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void aBallDraggedUpInTheFrontViewRisesAndTheViewportShowsIt();
};

void SceneViewTest::aBallDraggedUpInTheFrontViewRisesAndTheViewportShowsIt() {
    QTemporaryDir dir;
    RecordingReporter reporter(false);
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    QVERIFY(test::show_and_open(w, test::write_small_sample(dir.path())));
    QVERIFY(test::wait_refined(w));
    Document* doc = w.document();
    QVERIFY(!doc->project().objects.empty());
    auto* view = w.findChild<SceneView*>("sceneView");
    QVERIFY(view);
    w.findChild<QDockWidget*>("sceneViewDock")->raise();
    QVERIFY(QTest::qWaitForWindowExposed(view));
    QTest::mouseClick(w.findChild<QToolButton*>("sceneViewFront"), Qt::LeftButton);
    QCOMPARE(view->view(), SceneView::View::Front);

    // Top view: the photo's camera and the ball both in sight.
    QTest::mouseClick(w.findChild<QToolButton*>("sceneViewTop"), Qt::LeftButton);
    const Camera photo = w.viewport()->viewCamera();
    QPointF eye, ball;
    QVERIFY(view->widgetPosition(photo.position(), eye));
    QVERIFY(view->rect().contains(eye.toPoint()));
    const VirtualObject before = doc->project().objects[0];
    QVERIFY(view->widgetPosition(before.transform.translation, ball));
    QVERIFY(view->rect().contains(ball.toPoint()));

    // Front view: drag the ball 40 pixels up, 60 mouse moves a second.
    QTest::mouseClick(w.findChild<QToolButton*>("sceneViewFront"), Qt::LeftButton);
    QVERIFY(view->widgetPosition(before.transform.translation, ball));
    const Camera front = view->camera();
    const float depth = glm::dot(before.transform.translation - front.position(), front.forward());
    const float metres = 40.0f * depth / front.fy();
    const int steps = doc->undoStack()->count();
    test::drag(view, ball, ball - QPointF(0, 40), 20);
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("\n")));
    const VirtualObject after = doc->project().objects[0];
    qInfo("ball up %.4f m for 40 px (%.4f expected)", after.transform.translation.y - before.transform.translation.y, metres);
    QVERIFY(std::abs(after.transform.translation.y - before.transform.translation.y - metres) < 0.03f * metres);
    QVERIFY(std::abs(after.transform.translation.x - before.transform.translation.x) < 1e-4f);
    QVERIFY(std::abs(after.transform.translation.z - before.transform.translation.z) < 1e-4f);
    QCOMPARE(doc->undoStack()->count(), steps + 1);

    // The viewport, once refined, shows the ball higher: where its lowest point was, the photo.
    QVERIFY(test::wait_refined(w));
    Viewport* v = w.viewport();
    QPointF low;
    const vec3 bottom = before.transform.translation - vec3(0, 0.9f * before.shape.radius, 0);
    vec2 px;
    QVERIFY(v->viewCamera().project(bottom, px));
    const QImage shown = v->shownImage();
    const QRgb there = shown.pixel(int(px.x), int(px.y));
    w.action("undo")->trigger();
    QVERIFY(doc->project().objects[0] == before);
    QVERIFY(test::wait_refined(w));
    const QRgb was = v->shownImage().pixel(int(px.x), int(px.y));
    QVERIFY2(there != was, "the ball's old bottom looks the same after it rose");

    // The toolbar's Rotate: a drag across the top view turns the ball about the vertical.
    w.action("gizmoRotate")->trigger();
    QTest::mouseClick(w.findChild<QToolButton*>("sceneViewTop"), Qt::LeftButton);
    QVERIFY(view->widgetPosition(before.transform.translation, ball));
    test::drag(view, ball + QPointF(0, 0), ball + QPointF(60, 0), 20);
    const VirtualObject turned = doc->project().objects[0];
    qInfo("turned %.1f deg", turned.transform.rotation_deg.y);
    QVERIFY(std::abs(turned.transform.rotation_deg.y - before.transform.rotation_deg.y) > 10);
    QVERIFY(glm::length(turned.transform.translation - before.transform.translation) < 1e-5f);
    doc->undoStack()->setClean();
}

QTEST_MAIN(SceneViewTest)
#include "scene_view_test.moc"
