#pragma once
// OpenCV <-> glm conversions and helpers shared by the calibration methods (internal).
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "base/error.h"
#include "calibration/calibration.h"

namespace dp::calib {

/// A 3x3 matrix given row by row (glm stores columns).
inline glm::dmat3 from_rows(const glm::dvec3& r0, const glm::dvec3& r1, const glm::dvec3& r2) {
    return glm::transpose(glm::dmat3(r0, r1, r2));
}

cv::Matx33d to_cv(const glm::dmat3& m);
glm::dmat3 from_cv(const cv::Matx33d& m);
cv::Matx33d camera_matrix(const Intrinsics& k);
/// [k1, k2, p1, p2, k3].
std::vector<double> dist_coeffs(const Distortion& d);
Distortion distortion_from(const cv::Mat& coeffs);

/// Pose from OpenCV's Rodrigues vector and translation.
Pose pose_from(const cv::Vec3d& rvec, const cv::Vec3d& tvec);
void to_rvec_tvec(const Pose& pose, cv::Vec3d& rvec, cv::Vec3d& tvec);

/// A planar target solved in its own frame (points (x, y, 0)) moved into the world frame:
/// the plane becomes y = 0 with the camera on the +Y side. `target_to_world` receives the
/// rotation that maps target coordinates to world coordinates.
Pose planar_to_world(const Pose& target_pose, glm::dmat3* target_to_world = nullptr);

/// RMS distance in pixels between the projections of `world` and `image`.
double rms_reprojection(const std::vector<cv::Point3d>& world,
                        const std::vector<cv::Point2d>& image, const Intrinsics& k,
                        const Pose& pose);

std::vector<cv::Point2d> to_cv(const std::vector<ImagePoint>& points);

/// Runs `work`, turning an OpenCV assertion (cv::Exception: raw source text and an internal
/// condition) into an InputError naming `source` and saying what failed in a person's words.
template <class F>
auto translating_cv_errors(const std::string& source, const std::string& what_failed, F&& work) {
    try {
        return std::forward<F>(work)();
    } catch (const cv::Exception& e) {
        throw InputError(source, "", what_failed + " failed (OpenCV: " + e.err.substr(0, 160) + ")");
    }
}

}  // namespace dp::calib
