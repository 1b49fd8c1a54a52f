#include "calibration/reprojection.h"

#include <cmath>
#include <numbers>

#include "calibration/least_squares.h"

namespace dp::calib {

namespace {

double image_size(const Intrinsics& k) { return double(std::max({k.width, k.height, 1})); }

ResidualFunction residuals_of(const std::vector<glm::dvec3>& world,
                              const std::vector<ImagePoint>& image,
                              const ReprojectionParams& params) {
    return [&world, &image, params](const std::vector<double>& x, std::vector<double>& r) {
        Intrinsics k;
        Pose pose;
        params.apply(x, k, pose);
        r.resize(2 * world.size());
        for (size_t i = 0; i < world.size(); ++i) {
            const ImagePoint p = project(k, pose, world[i]);
            r[2 * i] = p.x - image[i].x;
            r[2 * i + 1] = p.y - image[i].y;
        }
    };
}

}  // namespace

ImagePoint project(const Intrinsics& k, const Pose& pose, const glm::dvec3& world) {
    const glm::dvec3 c = pose.R * world + pose.t;
    const double x = c.x / c.z, y = c.y / c.z;
    const Distortion& d = k.distortion;
    const double r2 = x * x + y * y;
    const double radial = 1 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3));
    const double xd = x * radial + 2 * d.p1 * x * y + d.p2 * (r2 + 2 * x * x);
    const double yd = y * radial + d.p1 * (r2 + 2 * y * y) + 2 * d.p2 * x * y;
    return ImagePoint(k.fx * xd + k.cx, k.fy * yd + k.cy);
}

int ReprojectionParams::count() const {
    return 6 + (free == FreeIntrinsics::Focal ? 1 : free == FreeIntrinsics::All ? 4 : 0);
}

void ReprojectionParams::apply(const std::vector<double>& x, Intrinsics& k, Pose& pose) const {
    pose.R = rotation_exp(glm::dvec3(x[0], x[1], x[2])) * pose0.R;
    const double t_scale = std::max(glm::length(pose0.t), 1e-9);
    pose.t = pose0.t + t_scale * glm::dvec3(x[3], x[4], x[5]);
    k = k0;
    if (free == FreeIntrinsics::Focal) {
        k.fx = k0.fx * std::exp(x[6]);
        k.fy = k0.fy * std::exp(x[6]);
    } else if (free == FreeIntrinsics::All) {
        k.fx = k0.fx * std::exp(x[6]);
        k.fy = k0.fy * std::exp(x[7]);
        k.cx = k0.cx + image_size(k0) * x[8];
        k.cy = k0.cy + image_size(k0) * x[9];
    }
}

double refine_reprojection(const std::vector<glm::dvec3>& world,
                           const std::vector<ImagePoint>& image, Intrinsics& k, Pose& pose,
                           FreeIntrinsics free) {
    const ReprojectionParams params{k, pose, free};
    const LeastSquaresResult fit = levenberg_marquardt(
        residuals_of(world, image, params), std::vector<double>(size_t(params.count()), 0.0));
    params.apply(fit.x, k, pose);
    return world.empty() ? 0.0 : std::sqrt(fit.cost / double(world.size()));
}

void pose_uncertainty(const cv::Mat& cov, const std::vector<double>& x0,
                      const std::function<glm::dvec3(const std::vector<double>&)>& position,
                      Uncertainty& u, const glm::dmat3& extra_position_cov) {
    glm::dmat3 rot(0.0);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) rot[j][i] = cov.at<double>(i, j);
    u.rotation_cov = rot;
    u.rotation_deg = std::sqrt(std::max(0.0, rot[0][0] + rot[1][1] + rot[2][2])) * 180.0 /
                     std::numbers::pi;
    // The camera centre's Jacobian by central differences, then J cov J^T.
    const int p = int(x0.size());
    cv::Mat Jc(3, p, CV_64F);
    std::vector<double> x = x0;
    for (int j = 0; j < p; ++j) {
        const double h = 1e-6 * std::max(1.0, std::abs(x0[size_t(j)]));
        x[size_t(j)] = x0[size_t(j)] + h;
        const glm::dvec3 a = position(x);
        x[size_t(j)] = x0[size_t(j)] - h;
        const glm::dvec3 b = position(x);
        x[size_t(j)] = x0[size_t(j)];
        for (int i = 0; i < 3; ++i) Jc.at<double>(i, j) = (a[i] - b[i]) / (2 * h);
    }
    const cv::Mat C = Jc * cov * Jc.t();
    glm::dmat3 pos = extra_position_cov;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) pos[j][i] += C.at<double>(i, j);
    u.position_cov = pos;
    u.position_m = std::sqrt(std::max(0.0, pos[0][0] + pos[1][1] + pos[2][2]));
}

Uncertainty reprojection_uncertainty(const std::vector<glm::dvec3>& world,
                                     const std::vector<ImagePoint>& image, const Intrinsics& k,
                                     const Pose& pose, FreeIntrinsics free,
                                     double prior_sigma_px, const cv::Mat& intrinsics_cov) {
    const ReprojectionParams params{k, pose, free};
    const ResidualFunction f = residuals_of(world, image, params);
    const std::vector<double> x0(size_t(params.count()), 0.0);
    std::vector<double> r;
    f(x0, r);
    double cost = 0;
    for (double v : r) cost += v * v;
    const cv::Mat J = numeric_jacobian(f, x0);
    const double sigma = residual_sigma(cost, int(r.size()), params.count(), prior_sigma_px);
    cv::Mat cov = sigma * sigma * inverse_normal_matrix(J);

    if (!intrinsics_cov.empty() && free == FreeIntrinsics::None) {
        // Pose sensitivity to the intrinsics, S = (Jp^T Jp)^-1 Jp^T Jk: their spread moves
        // the pose as S cov_k S^T on top of this photo's own noise.
        const ReprojectionParams all{k, pose, FreeIntrinsics::All};
        const cv::Mat Ja = numeric_jacobian(residuals_of(world, image, all),
                                            std::vector<double>(10, 0.0));
        cv::Mat Jk = Ja.colRange(6, 10).clone();
        // Columns are per log focal / per image size: back to pixels.
        const double fx = k.fx, fy = k.fy, s = image_size(k);
        Jk.col(0) /= fx, Jk.col(1) /= fy, Jk.col(2) /= s, Jk.col(3) /= s;
        const cv::Mat S = inverse_normal_matrix(J) * J.t() * Jk;
        cov += S * intrinsics_cov * S.t();
    }

    Uncertainty u;
    u.known = true;
    u.point_sigma_px = sigma;
    u.focal_free = free != FreeIntrinsics::None;
    u.principal_free = free == FreeIntrinsics::All;
    if (free == FreeIntrinsics::Focal) {
        u.fx = k.fx * std::sqrt(cov.at<double>(6, 6));
        u.fy = k.fy * std::sqrt(cov.at<double>(6, 6));
    } else if (free == FreeIntrinsics::All) {
        u.fx = k.fx * std::sqrt(cov.at<double>(6, 6));
        u.fy = k.fy * std::sqrt(cov.at<double>(7, 7));
        u.cx = image_size(k) * std::sqrt(cov.at<double>(8, 8));
        u.cy = image_size(k) * std::sqrt(cov.at<double>(9, 9));
    }
    pose_uncertainty(cov, x0,
                     [&params](const std::vector<double>& x) {
                         Intrinsics kk;
                         Pose pp;
                         params.apply(x, kk, pp);
                         return pp.position();
                     },
                     u);
    return u;
}

}  // namespace dp::calib
