#include "calibration/calibration.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
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

CalibrationResult scaled_to(const CalibrationResult& r, int width, int height,
                            const std::string& file, const std::string& field) {
    const Intrinsics& k = r.intrinsics;
    if (k.width == width && k.height == height) return r;
    const double sx = double(width) / k.width, sy = double(height) / k.height;
    if (!(std::abs(sx / sy - 1) <= 0.01))
        throw InputError(file, field,
                         "the photo is " + std::to_string(width) + "x" + std::to_string(height) +
                             " but the camera was matched on a " + std::to_string(k.width) +
                             "x" + std::to_string(k.height) +
                             " image: the aspect ratios differ");
    CalibrationResult out = r;
    Intrinsics& s = out.intrinsics;
    s.fx *= sx, s.fy *= sy;
    s.cx = (k.cx + 0.5) * sx - 0.5, s.cy = (k.cy + 0.5) * sy - 0.5;
    s.width = width, s.height = height;
    return out;
}

Camera CalibrationResult::camera() const {
    return camera_spec().build(intrinsics.width, intrinsics.height);
}

namespace {

/// Decimals that show `sigma` with two significant digits.
int decimals_for(double sigma) {
    if (!(sigma > 0) || !std::isfinite(sigma)) return 1;
    return std::clamp(1 - int(std::floor(std::log10(sigma))), 0, 6);
}

std::string format(const char* fmt, auto... args) {
    char buf[256];
    std::snprintf(buf, sizeof(buf), fmt, args...);
    return buf;
}

/// "495 ± 12" with the value to the uncertainty's precision.
std::string plus_minus(double value, double sigma) {
    const int d = decimals_for(sigma);
    return format("%.*f ± %.*f", d, value, d, sigma);
}

}  // namespace

void add_quality_warnings(CalibrationResult& r, double rms_limit_px) {
    const Intrinsics& k = r.intrinsics;
    const Uncertainty& u = r.uncertainty;
    if (u.known && u.focal_free && !(u.fx <= 0.05 * k.fx))
        r.warnings.push_back(
            "the focal length is uncertain: fx " + plus_minus(k.fx, u.fx) + " px (" +
            format("%.0f", 100 * u.fx / k.fx) +
            " %, more than 5 %); give the focal length if it is known (EXIF, the lens), or "
            "input that shows more perspective (longer lines farther apart, a target seen at a "
            "steeper angle)");
    if (u.known && u.focal_free && k.width > 0 && k.hfov_deg() > 120)
        r.warnings.push_back(format("the field of view found, %.0f° across, is wider than almost "
                                    "any lens but a fisheye: a point is probably misplaced",
                                    k.hfov_deg()));
    if (k.width > 0 && k.height > 0 &&
        (std::abs(k.cx - 0.5 * (k.width - 1)) > 0.25 * k.width ||
         std::abs(k.cy - 0.5 * (k.height - 1)) > 0.25 * k.height))
        r.warnings.push_back(format("the principal point (%.0f, %.0f) is outside the middle half "
                                    "of the %dx%d image: photos are rarely cropped that much, so "
                                    "the camera is probably wrong; hold the principal point at "
                                    "the centre or give the focal length",
                                    k.cx, k.cy, k.width, k.height));
    if (r.rms_px > rms_limit_px)
        r.warnings.push_back(format("the input fits the camera poorly (rms %.2f px, more than "
                                    "%.0f px): a point may be misplaced or a line in the wrong "
                                    "group",
                                    r.rms_px, rms_limit_px));
}

void check_usable_fit(const CalibrationResult& r, const std::string& source,
                      const std::string& field, const std::string& what) {
    const Intrinsics& k = r.intrinsics;
    const double limit = std::max(5.0, 0.005 * std::hypot(k.width, k.height));
    if (r.rms_px > limit)
        throw InputError(source, field,
                         format("the input does not fit one camera (rms %.1f px; more than "
                                "%.1f px is not a camera to use): ",
                                r.rms_px, limit) +
                             what);
}

std::string uncertainty_text(const CalibrationResult& r) {
    const Uncertainty& u = r.uncertainty;
    if (!u.known) return "n/a";
    const Intrinsics& k = r.intrinsics;
    std::string s;
    if (u.focal_free) {
        s = "fx " + plus_minus(k.fx, u.fx) + " px (" + format("%.1f", 100 * u.fx / k.fx) + " %)";
        if (k.fy != k.fx) s += ", fy " + plus_minus(k.fy, u.fy) + " px";
    } else {
        s = "focal length given";
    }
    if (u.principal_free)
        s += ", cx " + plus_minus(k.cx, u.cx) + " cy " + plus_minus(k.cy, u.cy) + " px";
    else
        s += ", principal point held";
    s += ", rotation ± " + format("%.*f", decimals_for(u.rotation_deg), u.rotation_deg) + "°";
    s += ", position ± " + format("%.*f", decimals_for(u.position_m), u.position_m) + " m";
    return s;
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
