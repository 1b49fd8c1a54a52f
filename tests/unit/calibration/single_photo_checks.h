#pragma once
// Checks of the single-photo methods on a synthetic photo of the ground board with a known
// camera, shared by the unit tests (drawn photos) and the render suite (path-traced photos).
#include "calibration/correspondences.h"
#include "calibration/vanishing.h"
#include "synthetic_board.h"

namespace dp::test {

/// One photo of `board`: the detected corners and the camera that took it.
struct BoardPhoto {
    ChessboardView view;
    CameraSpec truth;
    int width = 0, height = 0;
    double focal() const { return truth.fx; }
    Intrinsics intrinsics() const { return Intrinsics::centred(width, height, truth.fx); }
    double camera_height() const { return truth.build(width, height).position().y; }
};

/// Photos of `board` from `eyes` (looking near its centre) at W x H with focal `f` pixels,
/// made by `make(board, camera, W, H)`.
template <class Make>
std::vector<BoardPhoto> board_photos(const GroundBoard& board,
                                     const std::vector<glm::dvec3>& eyes, int W, int H, double f,
                                     Make make) {
    std::vector<BoardPhoto> out;
    for (size_t i = 0; i < eyes.size(); ++i) {
        BoardPhoto p;
        p.truth = camera_at(eyes[i], glm::dvec3(0.05, 0, -0.03), W, H, f);
        p.width = W, p.height = H;
        p.view = detect_chessboard(make(board, p.truth, W, H), board.spec(),
                                   "view " + std::to_string(i));
        out.push_back(p);
    }
    return out;
}

/// Back-projects image points onto the ground (y = 0) of a calibrated camera.
inline std::vector<glm::dvec3> on_ground(const CalibrationResult& r,
                                         const std::vector<ImagePoint>& px) {
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

/// Chessboard, one photo: the pose with the focal length known, and the focal length too from
/// a tilted board.
inline void check_chessboard_one_photo(const GroundBoard& b, const BoardPhoto& p) {
    const auto truth = true_corners_for(p.view, b, p.truth);
    CalibrationResult r = chessboard_pose(p.view, b.spec(), p.intrinsics());
    EXPECT_LT(r.rms_px, 0.5);
    expect_matches(r, p.truth, r.world_points, truth);
    CalibrationResult s = chessboard_single(p.view, b.spec());
    expect_matches(s, p.truth, s.world_points, truth);
}

/// Rectangle: the board's four outer inner corners, with the focal length known and estimated
/// from the rectangle's perspective (four points: a looser 2% bound on the focal length).
inline void check_rectangle(const GroundBoard& b, const BoardPhoto& p) {
    const double w = (b.cols - 1) * b.square, h = (b.rows - 1) * b.square;
    const size_t idx[4] = {0, size_t(b.cols - 1), size_t(b.cols * b.rows - 1),
                           size_t((b.rows - 1) * b.cols)};
    std::vector<ImagePoint> corners;
    for (size_t j : idx) corners.push_back(p.view.corners[j]);
    std::vector<glm::dvec3> all = true_corners_for(p.view, b, p.truth), truth;
    for (size_t j : idx) truth.push_back(all[j]);
    CalibrationResult r =
        calibrate_rectangle(corners, w, h, p.width, p.height, p.intrinsics(), "");
    expect_matches(r, p.truth, r.world_points, truth);
    CalibrationResult e = calibrate_rectangle(corners, w, h, p.width, p.height, std::nullopt, "");
    expect_matches(e, p.truth, e.world_points, truth, 0.02);
}

/// Vanishing points: lines through the detected rows (world X) and columns (world Z), the
/// first corner as the origin and the first row's length (or the camera height) as the scale.
inline void check_vanishing(const GroundBoard& b, const BoardPhoto& p) {
    const ChessboardView& v = p.view;
    auto at = [&](int c, int r) { return v.corners[size_t(r * b.cols + c)]; };
    VanishingInput in;
    for (int r = 0; r < b.rows; ++r) in.x.push_back({at(0, r), at(b.cols - 1, r)});
    for (int c = 0; c < b.cols; ++c) in.z.push_back({at(c, 0), at(c, b.rows - 1)});
    in.origin = at(0, 0);
    in.distance = VanishingInput::Distance{at(0, 0), at(b.cols - 1, 0), (b.cols - 1) * b.square};
    CalibrationResult r = calibrate_vanishing(in, p.width, p.height, "");
    EXPECT_LT(r.rms_px, 0.5);
    EXPECT_LT(glm::length(on_ground(r, {at(0, 0)})[0]), 1e-9);  // the origin is where it was put
    const auto truth = true_corners_for(v, b, p.truth);
    expect_matches(r, p.truth, on_ground(r, v.corners), truth);
    VanishingInput h = in;
    h.distance.reset();
    h.camera_height = p.camera_height();
    CalibrationResult rh = calibrate_vanishing(h, p.width, p.height, "");
    expect_matches(rh, p.truth, on_ground(rh, v.corners), truth);
}

}  // namespace dp::test
