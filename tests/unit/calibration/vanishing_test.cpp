// Vanishing points from exact line segments of a known camera, including vertical lines.
#include <gtest/gtest.h>

#include "calibration/vanishing.h"
#include "synthetic_board.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr int kW = 1000, kH = 750;

/// Looks down at about 28 degrees with the principal point off centre, so that the three
/// vanishing points are finite and the principal point must come from them.
CameraSpec shifted_camera() {
    CameraSpec c = camera_at({1.5, 1.6, 2.5}, {0.3, 0, -0.2}, kW, kH, 800);
    c.cx += 23;
    c.cy -= 17;
    return c;
}

LineSegment segment(const Camera& cam, glm::dvec3 a, glm::dvec3 b) {
    vec2 pa, pb;
    EXPECT_TRUE(cam.project(vec3(a), pa) && cam.project(vec3(b), pb));
    return {glm::dvec2(pa), glm::dvec2(pb)};
}

VanishingInput lines(const Camera& cam) {
    VanishingInput in;
    for (double z : {0.0, 0.4, -0.5}) in.x.push_back(segment(cam, {-0.5, 0, z}, {1.0, 0, z}));
    for (double x : {0.0, 0.6, 1.0}) in.z.push_back(segment(cam, {x, 0, -0.6}, {x, 0, 0.5}));
    for (double x : {-0.4, 0.9}) in.y.push_back(segment(cam, {x, 0, -0.5}, {x, 1.2, -0.5}));
    vec2 o;
    EXPECT_TRUE(cam.project(vec3(0), o));
    in.origin = glm::dvec2(o);
    in.camera_height = cam.position().y;
    return in;
}

}  // namespace

TEST(Vanishing, ThreeDirectionsGiveThePrincipalPointAsTheOrthocentre) {
    const CameraSpec truth = shifted_camera();
    const Camera cam = truth.build(kW, kH);
    CalibrationResult r = calibrate_vanishing(lines(cam), kW, kH, "");
    EXPECT_NEAR(r.intrinsics.cx, truth.cx, 0.05);
    EXPECT_NEAR(r.intrinsics.cy, truth.cy, 0.05);
    EXPECT_NEAR(r.intrinsics.fx, truth.fx, 0.05);
    EXPECT_LT(r.rms_px, 1e-3);
    EXPECT_LT(glm::length(r.pose.position() - glm::dvec3(cam.position())), 1e-4);
    EXPECT_LT(rotation_angle_deg(r.pose.R, glm::dmat3(truth.rotation)), 1e-3);
}

TEST(Vanishing, AnyTwoDirectionsGiveTheSameCameraWithACentredPrincipalPoint) {
    const CameraSpec truth = camera_at({1.5, 1.6, 2.5}, {0.3, 0, -0.2}, kW, kH, 800);
    const Camera cam = truth.build(kW, kH);
    const VanishingInput all = lines(cam);
    for (int drop = 0; drop < 3; ++drop) {
        SCOPED_TRACE("without direction " + std::to_string(drop));
        VanishingInput in = all;
        (drop == 0 ? in.x : drop == 1 ? in.y : in.z).clear();
        CalibrationResult r = calibrate_vanishing(in, kW, kH, "");
        EXPECT_NEAR(r.intrinsics.fx, 800.0, 0.05);
        EXPECT_LT(glm::length(r.pose.position() - glm::dvec3(cam.position())), 1e-4);
        EXPECT_LT(rotation_angle_deg(r.pose.R, glm::dmat3(truth.rotation)), 1e-3);
    }
}

TEST(Vanishing, AGivenFocalLengthIsKept) {
    const CameraSpec truth = camera_at({1.5, 1.6, 2.5}, {0.3, 0, -0.2}, kW, kH, 800);
    VanishingInput in = lines(truth.build(kW, kH));
    in.y.clear();
    in.focal_px = 800.0;
    CalibrationResult r = calibrate_vanishing(in, kW, kH, "");
    EXPECT_EQ(r.intrinsics.fx, 800.0);
    EXPECT_LT(rotation_angle_deg(r.pose.R, glm::dmat3(truth.rotation)), 1e-3);
}
