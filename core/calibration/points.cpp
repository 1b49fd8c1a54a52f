// Camera from general world-image correspondences.
#include <cmath>
#include <cstdio>

#include <opencv2/calib3d.hpp>

#include "base/error.h"
#include "calibration/correspondences.h"
#include "calibration/cv_util.h"
#include "calibration/reprojection.h"

namespace dp {
namespace {

/// Spreads of the world points along their principal axes relative to the largest: {middle,
/// smallest}; the first is 0 for points on a line, the second for points in one plane.
std::pair<double, double> spreads(const std::vector<PointCorrespondence>& pts) {
    glm::dvec3 mean(0.0);
    for (const auto& p : pts) mean += p.world;
    mean /= double(pts.size());
    cv::Matx33d cov = cv::Matx33d::zeros();
    for (const auto& p : pts) {
        cv::Vec3d d(p.world.x - mean.x, p.world.y - mean.y, p.world.z - mean.z);
        cov += d * d.t();
    }
    cv::Vec3d eig;
    cv::eigen(cov, eig);
    if (!(eig[0] > 0)) return {0.0, 0.0};
    return {std::sqrt(std::max(0.0, eig[1]) / eig[0]), std::sqrt(std::max(0.0, eig[2]) / eig[0])};
}

/// Normalising similarity (Hartley): centroid to the origin, mean distance sqrt(dim).
template <int N>
cv::Matx<double, N + 1, N + 1> normaliser(const std::vector<cv::Vec<double, N>>& pts) {
    cv::Vec<double, N> mean = cv::Vec<double, N>::all(0);
    for (const auto& p : pts) mean += p;
    mean *= 1.0 / double(pts.size());
    double dist = 0;
    for (const auto& p : pts) dist += cv::norm(p - mean);
    dist /= double(pts.size());
    const double s = std::sqrt(double(N)) / std::max(dist, 1e-12);
    cv::Matx<double, N + 1, N + 1> T = cv::Matx<double, N + 1, N + 1>::eye() * s;
    for (int i = 0; i < N; ++i) T(i, N) = -s * mean[i];
    T(N, N) = 1;
    return T;
}

/// Intrinsics and pose from the 3x4 projection matrix of a normalised DLT.
Intrinsics dlt_intrinsics(const std::vector<PointCorrespondence>& pts, int width, int height) {
    std::vector<cv::Vec3d> X;
    std::vector<cv::Vec2d> x;
    for (const auto& p : pts) {
        X.emplace_back(p.world.x, p.world.y, p.world.z);
        x.emplace_back(p.image.x, p.image.y);
    }
    const cv::Matx44d T3 = normaliser<3>(X);
    const cv::Matx33d T2 = normaliser<2>(x);
    cv::Mat A = cv::Mat::zeros(int(2 * pts.size()), 12, CV_64F);
    for (size_t i = 0; i < pts.size(); ++i) {
        cv::Vec4d Xn = T3 * cv::Vec4d(X[i][0], X[i][1], X[i][2], 1);
        cv::Vec3d xn = T2 * cv::Vec3d(x[i][0], x[i][1], 1);
        double* r0 = A.ptr<double>(int(2 * i));
        double* r1 = A.ptr<double>(int(2 * i + 1));
        for (int j = 0; j < 4; ++j) {
            r0[4 + j] = -xn[2] * Xn[j];
            r0[8 + j] = xn[1] * Xn[j];
            r1[j] = xn[2] * Xn[j];
            r1[8 + j] = -xn[0] * Xn[j];
        }
    }
    cv::Mat w, u, vt;
    cv::SVDecomp(A, w, u, vt, cv::SVD::FULL_UV);
    cv::Matx34d Pn;
    for (int i = 0; i < 12; ++i) Pn(i / 4, i % 4) = vt.at<double>(11, i);
    const cv::Matx34d P = T2.inv() * Pn * T3;
    cv::Mat K, R, C;
    cv::decomposeProjectionMatrix(cv::Mat(P), K, R, C);
    K /= K.at<double>(2, 2);
    Intrinsics k;
    k.width = width, k.height = height;
    k.fx = std::abs(K.at<double>(0, 0));
    k.fy = std::abs(K.at<double>(1, 1));
    k.cx = K.at<double>(0, 2);
    k.cy = K.at<double>(1, 2);
    return k;
}

/// Throws InputError for a point far outside the photo: more than the photo's own size beyond
/// its border. A point a little outside is a known point just out of frame; one that far is a
/// slip (a wrong --size, a click on another picture), and OpenCV's solvers fail on such points
/// with their own assertion text.
void check_points_near_photo(const std::vector<ImagePoint>& points, int width, int height, const std::string& source) {
    for (size_t i = 0; i < points.size(); ++i) {
        const ImagePoint& p = points[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;  // check_image_points says so
        if (p.x >= -width && p.x <= 2.0 * width && p.y >= -height && p.y <= 2.0 * height) continue;
        char buf[240];
        std::snprintf(buf, sizeof buf,
                      "point %zu at (%.6g, %.6g) is far outside the %dx%d photo (more than its own size beyond its "
                      "border): image points are pixels of the photo",
                      i + 1, p.x, p.y, width, height);
        throw InputError(source, "points", buf);
    }
}

/// The camera from points that passed calibrate_points' checks; OpenCV may still throw.
CalibrationResult solve_points(const std::vector<PointCorrespondence>& points, const std::vector<ImagePoint>& image_points,
                               int image_width, int image_height, const std::optional<Intrinsics>& intrinsics,
                               const std::string& source, double click_sigma_px) {
    const bool known = intrinsics && intrinsics->fx != 0;
    std::vector<cv::Point3d> world;
    for (const auto& p : points) world.emplace_back(p.world.x, p.world.y, p.world.z);
    const std::vector<cv::Point2d> image = calib::to_cv(image_points);

    CalibrationResult r;
    Intrinsics k;
    if (known) {
        k = *intrinsics;
        check_focal(k.fx, source, "focal");
        check_focal(k.fy, source, "focal");
    } else {
        k = dlt_intrinsics(points, image_width, image_height);
        check_focal(k.fx, source, "focal");
        // Refine focal length, principal point and pose together (no distortion).
        cv::Mat K = cv::Mat(calib::camera_matrix(k)).clone(), dist = cv::Mat::zeros(1, 5, CV_64F);
        std::vector<cv::Point3f> wf(world.begin(), world.end());
        std::vector<cv::Point2f> imf(image.begin(), image.end());
        std::vector<cv::Mat> rv, tv;
        cv::calibrateCamera(std::vector<std::vector<cv::Point3f>>{wf},
                            std::vector<std::vector<cv::Point2f>>{imf},
                            cv::Size(image_width, image_height), K, dist, rv, tv,
                            cv::CALIB_USE_INTRINSIC_GUESS | cv::CALIB_ZERO_TANGENT_DIST |
                                cv::CALIB_FIX_K1 | cv::CALIB_FIX_K2 | cv::CALIB_FIX_K3);
        k.fx = K.at<double>(0, 0), k.fy = K.at<double>(1, 1);
        k.cx = K.at<double>(0, 2), k.cy = K.at<double>(1, 2);
        check_focal(k.fx, source, "focal");
        check_focal(k.fy, source, "focal");
    }
    k.width = image_width, k.height = image_height;
    cv::Vec3d rvec, tvec;
    const cv::Matx33d K = calib::camera_matrix(k);
    const std::vector<double> dist = calib::dist_coeffs(k.distortion);
    if (!cv::solvePnP(world, image, K, dist, rvec, tvec, false, cv::SOLVEPNP_SQPNP))
        throw InputError(source, "points", "the pose could not be solved from these points");
    cv::solvePnPRefineLM(world, image, K, dist, rvec, tvec);
    r.intrinsics = k;
    r.pose = calib::pose_from(rvec, tvec);
    r.rms_px = calib::rms_reprojection(world, image, k, r.pose);
    for (const auto& p : points) r.world_points.push_back(p.world);
    check_usable_fit(r, source, "points",
                     "a point is misplaced in the image or its world coordinates are wrong");
    r.uncertainty = calib::reprojection_uncertainty(
        r.world_points, image_points, k, r.pose,
        known ? calib::FreeIntrinsics::None : calib::FreeIntrinsics::All, click_sigma_px);
    add_quality_warnings(r);
    return r;
}

}  // namespace

CalibrationResult calibrate_points(const std::vector<PointCorrespondence>& points,
                                   int image_width, int image_height,
                                   const std::optional<Intrinsics>& intrinsics,
                                   const std::string& source, double click_sigma_px) {
    const bool known = intrinsics && intrinsics->fx != 0;
    std::vector<ImagePoint> image_points;
    for (const auto& p : points) {
        if (!std::isfinite(p.world.x) || !std::isfinite(p.world.y) || !std::isfinite(p.world.z))
            throw InputError(source, "points", "world coordinates must be finite");
        image_points.push_back(p.image);
    }
    // Near the photo first: one far-off click would also make the others look collinear.
    check_points_near_photo(image_points, image_width, image_height, source);
    check_image_points(image_points, 4, source, "points", "points");
    if (!known && points.size() < 6)
        throw InputError(source, "points",
                         "without a focal length, need at least 6 points (not all in one "
                         "plane), got " + std::to_string(points.size()) +
                             "; or give the focal length");
    const auto [line, flat] = spreads(points);
    if (line < 1e-3)
        throw InputError(source, "points",
                         "the world points are collinear (or coincide): they fix no pose");
    if (!known && flat < 0.02)
        throw InputError(source, "points",
                         "the world points lie (nearly) in one plane: that fixes the pose but "
                         "not the focal length; give the focal length, or add points off the "
                         "plane");
    try {
        return solve_points(points, image_points, image_width, image_height, intrinsics, source, click_sigma_px);
    } catch (const cv::Exception&) {
        // OpenCV's text names its own source lines and conditions; what it means for the user:
        throw InputError(source, "points",
                         "no camera fits these points: they are degenerate as the camera would see them "
                         "(a world point clicked far from where it is, or world and image points that "
                         "do not belong together)");
    }
}

}  // namespace dp
