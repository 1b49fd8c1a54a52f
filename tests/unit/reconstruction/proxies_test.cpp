#include <gtest/gtest.h>

#include <cmath>

#include "base/error.h"
#include "geometry/mesh.h"
#include "reconstruction/proxies.h"

using namespace dp;

namespace {

Camera test_camera() {
    return Camera::look_at(640, 480, vec3(0.4f, 1.6f, 5.0f), vec3(0, 0, 0), vec3(0, 1, 0), 50.0f);
}

/// World corners of a box proxy (its mesh's positions, deduplicated by the caller's tolerance).
std::vector<vec3> corners_of(const RealProxy& proxy) {
    TriangleMesh m = proxy.shape.kind == Shape::Kind::Box ? make_box(proxy.shape.size)
                                                          : make_plane(proxy.shape.size.x, proxy.shape.size.z);
    m.transform(proxy.transform.matrix());
    return m.positions;
}

/// Largest distance from a corner of `want` to the nearest corner of `got`, both ways.
float corner_distance(const std::vector<vec3>& got, const std::vector<vec3>& want) {
    auto one_way = [](const std::vector<vec3>& a, const std::vector<vec3>& b) {
        float worst = 0;
        for (const vec3& p : a) {
            float best = INFINITY;
            for (const vec3& q : b) best = std::min(best, glm::length(p - q));
            worst = std::max(worst, best);
        }
        return worst;
    };
    return std::max(one_way(got, want), one_way(want, got));
}

vec2 click(const Camera& cam, const vec3& p, bool round_to_pixel) {
    vec2 px;
    EXPECT_TRUE(cam.project(p, px));
    return round_to_pixel ? glm::round(px) : px;
}

/// A box standing on the ground, turned 30 degrees, in front of the camera.
RealProxy true_box() {
    RealProxy b;
    b.shape.kind = Shape::Kind::Box;
    b.shape.size = vec3(1.2f, 0.8f, 0.6f);
    b.transform.translation = vec3(0.5f, 0.4f, -0.3f);
    b.transform.rotation_deg = vec3(0, 30, 0);
    return b;
}

/// The box's four bottom corners in order around it.
std::vector<vec3> bottom_corners(const RealProxy& b) {
    glm::mat4 m = b.transform.matrix();
    vec3 h = 0.5f * b.shape.size;
    std::vector<vec3> out;
    for (vec3 c : {vec3(-h.x, -h.y, h.z), vec3(h.x, -h.y, h.z), vec3(h.x, -h.y, -h.z), vec3(-h.x, -h.y, -h.z)})
        out.push_back(vec3(m * glm::vec4(c, 1)));
    return out;
}

}  // namespace

TEST(GroundPoint, AProjectedGroundPointComesBackToItself) {
    Camera cam = test_camera();
    for (vec3 p : {vec3(0, 0, 0), vec3(-1.5f, 0, 1.2f), vec3(2, 0, -6)}) {
        vec3 back = point_on_plane_y(cam, click(cam, p, false), 0);
        EXPECT_LT(glm::length(back - p), 1e-3f) << p.x << " " << p.z;
    }
    // A point at a height comes back from the plane at that height.
    vec3 raised(0.3f, 0.9f, -0.4f);
    EXPECT_LT(glm::length(point_on_plane_y(cam, click(cam, raised, false), 0.9f) - raised), 1e-3f);
}

TEST(GroundPoint, APointAboveTheHorizonIsRejectedWithAClearMessage) {
    Camera cam = test_camera();
    try {
        point_on_plane_y(cam, vec2(320, 5), 0, "points[0]");
        FAIL() << "no error for a point above the horizon";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("above the horizon"), std::string::npos) << e.what();
        EXPECT_EQ(e.field(), "points[0]");
    }
}

TEST(BoxProxy, FourClickedCornersGiveTheTrueBox) {
    Camera cam = test_camera();
    RealProxy truth = true_box();
    std::vector<vec2> clicks;
    for (const vec3& c : bottom_corners(truth)) clicks.push_back(click(cam, c, false));
    ProxyFit fit = box_proxy(cam, clicks, truth.shape.size.y);
    EXPECT_LT(corner_distance(corners_of(fit.proxy), corners_of(truth)), 1e-3f);
    EXPECT_LT(fit.rms_error_px, 0.05f);
}

TEST(BoxProxy, ClicksRoundedToWholePixelsStayWithinTwoCentimetres) {
    // About 5 m away, a pixel of this 640x480 camera spans 1 to 3 cm of ground.
    Camera cam = test_camera();
    RealProxy truth = true_box();
    std::vector<vec2> clicks;
    for (const vec3& c : bottom_corners(truth)) clicks.push_back(click(cam, c, true));
    ProxyFit fit = box_proxy(cam, clicks, truth.shape.size.y);
    float d = corner_distance(corners_of(fit.proxy), corners_of(truth));
    RecordProperty("corner_error_m", std::to_string(d));
    EXPECT_LT(d, 0.02f);
    EXPECT_LT(fit.rms_error_px, 1.0f);
}

