#pragma once
// Choosing the ground when the calibration target is not on it. A board or rectangle solved
// in its own frame makes its plane the ground (y = 0); hung on a wall it would make the wall
// the ground. These functions put the world's ground where it belongs: the direction of up
// comes from the camera (no roll against a vertical target) or from a clicked horizon, and the
// target keeps its place in the world.
#include <string>

#include <glm/glm.hpp>

#include "calibration/calibration.h"

namespace dp {

/// Up for a target on a vertical wall photographed without roll (the camera's X axis level),
/// in camera coordinates: the direction in the target's plane (the y = 0 plane of `r`'s world)
/// at right angles to the camera's X axis, signed towards the image's top (camera -Y). Throws
/// InputError naming `source` when the plane is seen nearly edge-on along the image's
/// horizontal (its normal within 6° of the camera's X axis), where that direction is lost.
glm::dvec3 up_from_camera(const CalibrationResult& r, const std::string& source);

/// The ground's normal from two points `a`, `b` (photo pixels) on the horizon, in camera
/// coordinates: the horizon is the image of the ground's vanishing line l, so n ∝ Kᵀ l, which
/// for undistorted points is the cross product of their two rays. The points are undistorted
/// through `k`'s lens first. The sign makes n point to the image's upper side of the line.
/// Throws InputError for points that are not finite, closer than 2 px, or on a line closer to
/// vertical than 10° from the image's vertical (which side is up is then ambiguous).
glm::dvec3 up_from_horizon(const Intrinsics& k, ImagePoint a, ImagePoint b,
                           const std::string& source);

/// `r` in a world whose +Y is `up_camera` (camera coordinates; normalised here) and whose
/// ground is y = 0: the origin lies on the ground straight below `r`'s world origin (a board's
/// first inner corner), which stands `origin_height_m` above it. World X is `r`'s X (the
/// board's rows) made level; where that runs nearly vertical, the camera's right made level.
/// The camera, the intrinsics and every reprojection are unchanged; world_points move into
/// the new frame. Of the uncertainty the camera-frame rotation covariance is kept and the
/// position covariance is turned into the new frame; the error of `up_camera` itself (the
/// no-roll assumption, the horizon clicks) and of the height are not included. Warnings are
/// kept, and added for a camera below the new ground and for a target plane more than 5° from
/// vertical in the new frame (a horizon that does not fit a wall, a leaning board). Throws
/// InputError for a zero or non-finite up or a negative or non-finite height.
CalibrationResult with_ground_from_up(const CalibrationResult& r, glm::dvec3 up_camera,
                                      double origin_height_m, const std::string& source);

}  // namespace dp
