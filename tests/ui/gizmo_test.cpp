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
    void aLightIsPickedByItsGlyphOrItsFaceBeforeTheObjectBehind();
    void aLightMovesWithoutSnappingAndTiltsWhenRotated();

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

void GizmoTest::aLightIsPickedByItsGlyphOrItsFaceBeforeTheObjectBehind() {
    Project p = project_;
    VirtualLight bulb;
    bulb.transform.translation = vec3(-2, 1.5f, -1);
    VirtualLight panel;
    panel.kind = VirtualLight::Kind::Rect;
    panel.size = vec2(1.0f, 0.6f);
    panel.transform.translation = vec3(1, 1.2f, 0);
    panel.transform.rotation_deg = vec3(-90, 0, 0);  // facing the camera (+z)
    p.lights = {bulb, panel};
    const vec2 b = pixel(bulb.transform.translation);
    QCOMPARE(pick_light(p, camera_, b.x + 6, b.y - 6, 12), 0);
    QCOMPARE(pick_light(p, camera_, b.x + 20, b.y, 12), -1);
    // Inside the panel's face, far from its centre; off its edge, nothing.
    const vec2 inside = pixel(panel.transform.translation + vec3(0.4f, 0.2f, 0));
    QCOMPARE(pick_light(p, camera_, inside.x, inside.y, 2), 1);
    const vec2 off = pixel(panel.transform.translation + vec3(0.6f, 0, 0));
    QCOMPARE(pick_light(p, camera_, off.x, off.y, 2), -1);
}

void GizmoTest::aLightMovesWithoutSnappingAndTiltsWhenRotated() {
    Transform start;
    start.translation = vec3(1.0f, 1.5f, -0.9f);
    // Dragged over the crate from high above it: a lamp keeps its height (an object would rise
    // onto the crate) and the grabbed point stays under the cursor.
    Transform high = start;
    high.translation.y = 3.5f;
    const vec3 over_crate(1.75f, 3.5f, -0.9f);
    Transform t = light_drag_transform(GizmoMode::Translate, high, camera_, pixel(high.translation),
                                       pixel(over_crate), -1);
    QVERIFY(glm::length(t.translation - over_crate) < 1e-3f);
    // At the eye's height (1.5 m) its horizontal plane is edge on: it slides across the view,
    // under the cursor, at its height.
    const vec2 aim = pixel(start.translation) + vec2(80, 30);
    t = light_drag_transform(GizmoMode::Translate, start, camera_, pixel(start.translation), aim, -1);
    QCOMPARE(t.translation.y, start.translation.y);
    const vec2 now = pixel(t.translation);
    qInfo("slid to %.2f %.2f %.2f, on screen %.1f %.1f", t.translation.x, t.translation.y, t.translation.z, now.x, now.y);
    QVERIFY(std::abs(now.x - aim.x) < 3 && std::abs(now.y - pixel(start.translation).y) < 0.5f);
    // Rotated 60 pixels right: it tilts 30 degrees, its beam swinging right on screen.
    const vec3 p = start.translation;
    t = light_drag_transform(GizmoMode::Rotate, start, camera_, vec2(300, 200), vec2(360, 200), -1);
    const vec3 axis = glm::mat3(t.matrix()) * vec3(0, -1, 0);
    QVERIFY(std::abs(axis.y + std::sqrt(0.75f)) < 1e-4f);
    QVERIFY(pixel(p + axis).x > pixel(p + vec3(0, -1, 0)).x + 20);
    // 60 pixels down: it tilts 30 degrees towards the camera.
    t = light_drag_transform(GizmoMode::Rotate, start, camera_, vec2(300, 200), vec2(300, 260), -1);
    const vec3 down = glm::mat3(t.matrix()) * vec3(0, -1, 0);
    vec3 towards = camera_.position() - p;
    towards = glm::normalize(vec3(towards.x, 0, towards.z));
    QVERIFY(std::abs(glm::dot(down, towards) - 0.5f) < 1e-4f && std::abs(down.y + std::sqrt(0.75f)) < 1e-4f);
}

QTEST_APPLESS_MAIN(GizmoTest)
#include "gizmo_test.moc"
