#pragma once
// Camera from chessboard photographs: several photos give intrinsics, distortion and one pose
// per photo (cv::calibrateCamera); a single photo gives the pose for known intrinsics
// (cv::solvePnP). The board's plane is the ground (y = 0), its first inner corner the origin,
// its columns world +X and the square size the metric scale.
#include <string>
#include <vector>

#include "calibration/calibration.h"
#include "image/image.h"

namespace dp {

/// Inner corners (not squares) of the board: OpenCV's 9x6 sample board has 10x7 squares.
struct ChessboardSpec {
    int cols = 9;
    int rows = 6;
    double square_size = 0.025;  ///< metres
};

/// The inner corners found in one photo, row by row.
struct ChessboardView {
    std::string source;  ///< file name, for messages
    int width = 0, height = 0;
    std::vector<ImagePoint> corners;
};

/// Finds the inner corners with sub-pixel refinement. The image is linear (as load_image
/// returns it); exposure does not matter. Throws InputError naming `source` when the board is
/// not found or the spec is invalid.
ChessboardView detect_chessboard(const Image& image, const ChessboardSpec& spec,
                                 const std::string& source);
/// Loads `path` with load_image and detects the board.
ChessboardView detect_chessboard(const std::string& path, const ChessboardSpec& spec);

/// Corners in the board's own frame: (col * size, row * size, 0).
std::vector<glm::dvec3> chessboard_target_points(const ChessboardSpec& spec);

/// A calibration from several photos of the board.
struct ChessboardCalibration {
    /// Intrinsics with the pose of the first photo, and the RMS error over all photos.
    CalibrationResult result;
    /// Per photo: the pose in that photo's board frame, its RMS error, the corners in world
    /// space (board on y = 0) and the pose's uncertainty (the lens' included).
    std::vector<Pose> poses;
    std::vector<double> view_rms_px;
    std::vector<std::vector<glm::dvec3>> world_corners;
    std::vector<Uncertainty> view_uncertainty;
    /// Per photo: the earlier photo it duplicates (left out of the lens fit), or -1.
    std::vector<int> duplicate_of;

    /// `result` with photo `i`'s pose, corners and uncertainty.
    CalibrationResult for_view(size_t i) const;
};

/// Calibrates intrinsics and distortion (k1 k2 p1 p2 k3) from two or more views (use ten or
/// more, tilted in different directions, for a good estimate). A photo whose corners lie
/// where an earlier one's do (the same photo twice) is left out of the lens fit with a
/// warning and gets its pose with the lens found. Throws InputError for fewer than two
/// different views or views of different sizes.
ChessboardCalibration calibrate_chessboard(const std::vector<ChessboardView>& views,
                                           const ChessboardSpec& spec);

/// Every photo's pose as JSON: the lens, and per photo its file, RMS error, world-to-camera
/// rotation (rows) and translation, camera position, uncertainty and its board corners as
/// world-image pairs (the `calibrate points` format).
std::string chessboard_poses_json(const ChessboardCalibration& c,
                                  const std::vector<ChessboardView>& views,
                                  const ChessboardSpec& spec);

/// Pose from one photo with known intrinsics (from EXIF, a given focal length or an earlier
/// calibration); the board frame is the world frame.
CalibrationResult chessboard_pose(const ChessboardView& view, const ChessboardSpec& spec,
                                  const Intrinsics& intrinsics);

/// Focal length and pose from one photo, with the principal point at the image centre and no
/// distortion. Needs the board tilted against the image plane; a board seen face-on leaves
/// the focal length undetermined (a warning says so).
CalibrationResult chessboard_single(const ChessboardView& view, const ChessboardSpec& spec);

}  // namespace dp
