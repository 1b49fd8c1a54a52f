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
    /// Scale: the camera's height above the ground, the distance between two ground points, or
    /// a vertical length (`a` its foot on the ground, `b` the point `metres` straight above).
    std::optional<double> camera_height;
    struct Distance {
        ImagePoint a, b;
        double metres = 0;
    };
    std::optional<Distance> distance;
    std::optional<Distance> vertical;
    /// Known focal length in pixels; otherwise it is estimated with the rotation.
    std::optional<double> focal_px;
    /// Estimate the principal point too. Only three directions whose vanishing points are all
    /// in finite reach constrain it; otherwise it stays at the image centre (a warning says so).
    bool free_principal_point = false;
    /// How precisely the segments and points were placed, pixels: the floor of the noise the
    /// stated uncertainty assumes (the fit's own residuals raise it).
    double click_sigma_px = 0.5;
};

/// Camera from vanishing lines, fitted jointly: one rotation (three orthogonal world axes),
/// the focal length unless given, and the principal point if freed, minimising the distance of
/// every segment's end points from the line through its midpoint and its axis' vanishing
/// point. The residuals are pixels at the end points, so a longer segment pins its direction
/// more tightly; a vanishing point at infinity (lines parallel in the image) is an ordinary
/// observation. World axes: Y up; X is the X segments' direction, signed to point right in
/// the image as far as it can (or, without X segments, Y x Z); Z = X x Y. The result carries
/// the uncertainty and quality warnings. Throws InputError (naming `source`) for fewer than
/// two segments per direction used, fewer than two directions, a focal length the lines do
/// not determine, directions that cannot be orthogonal, a fit too poor to use, an origin or
/// scale point above the horizon, or a scale <= 0.
CalibrationResult calibrate_vanishing(const VanishingInput& input, int width, int height,
                                      const std::string& source);

/// Least-squares vanishing point of two or more segments (homogeneous, w = 0 at infinity).
glm::dvec3 vanishing_point(const std::vector<LineSegment>& segments);

}  // namespace dp
