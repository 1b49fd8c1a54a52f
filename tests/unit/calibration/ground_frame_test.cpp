// A board on a wall: the ground chosen from the camera's up or from a clicked horizon. The
// corners are projected from known world points by a known camera (double precision, with
// and without lens distortion), so everything but the choice of up is exact.
#include "calibration/ground_frame.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "calibration/chessboard.h"
#include "calibration/reprojection.h"
#include "common/input_error.h"
#include "reconstruction/proxies.h"

using namespace dp;

namespace {

constexpr int kW = 640, kH = 480;
constexpr double kFocal = 600;
const ChessboardSpec kBoard{9, 6, 0.04};
/// The board hangs on the wall z = 0, its first inner corner 1.2 m above the floor; its rows
/// run along world +X and its columns down the wall.
constexpr double kBoardHeight = 1.2;
const glm::dvec3 kEye(0.9, 1.55, 1.6);

double degrees(double r) {
    return r * 180.0 / std::numbers::pi;
}
double angle_deg(const glm::dvec3& a, const glm::dvec3& b) {
    return degrees(
        std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)));
}

glm::dvec3 wall_corner(int c, int r) {
    return glm::dvec3(0.1 + c * kBoard.square_size, kBoardHeight - r * kBoard.square_size, 0.0);
}

/// The true camera: at kEye looking at the board, turned about its axis by `roll_deg`.
struct Truth {
    Intrinsics k;
    Pose pose;
};
Truth truth(double roll_deg, Distortion d = {}) {
    const Camera look =
        Camera::look_at(kW, kH, vec3(kEye), vec3(0.25f, 1.1f, 0.0f), vec3(0, 1, 0), 40.0f);
    const double a = roll_deg * std::numbers::pi / 180.0;
    // A turn about the camera's Z: x_cam' = Rz x_cam.
    const glm::dmat3 Rz(glm::dvec3(std::cos(a), std::sin(a), 0),
                        glm::dvec3(-std::sin(a), std::cos(a), 0), glm::dvec3(0, 0, 1));
    Truth t;
    t.k = Intrinsics::centred(kW, kH, kFocal);
    t.k.distortion = d;
    t.pose.R = Rz * glm::dmat3(look.rotation());
    t.pose.t = -(t.pose.R * kEye);
    return t;
}

ChessboardView wall_view(const Truth& t) {
    ChessboardView v;
    v.source = "wall board";
    v.width = kW;
    v.height = kH;
    for (int r = 0; r < kBoard.rows; ++r)
        for (int c = 0; c < kBoard.cols; ++c)
            v.corners.push_back(calib::project(t.k, t.pose, wall_corner(c, r)));
    return v;
}

/// Two points of the true horizon, at normalised x = -0.45 and 0.45, through the lens.
std::pair<ImagePoint, ImagePoint> true_horizon(const Truth& t) {
    const glm::dvec3 n = t.pose.R[1];  // world up in camera coordinates
    auto at = [&](double x) {
        const double y = -(n.x * x + n.z) / n.y;
        // A world direction along that ray (at infinity: project a far point).
        const glm::dvec3 cam_dir(x, y, 1.0);
        const glm::dvec3 world_dir = glm::transpose(t.pose.R) * cam_dir;
        return calib::project(t.k, t.pose, kEye + 1e7 * world_dir);
    };
    return {at(-0.45), at(0.45)};
}

/// Checks a re-expressed calibration against the truth.
void expect_true_ground(const CalibrationResult& board_frame, const CalibrationResult& g,
                        const Truth& t) {
    // World up: the new frame's Y and the true one, both in camera coordinates.
    const double up_error = angle_deg(g.pose.R[1], t.pose.R[1]);
    testing::Test::RecordProperty("up_error_deg", std::to_string(up_error));
    EXPECT_LT(up_error, 0.5);
    // The board's plane is vertical: its normal has no Y.
    const auto& w = g.world_points;
    ASSERT_EQ(w.size(), size_t(kBoard.cols * kBoard.rows));
    const glm::dvec3 normal =
        glm::normalize(glm::cross(w[1] - w[0], w[size_t(kBoard.cols)] - w[0]));
    EXPECT_LT(std::abs(normal.y), std::sin(0.5 * std::numbers::pi / 180));
    // The board's first corner stands at the given height straight above the origin.
    EXPECT_NEAR(w[0].x, 0.0, 1e-9);
    EXPECT_NEAR(w[0].y, kBoardHeight, 1e-9);
    EXPECT_NEAR(w[0].z, 0.0, 1e-9);
    EXPECT_NEAR(g.pose.position().y, kEye.y, 1e-3);
    // The camera is the same camera: every corner reprojects where it did.
    double worst = 0;
    for (size_t i = 0; i < w.size(); ++i)
        worst = std::max(worst, glm::length(calib::project(g.intrinsics, g.pose, w[i]) -
                                            calib::project(board_frame.intrinsics, board_frame.pose,
                                                           board_frame.world_points[i])));
    EXPECT_LT(worst, 1e-6);
    EXPECT_EQ(g.rms_px, board_frame.rms_px);
    // The ground is horizontal world X-Z: the board's rows (level on the wall) stay level.
    EXPECT_LT(std::abs(glm::normalize(w[1] - w[0]).y), 1e-3);
}

}  // namespace

