#pragma once
// Camera from user-picked correspondences: the four corners of a known rectangle (a sheet of
// paper, a floor tile) or six or more points with known world coordinates.
#include <optional>
#include <string>
#include <vector>

#include "calibration/calibration.h"

namespace dp {

/// Pose of a `width` x `height` metre rectangle from its corners in the image, given in order
/// around it: corner 0 -> 1 runs along `width`, 1 -> 2 along `height`. The rectangle lies on
/// the ground (y = 0) with corner 0 at the origin and edge 0 -> 1 along world +X.
/// `intrinsics` with fx == 0 (or nullopt): the focal length is estimated from the rectangle's
/// perspective with the principal point at the image centre, which needs the rectangle seen
/// at an angle. The pose (and focal length) are refined on the reprojection error; the
/// uncertainty assumes corners clicked to `click_sigma_px` or the fit's own residuals, whichever
/// is larger. Throws InputError (naming `source`) for fewer than four corners, three
/// collinear corners, corners not in order around the rectangle, a size <= 0, a focal length
/// <= 0, corners that fit a rectangle of another aspect than `width` x `height`, or a fit too
/// poor to use (a misplaced corner).
CalibrationResult calibrate_rectangle(const std::vector<ImagePoint>& corners, double width,
                                      double height, int image_width, int image_height,
                                      const std::optional<Intrinsics>& intrinsics,
                                      const std::string& source, double click_sigma_px = 0.5);

struct PointCorrespondence {
    glm::dvec3 world;
    ImagePoint image;
};

/// Pose (and, without `intrinsics`, the focal length and principal point) from world-image
/// correspondences in the project's world frame. With intrinsics: four or more points
/// (solvePnP). Without: six or more points not all in one plane (DLT, then refined).
/// The uncertainty assumes image points clicked to `click_sigma_px` or the fit's own
/// residuals, whichever is larger. Throws InputError for too few points, collinear image
/// points, coplanar world points where the intrinsics are unknown, or a fit too poor to use.
CalibrationResult calibrate_points(const std::vector<PointCorrespondence>& points,
                                   int image_width, int image_height,
                                   const std::optional<Intrinsics>& intrinsics,
                                   const std::string& source, double click_sigma_px = 0.5);

}  // namespace dp
