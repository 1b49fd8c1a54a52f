#include "calibration/calibration.h"

#include <cmath>
#include <numbers>

#include "base/error.h"

namespace dp {

Intrinsics Intrinsics::centred(int width, int height, double focal_px) {
    Intrinsics k;
    k.width = width;
    k.height = height;
    k.fx = k.fy = focal_px;
    k.cx = 0.5 * (width - 1);
    k.cy = 0.5 * (height - 1);
    return k;
}

double Intrinsics::hfov_deg() const {
    return 2.0 * std::atan(0.5 * width / fx) * 180.0 / std::numbers::pi;
}

CameraSpec CalibrationResult::camera_spec() const {
    CameraSpec c;
    c.model = CameraSpec::Model::Intrinsics;
    c.fx = float(intrinsics.fx);
    c.fy = float(intrinsics.fy);
    c.cx = float(intrinsics.cx);
    c.cy = float(intrinsics.cy);
    c.distortion = intrinsics.distortion;
    c.rotation = glm::mat3(pose.R);
    c.translation = vec3(pose.t);
    return c;
}

Camera CalibrationResult::camera() const {
    return camera_spec().build(intrinsics.width, intrinsics.height);
}

void check_focal(double focal_px, const std::string& source, const std::string& field) {
    if (!(std::isfinite(focal_px) && focal_px > 0))
        throw InputError(source, field,
                         "the focal length must be > 0 pixels (got " + std::to_string(focal_px) +
                             ")");
}

void check_image_points(const std::vector<ImagePoint>& points, size_t min_count,
                        const std::string& source, const std::string& field,
                        const std::string& what) {
    if (points.size() < min_count)
        throw InputError(source, field,
                         "need at least " + std::to_string(min_count) + " " + what + ", got " +
                             std::to_string(points.size()));
    glm::dvec2 mean(0.0);
    for (const ImagePoint& p : points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y))
            throw InputError(source, field, what + " must be finite pixel coordinates");
        mean += p;
    }
    mean /= double(points.size());
    // Spread along the principal axes of the point cloud: collinear points have no spread
    // across their line (relative to the spread along it).
    double sxx = 0, sxy = 0, syy = 0;
    for (const ImagePoint& p : points) {
        glm::dvec2 d = p - mean;
        sxx += d.x * d.x, sxy += d.x * d.y, syy += d.y * d.y;
    }
    const double tr = sxx + syy, det = sxx * syy - sxy * sxy;
    const double disc = std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
    const double major = 0.5 * tr + disc, minor = std::max(0.0, 0.5 * tr - disc);
    if (major <= 0 || std::sqrt(minor / major) < 1e-3)
        throw InputError(source, field,
                         "the " + what + " are collinear (or coincide): they do not span a plane "
                         "in the image");
}

}  // namespace dp