TEST(BoxProxy, ThreeCornersInEitherOrderGiveTheSameBox) {
    Camera cam = test_camera();
    RealProxy truth = true_box();
    std::vector<vec3> c = bottom_corners(truth);
    std::vector<vec2> ccw = {click(cam, c[0], false), click(cam, c[1], false), click(cam, c[2], false)};
    std::vector<vec2> cw = {ccw[2], ccw[1], ccw[0]};
    for (const auto& clicks : {ccw, cw}) {
        ProxyFit fit = box_proxy(cam, clicks, truth.shape.size.y);
        EXPECT_LT(corner_distance(corners_of(fit.proxy), corners_of(truth)), 1e-3f);
    }
}

TEST(WallProxy, TwoPointsAtItsFootGiveAWallBehindTheClickedLine) {
    Camera cam = test_camera();
    RealProxy truth;
    truth.shape.kind = Shape::Kind::Box;
    truth.shape.size = vec3(3.0f, 2.2f, 0.2f);
    truth.transform.translation = vec3(-0.5f, 1.1f, -2.0f);
    truth.transform.rotation_deg = vec3(0, -15, 0);
    // The front face's bottom edge (the side facing the camera, +Z before the turn).
    glm::mat4 m = truth.transform.matrix();
    vec3 a = vec3(m * glm::vec4(-1.5f, -1.1f, 0.1f, 1)), b = vec3(m * glm::vec4(1.5f, -1.1f, 0.1f, 1));
    ProxyFit fit = wall_proxy(cam, click(cam, a, false), click(cam, b, false), 2.2f, 0.2f);
    EXPECT_LT(corner_distance(corners_of(fit.proxy), corners_of(truth)), 1e-3f);
    // Clicking the ends the other way round gives the same wall.
    ProxyFit swapped = wall_proxy(cam, click(cam, b, false), click(cam, a, false), 2.2f, 0.2f);
    EXPECT_LT(corner_distance(corners_of(swapped.proxy), corners_of(truth)), 1e-3f);
}

TEST(GroundProxy, CoversEveryGroundPointTheCameraSeesUpToTheFarLimit) {
    for (Camera cam : {test_camera(),
                       Camera::look_at(320, 240, vec3(2, 3, 2), vec3(0, 0, 0), vec3(0, 1, 0), 70.0f),
                       Camera::look_at(320, 240, vec3(0, 1.5f, 0), vec3(0, 1.4f, -10), vec3(0, 1, 0), 60.0f)}) {
        const float far = 20.0f * cam.position().y;
        ProxyFit fit = ground_proxy(cam);
        ASSERT_EQ(fit.proxy.shape.kind, Shape::Kind::Plane);
        glm::mat4 to_local = glm::inverse(fit.proxy.transform.matrix());
        vec3 half = 0.5f * fit.proxy.shape.size;
        int seen = 0;
        for (int y = 0; y < cam.height(); y += 8)
            for (int x = 0; x < cam.width(); x += 8) {
                Ray r = cam.generate_ray(float(x), float(y));
                if (r.dir.y >= 0) continue;
                vec3 p = r.org + (-r.org.y / r.dir.y) * r.dir;
                if (std::hypot(p.x - r.org.x, p.z - r.org.z) > 0.99f * far) continue;
                vec3 l = vec3(to_local * glm::vec4(p, 1));
                ++seen;
                ASSERT_LE(std::abs(l.x), half.x) << x << "," << y;
                ASSERT_LE(std::abs(l.z), half.z) << x << "," << y;
            }
        EXPECT_GT(seen, 100);
        // And it does not reach much beyond the far limit.
        for (const vec3& c : fit.footprint)
            EXPECT_LT(std::hypot(c.x - cam.position().x, c.z - cam.position().z), 1.6f * far);
    }
}

TEST(GroundProxy, ACameraThatSeesNoGroundIsAnError) {
    Camera up = Camera::look_at(64, 48, vec3(0, 1, 0), vec3(0, 10, -1), vec3(0, 1, 0), 40.0f);
    EXPECT_THROW(ground_proxy(up), InputError);
    Camera below = Camera::look_at(64, 48, vec3(0, -1, 5), vec3(0, -1, 0), vec3(0, 1, 0), 40.0f);
    EXPECT_THROW(ground_proxy(below), InputError);
}

TEST(BoxProxy, DegenerateFootprintsAreRejectedWithAClearMessage) {
    Camera cam = test_camera();
    auto message = [&](const std::vector<vec2>& clicks, float height) -> std::string {
        try {
            box_proxy(cam, clicks, height);
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    };
    std::vector<vec3> c = bottom_corners(true_box());
    std::vector<vec2> good;
    for (const vec3& p : c) good.push_back(click(cam, p, false));
    EXPECT_NE(message({good[0], good[1]}, 1).find("3 or 4"), std::string::npos);
    vec2 mid = 0.5f * (good[0] + good[1]);
    EXPECT_NE(message({good[0], mid, good[1]}, 1).find("collinear"), std::string::npos);
    EXPECT_NE(message({good[0], good[2], good[1], good[3]}, 1).find("in order"), std::string::npos);
    EXPECT_NE(message({good[0], good[0], good[1], good[2]}, 1).find("same ground point"), std::string::npos);
    EXPECT_NE(message(good, 0).find("height"), std::string::npos);
    EXPECT_NE(message({good[0], vec2(320, 2), good[2]}, 1).find("horizon"), std::string::npos);
}
