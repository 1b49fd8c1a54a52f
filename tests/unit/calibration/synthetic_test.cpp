// Calibration of synthetic photographs of a chessboard on the ground, drawn through a known
// camera: focal length within 1%, rotation within 0.5 degree, position within 1% of distance.
// tests/render/calibration_photo_test.cpp runs the single-photo checks on path-traced photos.
#include <gtest/gtest.h>

#include "calibration/chessboard.h"
#include "calibration/correspondences.h"
#include "single_photo_checks.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr int kW = 640, kH = 480;
constexpr double kFocal = 600;

const GroundBoard& board() {
    static const GroundBoard b;
    return b;
}

/// Single-photo methods: two oblique views (the vanishing-point method needs both ground
/// directions to converge visibly), drawn once per process.
const std::vector<BoardPhoto>& photos() {
    static const std::vector<BoardPhoto> p = board_photos(
        board(), {{1.0, 1.1, 1.1}, {1.2, 1.0, -0.6}}, kW, kH, kFocal,
        [](const GroundBoard& b, const CameraSpec& c, int w, int h) { return b.draw(c, w, h); });
    return p;
}

/// Lens calibration needs many views with the board in different parts of the image: these
/// are drawn directly (board albedo through the camera), which costs a fraction of a render.
struct DrawnView {
    glm::dvec3 eye, target;
};
const std::vector<DrawnView>& drawn() {
    static const std::vector<DrawnView> d = {
        {{0.2, 1.2, 1.3}, {0.3, 0, 0.2}},     {{-1.1, 0.9, 0.9}, {-0.2, 0, -0.25}},
        {{1.2, 1.0, -0.6}, {0.25, 0, 0.3}},   {{0.15, 1.8, 0.4}, {-0.3, 0, 0.15}},
        {{-0.6, 0.8, -1.2}, {0.35, 0, 0.1}},  {{0.9, 1.4, 0.9}, {-0.3, 0, -0.2}},
        {{-1.3, 1.3, -0.2}, {0.1, 0, 0.3}},   {{0.0, 1.0, -1.5}, {-0.2, 0, 0.3}}};
    return d;
}
CameraSpec drawn_camera(size_t i) {
    return camera_at(drawn()[i].eye, drawn()[i].target, kW, kH, kFocal);
}

}  // namespace

TEST(SyntheticChessboard, SeveralPhotosRecoverTheCamera) {
    std::vector<ChessboardView> views;
    for (size_t i = 0; i < drawn().size(); ++i)
        views.push_back(detect_chessboard(board().draw(drawn_camera(i), kW, kH), board().spec(),
                                          "drawn view " + std::to_string(i)));
    ChessboardCalibration c = calibrate_chessboard(views, board().spec());
    RecordProperty("rms_px", std::to_string(c.result.rms_px));
    EXPECT_LT(c.result.rms_px, 0.5);
    // The stated uncertainty of the lens covers the true one (three standard deviations).
    const Intrinsics& k = c.result.intrinsics;
    const Uncertainty& u = c.result.uncertainty;
    RecordProperty("lens", uncertainty_text(c.result));
    EXPECT_LT(std::abs(k.fx - kFocal), 3 * u.fx);
    EXPECT_LT(std::abs(k.fy - kFocal), 3 * u.fy);
    EXPECT_LT(std::abs(k.cx - 0.5 * (kW - 1)), 3 * u.cx);
    EXPECT_LT(std::abs(k.cy - 0.5 * (kH - 1)), 3 * u.cy);
    for (size_t i = 0; i < views.size(); ++i) {
        SCOPED_TRACE(views[i].source);
        CalibrationResult r = c.result;
        r.pose = c.poses[i];
        expect_matches(r, drawn_camera(i), c.world_corners[i],
                       true_corners_for(views[i], board(), drawn_camera(i)));
    }
    // The renderer's lens has no distortion: where the board was seen, the fitted distortion
    // moves no point by more than 1 px (outside, a few views leave it unconstrained).
    Camera cam = c.result.camera();
    for (const ChessboardView& v : views)
        for (const ImagePoint& p : v.corners) {
            vec2 n((float(p.x) - cam.cx()) / cam.fx(), (float(p.y) - cam.cy()) / cam.fy());
            EXPECT_LT(glm::length((cam.distort(n) - n) * cam.fx()), 1.0f);
        }
}

TEST(SyntheticPoints, SixPointsOffThePlaneRecoverTheCamera) {
    // Board corners plus two corners lifted off the ground, projected by the true camera.
    const CameraSpec truth = camera_at({1.0, 1.1, 1.1}, {0.05, 0, -0.03}, kW, kH, kFocal);
    const Camera cam = truth.build(kW, kH);
    std::vector<PointCorrespondence> pts;
    for (glm::dvec3 w : {board().corner(0, 0), board().corner(8, 0), board().corner(8, 5),
                         board().corner(0, 5), board().corner(4, 2) + glm::dvec3(0, 0.5, 0),
                         board().corner(2, 4) + glm::dvec3(0, 0.3, 0),
                         board().corner(6, 1) + glm::dvec3(0, 0.8, 0)}) {
        vec2 px;
        ASSERT_TRUE(cam.project(vec3(w), px));
        pts.push_back({w, glm::dvec2(px)});
    }
    CalibrationResult r = calibrate_points(pts, kW, kH, std::nullopt, "");
    std::vector<glm::dvec3> world;
    for (const auto& p : pts) world.push_back(p.world);
    expect_matches(r, truth, world, world);
    EXPECT_LT(r.rms_px, 0.05);
    CalibrationResult k = calibrate_points(pts, kW, kH, Intrinsics::centred(kW, kH, kFocal), "");
    expect_matches(k, truth, world, world);
}


TEST(SyntheticChessboard, OnePhotoRecoversThePoseAndTheFocalLength) {
    for (const BoardPhoto& p : photos()) {
        SCOPED_TRACE(p.view.source);
        check_chessboard_one_photo(board(), p);
    }
}

TEST(SyntheticRectangle, TheBoardsOuterCornersRecoverTheCamera) {
    for (const BoardPhoto& p : photos()) {
        SCOPED_TRACE(p.view.source);
        check_rectangle(board(), p);
    }
}

TEST(SyntheticVanishing, BoardLinesAndOneDistanceRecoverTheCamera) {
    for (const BoardPhoto& p : photos()) {
        SCOPED_TRACE(p.view.source);
        check_vanishing(board(), p);
    }
}
