#pragma once
// A camera from the photo's own lines: segments found by OpenCV's line segment detector,
// grouped by the vanishing point they run to (sequential RANSAC over segments, as in the
// vanishing-point literature), the groups matched to three orthogonal world directions, then
// the joint solver of calibrate_vanishing with its uncertainty.
#include <optional>
#include <string>
#include <vector>

#include "calibration/vanishing.h"
#include "image/image.h"

namespace dp {

/// Line segments of `photo` (linear RGB) found by OpenCV's line segment detector (LSD, von Gioi
/// et al.) on its sRGB-encoded luminance, at least `min_length_px` long, longest first.
std::vector<LineSegment> detect_line_segments(const Image& photo, double min_length_px);

/// Segments that run to one vanishing point.
struct VanishingCluster {
    glm::dvec3 vp{0.0};        ///< homogeneous, w = 0 at infinity (lines parallel in the image)
    std::vector<int> members;  ///< indices into the segments
    double support = 0;        ///< their total length, pixels
};

/// Vanishing points by sequential RANSAC: a segment supports a point when the line from its
/// midpoint to the point is within `max_angle_deg` of the segment's own direction (longer
/// segments count more); the best point is refined by least squares over its segments, which
/// are then taken out, up to `max_clusters` points, each held by 3 segments or more and by at
/// least 4% of all segments' length. Deterministic for a given `seed`.
std::vector<VanishingCluster> find_vanishing_clusters(const std::vector<LineSegment>& segments, int width,
                                                      int height, unsigned seed = 1, int max_clusters = 6,
                                                      double max_angle_deg = 1.0);

/// The segments proposed for each world direction (X and Z on the ground, Y vertical, as
/// VanishingInput has them) and why the choice was made.
struct LineProposal {
    std::vector<LineSegment> axis[3];   ///< X, Y, Z; an empty list: that direction is not used
    std::vector<LineSegment> other;     ///< detected but in no chosen direction
    std::vector<std::string> notes;     ///< what was found and chosen, for the user
};

/// Matches clusters to orthogonal directions: of the strongest clusters, the pair or triple
/// whose vanishing points agree with one focal length (principal point at the centre, a field
/// of view of 10 to 150 degrees) and hold the most length. A cluster is the vertical when its
/// segments are steep in the image and its vanishing point far (beyond twice the image's
/// size, as for a camera within about 25 degrees of level); else the two strongest
/// orthogonal horizontal directions are the ground's. `focal_px`, where known, replaces the
/// focal length the pairs must agree on. Every such reading, best first, at most
/// `max_proposals` (one, with no axes, where none fits).
std::vector<LineProposal> propose_axes_ranked(const std::vector<LineSegment>& segments,
                                             const std::vector<VanishingCluster>& clusters, int width, int height,
                                             std::optional<double> focal_px, size_t max_proposals);

/// What `calibrate auto` and the studio's Detect Lines start from.
struct AutoLinesOptions {
    double min_length_fraction = 0.025;  ///< of the image's diagonal
    std::optional<double> focal_px;      ///< a known focal length (EXIF), else estimated
    double camera_height = 1.5;          ///< metres: the scale, where nothing else gives one
    unsigned seed = 1;
};

/// The detected lines, the proposal, and the camera where the proposal determines one.
struct AutoLinesResult {
    std::vector<LineSegment> segments;
    std::vector<VanishingCluster> clusters;
    LineProposal proposal;
    std::optional<CalibrationResult> camera;
    ImagePoint origin{0.0};  ///< the image of the world origin the camera was placed by
    std::string failure;     ///< why there is no camera: what the user must add
};

/// Detects, clusters, proposes and solves: the first of the (up to eight) readings
/// propose_axes_ranked gives that the solver can place. Never throws for what the photo lacks
/// (that is in `failure`); the origin is put on the ground below the image centre.
AutoLinesResult calibrate_from_lines(const Image& photo, const AutoLinesOptions& options, const std::string& source);

/// The VanishingInput for a proposal: its segments, `origin` and the camera height as scale.
VanishingInput vanishing_input(const LineProposal& p, ImagePoint origin, double camera_height,
                               std::optional<double> focal_px);

}  // namespace dp
