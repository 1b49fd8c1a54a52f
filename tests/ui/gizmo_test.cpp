// The viewport gizmo's picking and dragging math on the sample project's camera.
#include <QTest>

#include "gizmo.h"
#include "scene/project_io.h"

using namespace dp;
using namespace dp::ui;

class GizmoTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void initTestCase();
    void clickPicksTheNearestObjectAndNothingOffThem();
    void translateKeepsTheGrabbedPointUnderTheCursorAndSnapsOntoTheCrate();
    void rotateTurnsHalfADegreePerPixelAboutTheVertical();
    void scaleFollowsTheCursorsDistanceFromTheCentre();

private:
    vec2 pixel(const vec3& world) const {
        vec2 px;
        if (!camera_.project(world, px)) qFatal("point behind the camera");
        return px;
    }
    Project project_;
    Camera camera_;
};

void GizmoTest::initTestCase() {
    project_ = load_project(std::string(DP_SOURCE_DIR) + "/resources/sample/sample.json");
    camera_ = view_camera(project_, 1024, 512, 1024, 512);
}

void GizmoTest::clickPicksTheNearestObjectAndNothingOffThem() {
    for (int i = 0; i < int(project_.objects.size()); ++i) {
        const vec2 c = pixel(project_.objects[size_t(i)].transform.translation);
        QCOMPARE(pick_object(project_, camera_, c.x, c.y), i);
    }
    QCOMPARE(pick_object(project_, camera_, 5, 5), -1);  // the sky
    // A hidden object cannot be picked: the ray goes on to nothing.
    Project hidden = project_;
    hidden.objects[0].visible = false;
    const vec2 c = pixel(hidden.objects[0].transform.translation);
    QCOMPARE(pick_object(hidden, camera_, c.x, c.y), -1);
}

void GizmoTest::translateKeepsTheGrabbedPointUnderTheCursorAndSnapsOntoTheCrate() {
    const Transform start = project_.objects[0].transform;  // the clay ball, on the ground
    const vec3 grab = start.translation + vec3(0.1f, 0, 0.05f);
    const vec3 free_spot = grab + vec3(0.4f, 0, 0.6f);
    Transform t = drag_transform(GizmoMode::Translate, start, camera_, pixel(grab),
                                 pixel(free_spot), &project_);
    QVERIFY(glm::length(t.translation - (start.translation + vec3(0.4f, 0, 0.6f))) < 1e-3f);
    QVERIFY(t.rotation_deg == start.rotation_deg);

    // Onto the crate (0.7 m box centred at x 1.75, z -0.9): it rises by the crate's height.
    const vec3 over_crate(1.75f, start.translation.y, -0.9f);
    t = drag_transform(GizmoMode::Translate, start, camera_, pixel(start.translation),
                       pixel(over_crate), &project_);
    QVERIFY(std::abs(t.translation.x - 1.75f) < 1e-3f);
    QVERIFY(std::abs(t.translation.y - (start.translation.y + 0.7f)) < 1e-4f);
    // Without snapping it stays at its height.
    t = drag_transform(GizmoMode::Translate, start, camera_, pixel(start.translation),
                       pixel(over_crate));
    QCOMPARE(t.translation.y, start.translation.y);
}

void GizmoTest::rotateTurnsHalfADegreePerPixelAboutTheVertical() {
    const Transform start = project_.objects[1].transform;
    const Transform t = drag_transform(GizmoMode::Rotate, start, camera_, vec2(300, 200),
                                       vec2(380, 260));
    QCOMPARE(t.rotation_deg.y, start.rotation_deg.y + 40.0f);
    QVERIFY(t.translation == start.translation);
}

void GizmoTest::scaleFollowsTheCursorsDistanceFromTheCentre() {
    const Transform start = project_.objects[2].transform;
    const vec2 c = pixel(start.translation);
    const Transform t = drag_transform(GizmoMode::Scale, start, camera_, c + vec2(20, 0),
                                       c + vec2(0, 50));
    QVERIFY(glm::length(t.scale - start.scale * 2.5f) < 1e-4f);
}

QTEST_APPLESS_MAIN(GizmoTest)
#include "gizmo_test.moc"
