// Calibration of synthetic photographs rendered by the reference path tracer with a known
// camera: focal length within 1%, rotation within 0.5 degree, position within 1% of distance.
#include <gtest/gtest.h>

#include <chrono>

#include "calibration/chessboard.h"
#include "calibration/correspondences.h"
#include "calibration/vanishing.h"
#include "synthetic_board.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr int kW = 640, kH = 480;
constexpr double kFocal = 600;

const GroundBoard& board() {
    static const GroundBoard b;
    return b;
}

/// Photographs rendered by the path tracer (4 samples per pixel), for the single-photo methods.
const std::vector<glm::dvec3>& traced_eyes() {
    static const std::vector<glm::dvec3> e = {{1.0, 1.1, 1.1}, {1.2, 1.0, -0.6}};
    return e;
}

CameraSpec true_camera(size_t i) {
    return camera_at(traced_eyes()[i], glm::dvec3(0.05, 0, -0.03), kW, kH, kFocal);
}

/// Rendered and detected once for the whole file.
const std::vector<ChessboardView>& views() {
    static const std::vector<ChessboardView> v = [] {
        std::vector<ChessboardView> out;
        for (size_t i = 0; i < traced_eyes().size(); ++i) {
            Image photo = board().render(true_camera(i), kW, kH);
            out.push_back(detect_chessboard(photo, board().spec(), "view " + std::to_string(i)));
        }
        return out;
    }();
    return v;
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

TEST(SyntheticChessboard, OnePhotoWithAKnownFocalLengthRecoversThePose) {
    const Intrinsics k = Intrinsics::centred(kW, kH, kFocal);
    for (size_t i = 0; i < views().size(); ++i) {
        SCOPED_TRACE("view " + std::to_string(i));
        CalibrationResult r = chessboard_pose(views()[i], board().spec(), k);
        EXPECT_LT(r.rms_px, 0.5);
        expect_matches(r, true_camera(i), r.world_points,
                       true_corners_for(views()[i], board(), true_camera(i)));
    }
}

TEST(SyntheticChessboard, OneTiltedPhotoRecoversTheFocalLength) {
    for (size_t i = 0; i < views().size(); ++i) {
        SCOPED_TRACE("view " + std::to_string(i));
        CalibrationResult r = chessboard_single(views()[i], board().spec());
        expect_matches(r, true_camera(i), r.world_points,
                       true_corners_for(views()[i], board(), true_camera(i)));
    }
}

TEST(SyntheticRectangle, TheBoardsOuterCornersRecoverTheCamera) {
    const GroundBoard& b = board();
    const double w = (b.cols - 1) * b.square, h = (b.rows - 1) * b.square;
    for (size_t i = 0; i < views().size(); ++i) {
        SCOPED_TRACE("view " + std::to_string(i));
        const ChessboardView& v = views()[i];
        const size_t idx[4] = {0, size_t(b.cols - 1), size_t(b.cols * b.rows - 1),
                               size_t((b.rows - 1) * b.cols)};
        std::vector<ImagePoint> corners;
        for (size_t j : idx) corners.push_back(v.corners[j]);
        std::vector<glm::dvec3> all = true_corners_for(v, b, true_camera(i)), truth;
        for (size_t j : idx) truth.push_back(all[j]);
        // With the focal length known...
        CalibrationResult r =
            calibrate_rectangle(corners, w, h, kW, kH, Intrinsics::centred(kW, kH, kFocal), "");
        expect_matches(r, true_camera(i), r.world_points, truth);
        // ... and estimated from the rectangle's perspective (four points: a looser focal bound).
        CalibrationResult e = calibrate_rectangle(corners, w, h, kW, kH, std::nullopt, "");
        expect_matches(e, true_camera(i), e.world_points, truth, 0.02);
    }
}

TEST(SyntheticPoints, SixPointsOffThePlaneRecoverTheCamera) {
    // Board corners plus two corners lifted off the ground, projected by the true camera.
    const CameraSpec truth = true_camera(0);
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

namespace {

/// Back-projects image points onto the ground (y = 0) of a calibrated camera.
std::vector<glm::dvec3> on_ground(const CalibrationResult& r, const std::vector<ImagePoint>& px) {
    std::vector<glm::dvec3> out;
    const glm::dmat3 Rt = glm::transpose(r.pose.R);
    const glm::dvec3 c = r.pose.position();
    for (const ImagePoint& p : px) {
        glm::dvec3 d = Rt * glm::dvec3((p.x - r.intrinsics.cx) / r.intrinsics.fx,
                                       (p.y - r.intrinsics.cy) / r.intrinsics.fy, 1.0);
        out.push_back(c + (-c.y / d.y) * d);
    }
    return out;
}

}  // namespace

TEST(SyntheticVanishing, BoardLinesAndOneDistanceRecoverTheCamera) {
    const GroundBoard& b = board();
    for (size_t i = 0; i < views().size(); ++i) {
        SCOPED_TRACE("view " + std::to_string(i));
        const ChessboardView& v = views()[i];
        auto at = [&](int c, int r) { return v.corners[size_t(r * b.cols + c)]; };
        // Detected rows and columns: lines along the board's two axes on the ground.
        VanishingInput in;
        for (int r = 0; r < b.rows; ++r) in.x.push_back({at(0, r), at(b.cols - 1, r)});
        for (int c = 0; c < b.cols; ++c) in.z.push_back({at(c, 0), at(c, b.rows - 1)});
        in.origin = at(0, 0);
        in.distance = VanishingInput::Distance{at(0, 0), at(b.cols - 1, 0),
                                               (b.cols - 1) * b.square};
        CalibrationResult r = calibrate_vanishing(in, kW, kH, "");
        EXPECT_LT(r.rms_px, 0.5);
        // The origin is where it was put, on the ground.
        EXPECT_LT(glm::length(on_ground(r, {at(0, 0)})[0]), 1e-9);
        expect_matches(r, true_camera(i), on_ground(r, v.corners),
                       true_corners_for(v, b, true_camera(i)));
        // The camera height gives the same camera.
        VanishingInput h = in;
        h.distance.reset();
        h.camera_height = traced_eyes()[i].y;
        CalibrationResult rh = calibrate_vanishing(h, kW, kH, "");
        expect_matches(rh, true_camera(i), on_ground(rh, v.corners),
                       true_corners_for(v, b, true_camera(i)));
    }
}
