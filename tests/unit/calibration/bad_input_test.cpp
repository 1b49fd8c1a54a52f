// Bad input to the calibration methods: an InputError that says what is wrong, never a camera.
#include <gtest/gtest.h>

#include <functional>

#include "base/error.h"
#include "calibration/correspondences.h"
#include "calibration/vanishing.h"
#include "common/input_error.h"

using namespace dp;
using dp::test::input_error_message;

namespace {

#define EXPECT_INPUT_ERROR(call, text) \
    EXPECT_NE(input_error_message([&] { call; }).find(text), std::string::npos) << input_error_message([&] { call; })

const Intrinsics kK = Intrinsics::centred(640, 480, 500);

/// Ground lines of a 1000x750 photo (f = 800 px) looking down at about 28 degrees.
VanishingInput converging() {
    VanishingInput in;
    in.x = {{{313.041, 358.962}, {650.975, 434.827}}, {{253.016, 401.398}, {620.047, 495.192}}};
    in.z = {{{475.916, 325.495}, {345.697, 442.412}}, {{597.218, 348.529}, {496.481, 482.324}}};
    in.origin = {413.518, 381.519};
    in.camera_height = 1.5;
    return in;
}

}  // namespace

TEST(RectangleInput, FewerThanFourCornersAreRejected) {
    EXPECT_INPUT_ERROR(calibrate_rectangle({{10, 10}, {50, 12}, {48, 40}}, 1, 1, 640, 480, kK, "r"),
                       "need at least 4 rectangle corners, got 3");
}

TEST(RectangleInput, CollinearCornersAreRejected) {
    EXPECT_INPUT_ERROR(calibrate_rectangle({{10, 10}, {20, 20}, {30, 30}, {40, 40}}, 1, 1, 640,
                                           480, kK, "r"),
                       "collinear");
    EXPECT_INPUT_ERROR(calibrate_rectangle({{10, 10}, {30, 10}, {50, 10}, {30, 40}}, 1, 1, 640,
                                           480, kK, "r"),
                       "three of the rectangle corners are collinear");
}

TEST(RectangleInput, CornersOutOfOrderAreRejected) {
    EXPECT_INPUT_ERROR(calibrate_rectangle({{10, 10}, {50, 40}, {50, 10}, {10, 40}}, 1, 1, 640,
                                           480, kK, "r"),
                       "do not go around the rectangle in order");
}

TEST(RectangleInput, AZeroFocalLengthOrSizeIsRejected) {
    const std::vector<ImagePoint> quad = {{100, 100}, {300, 110}, {310, 300}, {90, 280}};
    EXPECT_INPUT_ERROR(
        calibrate_rectangle(quad, 1, 1, 640, 480, Intrinsics::centred(640, 480, -3), "r"),
        "the focal length must be > 0");
    EXPECT_INPUT_ERROR(calibrate_rectangle(quad, 0, 1, 640, 480, kK, "r"), "must be > 0 metres");
}

TEST(RectangleInput, AFaceOnRectangleGivesNoFocalLength) {
    // An axis-aligned rectangle in the image: no perspective to measure.
    EXPECT_INPUT_ERROR(calibrate_rectangle({{100, 100}, {300, 100}, {300, 200}, {100, 200}}, 2, 1,
                                           640, 480, std::nullopt, "r"),
                       "seen too nearly face-on, or too small");
}

TEST(PointsInput, TooFewOrDegeneratePointsAreRejected) {
    std::vector<PointCorrespondence> three = {
        {{0, 0, 0}, {10, 10}}, {{1, 0, 0}, {50, 12}}, {{0, 0, 1}, {20, 40}}};
    EXPECT_INPUT_ERROR(calibrate_points(three, 640, 480, kK, "p"), "need at least 4 points, got 3");
    std::vector<PointCorrespondence> line = {{{0, 0, 0}, {10, 10}}, {{1, 0, 0}, {20, 20}},
                                             {{2, 0, 0}, {30, 30}}, {{3, 0, 0}, {40, 40}}};
    EXPECT_INPUT_ERROR(calibrate_points(line, 640, 480, kK, "p"), "collinear");
    // Six points in one plane fix no focal length; five are too few without one.
    std::vector<PointCorrespondence> flat;
    for (int i = 0; i < 6; ++i)
        flat.push_back({{double(i % 3), 0, double(i / 3)},
                        {100.0 + 50 * (i % 3) + 7 * i, 200.0 + 60 * (i / 3)}});
    EXPECT_INPUT_ERROR(calibrate_points(flat, 640, 480, std::nullopt, "p"), "in one plane");
    flat.pop_back();
    EXPECT_INPUT_ERROR(calibrate_points(flat, 640, 480, Intrinsics::centred(640, 480, 0), "p"),
                       "need at least 6 points");
}

TEST(VanishingInput, ParallelLinesAndOneOtherDirectionNeedAGivenFocalLength) {
    VanishingInput in = converging();
    in.x = {{{100, 300}, {600, 300}}, {{100, 400}, {600, 400}}};
    EXPECT_INPUT_ERROR(calibrate_vanishing(in, 1000, 750, "v"), "vanishing point is at infinity");
    EXPECT_INPUT_ERROR(calibrate_vanishing(in, 1000, 750, "v"), "give it (--focal, --exif)");
    in.focal_px = 800;
    EXPECT_NO_THROW(calibrate_vanishing(in, 1000, 750, "v"));
}

TEST(VanishingInput, DirectionsThatCannotBeOrthogonalAreRejected) {
    VanishingInput in = converging();
    // Both groups converge to the right of the image: f^2 would be negative.
    in.x = {{{0, 300}, {200, 310}}, {{0, 400}, {200, 405}}};
    in.z = {{{300, 300}, {500, 310}}, {{300, 400}, {500, 405}}};
    EXPECT_INPUT_ERROR(calibrate_vanishing(in, 1000, 750, "v"), "cannot be orthogonal");
}

TEST(VanishingInput, MissingOrBadScaleAndDirectionsAreRejected) {
    EXPECT_NO_THROW(calibrate_vanishing(converging(), 1000, 750, "v"));
    VanishingInput one = converging();
    one.z.clear();
    EXPECT_INPUT_ERROR(calibrate_vanishing(one, 1000, 750, "v"), "at least two of the directions");
    VanishingInput single = converging();
    single.z.pop_back();
    EXPECT_INPUT_ERROR(calibrate_vanishing(single, 1000, 750, "v"), "at least 2 line segments");
    VanishingInput no_scale = converging();
    no_scale.camera_height.reset();
    EXPECT_INPUT_ERROR(calibrate_vanishing(no_scale, 1000, 750, "v"), "give a scale");
    VanishingInput sky = converging();
    sky.origin = {500, -3000};
    EXPECT_INPUT_ERROR(calibrate_vanishing(sky, 1000, 750, "v"), "below the horizon");
    VanishingInput zero = converging();
    zero.focal_px = 0.0;
    EXPECT_INPUT_ERROR(calibrate_vanishing(zero, 1000, 750, "v"), "the focal length must be > 0");
}