TEST(GroundFrame, ABoardOnAWallWithTheCameraUpGivesTheTrueGround) {
    const Truth t = truth(0);
    const CalibrationResult r = chessboard_pose(wall_view(t), kBoard, t.k);
    // In the board's own frame the wall is the ground: up is the wall's normal.
    ASSERT_GT(angle_deg(r.pose.R[1], t.pose.R[1]), 80.0);
    const CalibrationResult g =
        with_ground_from_up(r, up_from_camera(r, "wall"), kBoardHeight, "wall");
    expect_true_ground(r, g, t);
    EXPECT_TRUE(g.warnings.empty()) << g.warnings.front();
}

TEST(GroundFrame, AClickedHorizonGivesTheTrueGroundWhereTheCameraIsRolled) {
    const Truth t = truth(10);
    const CalibrationResult r = chessboard_pose(wall_view(t), kBoard, t.k);
    // The camera's up assumes no roll: 10° off here.
    const CalibrationResult wrong =
        with_ground_from_up(r, up_from_camera(r, "wall"), kBoardHeight, "wall");
    EXPECT_GT(angle_deg(wrong.pose.R[1], t.pose.R[1]), 9.0);
    const auto [a, b] = true_horizon(t);
    const CalibrationResult g =
        with_ground_from_up(r, up_from_horizon(r.intrinsics, a, b, "wall"), kBoardHeight, "wall");
    expect_true_ground(r, g, t);
    // Clicked the other way round, the same up.
    EXPECT_LT(angle_deg(up_from_horizon(r.intrinsics, b, a, "wall"), t.pose.R[1]), 1e-4);
}

TEST(GroundFrame, TheHorizonIsUndistortedThroughTheLensFirst) {
    const Truth t = truth(10, Distortion{-0.3f, 0.1f, 0.001f, -0.002f, 0.0f});
    const CalibrationResult r = chessboard_pose(wall_view(t), kBoard, t.k);
    const auto [a, b] = true_horizon(t);
    const CalibrationResult g =
        with_ground_from_up(r, up_from_horizon(r.intrinsics, a, b, "wall"), kBoardHeight, "wall");
    expect_true_ground(r, g, t);
    // Through a pinhole the same clicks give another up: the distortion matters here.
    Intrinsics pinhole = r.intrinsics;
    pinhole.distortion = {};
    EXPECT_GT(angle_deg(up_from_horizon(pinhole, a, b, "wall"), t.pose.R[1]), 1.0);
}

TEST(GroundFrame, AHorizonThatMissesTheWallIsWarnedAbout) {
    const Truth t = truth(0);
    const CalibrationResult r = chessboard_pose(wall_view(t), kBoard, t.k);
    // The camera looks about 15° down: a horizon clicked level through the image's centre
    // tilts the wall by as much.
    const CalibrationResult g = with_ground_from_up(
        r, up_from_horizon(r.intrinsics, {100, 240}, {540, 240}, "wall"), kBoardHeight, "wall");
    ASSERT_FALSE(g.warnings.empty());
    EXPECT_NE(g.warnings.back().find("from vertical"), std::string::npos) << g.warnings.back();
}

