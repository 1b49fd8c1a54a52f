#pragma once
// Camera from vanishing points of user-drawn line segments (as fSpy does): two or three
// orthogonal world directions, the image of the world origin on the ground and one known
// length for scale.
#include <optional>
#include <string>
#include <vector>

#include "calibration/calibration.h"

namespace dp {

struct LineSegment {
    ImagePoint a, b;
};

/// Segments are grouped by the world axis they are parallel to: X and Z lie on the ground,
/// Y is vertical. Give two or more segments for at least two axes.
struct VanishingInput {
    std::vector<LineSegment> x, y, z;
    /// Image of the world origin, a point on the ground.
    ImagePoint origin{0.0};
    /// Scale: the camera's height above the ground, or the distance between two ground points.
    std::optional<double> camera_height;
    struct Distance {
        ImagePoint a, b;
        double metres = 0;
    };
    std::optional<Distance> distance;
    /// Known focal length in pixels; otherwise it comes from two orthogonal vanishing points.
    std::optional<double> focal_px;
};

/// Intrinsics (principal point at the image centre, or the orthocentre of three vanishing
/// points) and pose. World axes: Y up; X is the X segments' direction, signed to point right in
/// the image as far as it can (or, without X segments, Y x Z); Z = X x Y. Throws InputError
/// (naming `source`) for fewer than two segments per direction used, fewer than two
/// directions, parallel segments (vanishing point at infinity), directions that cannot be
/// orthogonal (focal length squared <= 0), an origin or scale point above the horizon or a
/// scale <= 0.
CalibrationResult calibrate_vanishing(const VanishingInput& input, int width, int height,
                                      const std::string& source);

/// Least-squares vanishing point of two or more segments (homogeneous, w = 0 at infinity).
glm::dvec3 vanishing_point(const std::vector<LineSegment>& segments);

}  // namespace dp
