// Well-formed but wrong input: a warning that names the problem where the camera is still
// usable, an InputError where it is not; never a silently wrong camera.
#include <gtest/gtest.h>

#include "base/error.h"
#include "calibration/correspondences.h"
#include "common/input_error.h"
#include "line_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {

/// The first warning containing `text`, or "" (the test then fails with all of them).
bool has_warning(const CalibrationResult& r, const std::string& text) {
    for (const std::string& w : r.warnings)
        if (w.find(text) != std::string::npos) return true;
    ADD_FAILURE() << "no warning with '" << text << "' among " << r.warnings.size();
    for (const std::string& w : r.warnings) ADD_FAILURE() << "  warning: " << w;
    return false;
}

void expect_error(const std::function<void()>& f, const std::string& text) {
    const std::string m = input_error_message(f);
    EXPECT_NE(m.find(text), std::string::npos) << m;
}

/// The image corners of a 0.6 x 0.4 m rectangle on the ground, seen by oblique_camera().
std::vector<ImagePoint> rectangle_corners(double w = 0.6, double h = 0.4) {
    const LineScene s = ground_lines();
    return {s.pixel({0, 0, 0}), s.pixel({w, 0, 0}), s.pixel({w, 0, h}), s.pixel({0, 0, h})};
}

const Intrinsics kK = Intrinsics::centred(1000, 750, 800);

}  // namespace

TEST(CalibrationWrongInput, ARectangleOfAnotherAspectIsRefusedNamingTheAspect) {
    const auto c = rectangle_corners();
    EXPECT_NO_THROW(calibrate_rectangle(c, 0.6, 0.4, 1000, 750, kK, "r"));
    expect_error([&] { calibrate_rectangle(c, 0.6, 0.6, 1000, 750, kK, "r"); },
                 "the corners fit a rectangle of aspect 1.50 (width / height");
    expect_error([&] { calibrate_rectangle(c, 0.4, 0.6, 1000, 750, kK, "r"); },
                 "width and height swapped?");
}

TEST(CalibrationWrongInput, ARectangleCornerFarOffIsRefused) {
    auto c = rectangle_corners();
    c[2].x += 121;
    expect_error([&] { calibrate_rectangle(c, 0.6, 0.4, 1000, 750, kK, "r"); },
                 "a corner is misplaced");
    // Without a focal length four corners always fit some camera: an impossible lens warns.
    const CalibrationResult r = calibrate_rectangle(c, 0.6, 0.4, 1000, 750, std::nullopt, "r");
    has_warning(r, "wider than almost any lens");
}

TEST(CalibrationWrongInput, AFocalLengthFromASmallRectangleWarnsThatItIsUncertain) {
    // A 0.3 x 0.2 m sheet: about 60 px across.
    const auto c = rectangle_corners(0.3, 0.2);
    ASSERT_LT(glm::length(c[1] - c[0]), 90.0);
    const CalibrationResult r = calibrate_rectangle(c, 0.3, 0.2, 1000, 750, std::nullopt, "r");
    EXPECT_NEAR(r.intrinsics.fx, 800, 1);  // exact corners: right, but only by luck of the clicks
    EXPECT_GT(r.uncertainty.fx, 0.05 * r.intrinsics.fx);
    has_warning(r, "the focal length is uncertain");
}

TEST(CalibrationWrongInput, AVerticalLengthGivenAsAGroundDistanceWarns) {
    const LineScene scene = ground_lines_and_box_edges();
    VanishingInput in = scene.exact();
    const glm::dvec3 foot(0.7, 0, -0.1);
    in.distance = VanishingInput::Distance{scene.pixel(foot),
                                           scene.pixel(foot + glm::dvec3(0, 0.28, 0)), 0.28};
    const CalibrationResult r = calibrate_vanishing(in, scene.width, scene.height, "v");
    EXPECT_LT(r.pose.position().y, 0.5 * scene.camera().position().y);  // the scale is wrong
    has_warning(r, "give them as a vertical length");
}

TEST(CalibrationWrongInput, AVerticalLengthWhoseTopIsNotAboveItsFootWarns) {
    const LineScene scene = ground_lines_and_box_edges();
    VanishingInput in = scene.exact();
    in.distance.reset();
    const glm::dvec3 foot(0.7, 0, -0.1);
    in.vertical = VanishingInput::Distance{scene.pixel(foot),
                                           scene.pixel(foot + glm::dvec3(0, 0.28, 0)) +
                                               glm::dvec2(12, 0),
                                           0.28};
    has_warning(calibrate_vanishing(in, scene.width, scene.height, "v"), "off the vertical");
    in.vertical->b = scene.pixel(foot) + glm::dvec2(0, 30);  // below the foot
    expect_error([&] { calibrate_vanishing(in, scene.width, scene.height, "v"); },
                 "must be above its foot");
    in.camera_height = 1.6;
    expect_error([&] { calibrate_vanishing(in, scene.width, scene.height, "v"); },
                 "give one scale only");
}

TEST(CalibrationWrongInput, ALineInTheWrongGroupIsRefused) {
    const LineScene scene = long_ground_lines();
    VanishingInput in = scene.exact();
    in.x.push_back(in.z[1]);
    expect_error([&] { calibrate_vanishing(in, scene.width, scene.height, "v"); },
                 "wrong group");
}

TEST(CalibrationWrongInput, APointAFewPixelsOffWarnsOfThePoorFit) {
    const LineScene scene = ground_lines();
    std::vector<PointCorrespondence> pts;
    for (const glm::dvec3& w : {glm::dvec3(0, 0, 0), glm::dvec3(0.6, 0, 0), glm::dvec3(0.6, 0, 0.4),
                                glm::dvec3(0, 0, 0.4), glm::dvec3(0.3, 0.5, 0.2),
                                glm::dvec3(0.1, 0.8, -0.3), glm::dvec3(0.5, 0.3, -0.4)})
        pts.push_back({w, scene.pixel(w)});
    EXPECT_TRUE(calibrate_points(pts, 1000, 750, kK, "p").warnings.empty());
    pts[4].image.x += 12;
    has_warning(calibrate_points(pts, 1000, 750, kK, "p"), "fits the camera poorly");
}

TEST(CalibrationWrongInput, APrincipalPointOutsideTheMiddleHalfWarns) {
    // Points of a camera whose principal point is at x = 100 in a 1000 px wide photo.
    LineScene scene = ground_lines();
    scene.truth.cx = 100;
    std::vector<PointCorrespondence> pts;
    for (const glm::dvec3& w : {glm::dvec3(0, 0, 0), glm::dvec3(0.6, 0, 0), glm::dvec3(0.6, 0, 0.4),
                                glm::dvec3(0, 0, 0.4), glm::dvec3(0.3, 0.5, 0.2),
                                glm::dvec3(0.1, 0.8, -0.3), glm::dvec3(0.5, 0.3, -0.4)})
        pts.push_back({w, scene.pixel(w)});
    const CalibrationResult r = calibrate_points(pts, 1000, 750, std::nullopt, "p");
    EXPECT_NEAR(r.intrinsics.cx, 100, 1);
    has_warning(r, "outside the middle half");
}
