// Camera from the four corners of a known rectangle.
#include <cmath>
#include <cstdio>

#include <opencv2/calib3d.hpp>

#include "base/error.h"
#include "calibration/correspondences.h"
#include "calibration/cv_util.h"
#include "calibration/least_squares.h"
#include "calibration/reprojection.h"

namespace dp {
namespace {

double cross(const ImagePoint& a, const ImagePoint& b) { return a.x * b.y - a.y * b.x; }

/// Corners must form a convex quadrilateral with no three on a line.
void check_quad(const std::vector<ImagePoint>& c, const std::string& source) {
    check_image_points(c, 4, source, "corners", "rectangle corners");
    if (c.size() != 4)
        throw InputError(source, "corners",
                         "a rectangle has exactly 4 corners, got " + std::to_string(c.size()));
    double scale = 0;
    for (int i = 0; i < 4; ++i) scale = std::max(scale, glm::length(c[i] - c[(i + 1) % 4]));
    int sign = 0;
    for (int i = 0; i < 4; ++i) {
        const ImagePoint e0 = c[(i + 1) % 4] - c[i], e1 = c[(i + 2) % 4] - c[(i + 1) % 4];
        const double z = cross(e0, e1);
        if (std::abs(z) < 1e-3 * scale * scale)
            throw InputError(source, "corners",
                             "three of the rectangle corners are collinear (corners " +
                                 std::to_string(i) + ", " + std::to_string((i + 1) % 4) + ", " +
                                 std::to_string((i + 2) % 4) + ")");
        const int s = z > 0 ? 1 : -1;
        if (sign != 0 && s != sign)
            throw InputError(source, "corners",
                             "the corners do not go around the rectangle in order (the "
                             "quadrilateral they make is not convex)");
        sign = s;
    }
}

/// Focal length (pixels) from the homography of a rectangle, principal point `c`: the images
/// of the rectangle's two axes must be orthogonal and of equal length (Zhang's constraints
/// with square pixels). Returns 0 when the perspective is too weak to tell.
double focal_from_rectangle(const std::vector<ImagePoint>& corners, double width, double height,
                            const ImagePoint& c, double image_size) {
    std::vector<cv::Point2d> src = {{0, 0}, {width, 0}, {width, height}, {0, height}};
    std::vector<cv::Point2d> dst;
    for (const ImagePoint& p : corners) dst.emplace_back((p.x - c.x) / image_size,
                                                         (p.y - c.y) / image_size);
    cv::Mat H = cv::findHomography(src, dst);
    if (H.empty()) return 0;
    auto h = [&](int r, int col) { return H.at<double>(r, col); };
    // a * w + b = 0 with w = 1 / f^2 (f in units of image_size).
    const double a1 = h(0, 0) * h(0, 1) + h(1, 0) * h(1, 1), b1 = h(2, 0) * h(2, 1);
    const double a2 = h(0, 0) * h(0, 0) + h(1, 0) * h(1, 0) - h(0, 1) * h(0, 1) - h(1, 1) * h(1, 1);
    const double b2 = h(2, 0) * h(2, 0) - h(2, 1) * h(2, 1);
    const double w = -(a1 * b1 + a2 * b2) / (a1 * a1 + a2 * a2);
    if (!(w > 0)) return 0;
    const double f = 1.0 / std::sqrt(w);
    return f < 20.0 ? f * image_size : 0;  // beyond ~1 degree of field: no perspective left
}

/// Refuses corners that a rectangle of another aspect explains: with the focal length known
/// the four corners fix the aspect, so a mistyped size (or width and height swapped) shows
/// as a misfit the aspect's own fit removes.
void check_aspect(const std::vector<glm::dvec3>& world, const std::vector<ImagePoint>& image,
                  const Intrinsics& k, const Pose& pose, double width, double height,
                  double rms, double click_sigma, const std::string& source) {
    // Corners 2 and 3 lie `height` along the world direction from corner 1 to corner 2.
    const glm::dvec3 across = (world[2] - world[1]) / height;
    const calib::ReprojectionParams params{k, pose, calib::FreeIntrinsics::None};
    const calib::ResidualFunction f = [&](const std::vector<double>& x, std::vector<double>& r) {
        Intrinsics kk;
        Pose pp;
        params.apply(x, kk, pp);
        const double h = height * std::exp(x[6]);
        r.resize(8);
        for (size_t i = 0; i < 4; ++i) {
            const glm::dvec3 w = i < 2 ? world[i] : world[i] + (h - height) * across;
            const ImagePoint p = calib::project(kk, pp, w);
            r[2 * i] = p.x - image[i].x, r[2 * i + 1] = p.y - image[i].y;
        }
    };
    const calib::LeastSquaresResult fit =
        calib::levenberg_marquardt(f, std::vector<double>(7, 0.0));
    const double rms_free = std::sqrt(fit.cost / 4);
    const cv::Mat cov = calib::inverse_normal_matrix(calib::numeric_jacobian(f, fit.x));
    const double sigma = std::max(click_sigma, rms_free) * std::sqrt(cov.at<double>(6, 6));
    const double shift = fit.x[6];
    // Only an aspect that fits to click precision: a misplaced corner leaves a misfit anyway.
    const bool explained = rms_free < std::max(2.0, 3 * click_sigma) && rms_free < 0.5 * rms;
    if (!(explained && std::abs(shift) > 3 * sigma && std::abs(shift) > 0.02)) return;
    const double given = width / height, fitted = width / (height * std::exp(shift));
    char buf[512];
    std::snprintf(buf, sizeof(buf),
                  "the corners fit a rectangle of aspect %.2f (width / height, rms %.1f px) but "
                  "not the given %g x %g m (aspect %.2f, rms %.1f px)%s: check --width and "
                  "--height and the order of the corners",
                  fitted, rms_free, width, height, given, rms,
                  std::abs(fitted * given - 1) < 0.05
                      ? "; width and height swapped? --width is the edge from corner 1 to 2"
                      : "");
    throw InputError(source, "size", buf);
}

}  // namespace

CalibrationResult calibrate_rectangle(const std::vector<ImagePoint>& corners, double width,
                                      double height, int image_width, int image_height,
                                      const std::optional<Intrinsics>& intrinsics,
                                      const std::string& source, double click_sigma_px) {
    check_quad(corners, source);
    if (!(std::isfinite(width) && width > 0 && std::isfinite(height) && height > 0))
        throw InputError(source, "size", "the rectangle's width and height must be > 0 metres");
    if (image_width <= 0 || image_height <= 0)
        throw InputError(source, "size", "the image size must be positive");
    Intrinsics k;
    std::vector<std::string> warnings;
    const bool known = intrinsics && intrinsics->fx != 0;
    if (known) {
        k = *intrinsics;
        check_focal(k.fx, source, "focal");
        check_focal(k.fy, source, "focal");
    } else {
        k = Intrinsics::centred(image_width, image_height, 1.0);
        const double f = focal_from_rectangle(corners, width, height, ImagePoint(k.cx, k.cy),
                                              double(std::max(image_width, image_height)));
        if (f <= 0)
            throw InputError(source, "focal",
                             "the corners show too little perspective to tell the focal "
                             "length: the rectangle is seen too nearly face-on, or too small "
                             "for the precision of the clicks; give the focal length (or pick "
                             "a larger rectangle seen at an angle)");
        k.fx = k.fy = f;
        warnings.push_back("focal length estimated from the rectangle alone: check it against "
                           "the lens if you know it");
    }
    const std::vector<cv::Point3d> target = {
        {0, 0, 0}, {width, 0, 0}, {width, height, 0}, {0, height, 0}};
    const std::vector<cv::Point2d> image = calib::to_cv(corners);
    cv::Vec3d rvec, tvec;
    if (!cv::solvePnP(target, image, calib::camera_matrix(k), calib::dist_coeffs(k.distortion),
                      rvec, tvec, false, cv::SOLVEPNP_IPPE))
        throw InputError(source, "corners", "the rectangle's pose could not be solved");
    CalibrationResult r;
    glm::dmat3 M;
    r.pose = calib::planar_to_world(calib::pose_from(rvec, tvec), &M);
    for (const cv::Point3d& p : target) r.world_points.push_back(M * glm::dvec3(p.x, p.y, p.z));
    // IPPE is exact only for exact corners: the least-squares camera (with the focal length
    // where it is estimated) is the one the uncertainty describes.
    const auto free = known ? calib::FreeIntrinsics::None : calib::FreeIntrinsics::Focal;
    r.rms_px = calib::refine_reprojection(r.world_points, corners, k, r.pose, free);
    r.intrinsics = k;
    if (known && r.rms_px > 2.0)
        check_aspect(r.world_points, corners, k, r.pose, width, height, r.rms_px, click_sigma_px,
                     source);
    check_usable_fit(r, source, "corners",
                     "a corner is misplaced, the corners are not in order around the rectangle, "
                     "or its size or the focal length is wrong");
    r.uncertainty = calib::reprojection_uncertainty(r.world_points, corners, k, r.pose, free,
                                                    click_sigma_px);
    r.warnings = warnings;
    add_quality_warnings(r);
    return r;
}

}  // namespace dp