TEST(GroundFrame, BadUpAndHeightAreInputErrors) {
    const Truth t = truth(0);
    const CalibrationResult r = chessboard_pose(wall_view(t), kBoard, t.k);
    auto message = [&](auto f) { return test::input_error_message(f); };
    EXPECT_NE(
        message([&] { with_ground_from_up(r, glm::dvec3(0.0), 1.0, "wall"); }).find("non-zero"),
        std::string::npos);
    EXPECT_NE(message([&] {
                  with_ground_from_up(r, glm::dvec3(0, -1, 0), -0.5, "wall");
              }).find("height above the ground must be >= 0"),
              std::string::npos);
    EXPECT_NE(message([&] {
                  with_ground_from_up(r, glm::dvec3(0, -1, 0), NAN, "wall");
              }).find("board height"),
              std::string::npos);
    EXPECT_NE(message([&] {
                  up_from_horizon(r.intrinsics, {100, 100}, {100.5, 100.5}, "wall");
              }).find("0.7 px apart"),
              std::string::npos);
    EXPECT_NE(message([&] {
                  up_from_horizon(r.intrinsics, {300, 50}, {310, 400}, "wall");
              }).find("which side is up is ambiguous"),
              std::string::npos);
    EXPECT_NE(message([&] {
                  up_from_horizon(r.intrinsics, {NAN, 50}, {310, 400}, "wall");
              }).find("finite"),
              std::string::npos);
    // A board whose normal is the camera's X axis (a wall the camera looks along): no
    // direction in it is at right angles to a level X axis but its normal.
    CalibrationResult edge_on = r;
    edge_on.pose.R = glm::dmat3(glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0));
    EXPECT_NE(message([&] { up_from_camera(edge_on, "wall"); }).find("click the horizon instead"),
              std::string::npos);
}

TEST(GroundFrame, TheCameraBelowTheNewGroundIsWarnedAbout) {
    const Truth t = truth(0);
    const CalibrationResult r = chessboard_pose(wall_view(t), kBoard, t.k);
    // Up the wrong way round (down the wall): the camera, 0.35 m above the board's corner,
    // ends up 0.25 m under a floor 0.1 m "below" the corner.
    const CalibrationResult g = with_ground_from_up(r, -up_from_camera(r, "wall"), 0.1, "wall");
    ASSERT_FALSE(g.warnings.empty());
    EXPECT_NE(g.warnings.front().find("the camera is 0.25 m below the ground"), std::string::npos)
        << g.warnings.front();
}

TEST(GroundFrame, TheUprightBoardInOpenCvsLeft01StandsOnAWallAboveTheFloor) {
    // left01.jpg: the board held upright in front of the camera. With OpenCV's focal length
    // for the set (as the studio's chessboard test gives it) and the camera's up, the board's
    // columns run within a few degrees of vertical and the floor lies below the camera.
    const std::string path = "/usr/share/doc/opencv-doc/examples/data/left01.jpg";
    const ChessboardSpec spec{9, 6, 0.025};
    const ChessboardView view = detect_chessboard(path, spec);
    const CalibrationResult r = chessboard_pose(view, spec, Intrinsics::centred(640, 480, 536.0));
    const CalibrationResult g = with_ground_from_up(r, up_from_camera(r, path), 1.0, path);
    const auto& w = g.world_points;
    const glm::dvec3 column = w[size_t(spec.cols * (spec.rows - 1))] - w[0];
    const glm::dvec3 row = w[size_t(spec.cols - 1)] - w[0];
    const double tilt = std::min(angle_deg(column, {0, 1, 0}), angle_deg(column, {0, -1, 0}));
    RecordProperty("column_tilt_deg", std::to_string(tilt));
    EXPECT_LT(tilt, 5.0);
    EXPECT_LT(std::abs(glm::normalize(row).y), std::sin(5.0 * std::numbers::pi / 180));
    for (const glm::dvec3& p : w) EXPECT_GT(p.y, 0.8);  // the board is well above the floor
    // The floor the studio's "Add ground plane" makes: below the camera, clear of the board.
    const Camera cam = g.camera();
    EXPECT_GT(cam.position().y, 0.8f);
    const ProxyFit floor = ground_proxy(cam);
    EXPECT_EQ(floor.proxy.transform.translation.y, 0.0f);
    EXPECT_EQ(floor.proxy.transform.rotation_deg.x, 0.0f);
    EXPECT_EQ(floor.proxy.transform.rotation_deg.z, 0.0f);
    // In the board's own frame the camera would look at the "floor" from 0.3 m.
    EXPECT_LT(r.camera().position().y, 0.6f);
}
