#include "calibration/cv_util.h"

#include <cmath>

#include <opencv2/calib3d.hpp>

namespace dp::calib {

cv::Matx33d to_cv(const glm::dmat3& m) {
    cv::Matx33d r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r(i, j) = m[j][i];  // glm: [column][row]
    return r;
}

glm::dmat3 from_cv(const cv::Matx33d& m) {
    glm::dmat3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r[j][i] = m(i, j);
    return r;
}

cv::Matx33d camera_matrix(const Intrinsics& k) {
    return cv::Matx33d(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
}

std::vector<double> dist_coeffs(const Distortion& d) {
    return {d.k1, d.k2, d.p1, d.p2, d.k3};
}

Distortion distortion_from(const cv::Mat& coeffs) {
    cv::Mat c;
    coeffs.convertTo(c, CV_64F);
    c = c.reshape(1, 1);
    auto at = [&](int i) { return i < c.cols ? float(c.at<double>(0, i)) : 0.0f; };
    return Distortion{at(0), at(1), at(2), at(3), at(4)};
}

Pose pose_from(const cv::Vec3d& rvec, const cv::Vec3d& tvec) {
    cv::Matx33d R;
    cv::Rodrigues(rvec, R);
    return Pose{from_cv(R), glm::dvec3(tvec[0], tvec[1], tvec[2])};
}

void to_rvec_tvec(const Pose& pose, cv::Vec3d& rvec, cv::Vec3d& tvec) {
    cv::Rodrigues(to_cv(pose.R), rvec);
    tvec = cv::Vec3d(pose.t.x, pose.t.y, pose.t.z);
}

Pose planar_to_world(const Pose& target_pose, glm::dmat3* target_to_world) {
    // The target's normal is its +Z or -Z; world +Y becomes whichever faces the camera, and a
    // proper rotation keeps target X as world X.
    const glm::dvec3 c = target_pose.position();
    const glm::dmat3 M = c.z < 0 ? from_rows({1, 0, 0}, {0, 0, -1}, {0, 1, 0})
                                 : from_rows({1, 0, 0}, {0, 0, 1}, {0, -1, 0});
    if (target_to_world) *target_to_world = M;
    // x_cam = R_t x_target + t = R_t M^T x_world + t.
    return Pose{target_pose.R * glm::transpose(M), target_pose.t};
}

double rms_reprojection(const std::vector<cv::Point3d>& world,
                        const std::vector<cv::Point2d>& image, const Intrinsics& k,
                        const Pose& pose) {
    if (world.empty()) return 0;
    cv::Vec3d rvec, tvec;
    to_rvec_tvec(pose, rvec, tvec);
    std::vector<cv::Point2d> projected;
    cv::projectPoints(world, rvec, tvec, camera_matrix(k), dist_coeffs(k.distortion), projected);
    double sum = 0;
    for (size_t i = 0; i < world.size(); ++i) {
        cv::Point2d d = projected[i] - image[i];
        sum += d.dot(d);
    }
    return std::sqrt(sum / double(world.size()));
}

std::vector<cv::Point2d> to_cv(const std::vector<ImagePoint>& points) {
    std::vector<cv::Point2d> out;
    out.reserve(points.size());
    for (const ImagePoint& p : points) out.emplace_back(p.x, p.y);
    return out;
}

}  // namespace dp::calib
