#include "calibration/least_squares.h"

#include <cmath>

#include <opencv2/calib3d.hpp>

namespace dp::calib {

namespace {

double sum_squares(const std::vector<double>& r) {
    double s = 0;
    for (double v : r) s += v * v;
    return std::isfinite(s) ? s : HUGE_VAL;
}

}  // namespace

cv::Mat numeric_jacobian(const ResidualFunction& f, const std::vector<double>& x, double step) {
    std::vector<double> r0;
    f(x, r0);
    cv::Mat J(int(r0.size()), int(x.size()), CV_64F);
    std::vector<double> xp = x, rp, rm;
    for (size_t j = 0; j < x.size(); ++j) {
        const double h = step * std::max(1.0, std::abs(x[j]));
        xp[j] = x[j] + h;
        f(xp, rp);
        xp[j] = x[j] - h;
        f(xp, rm);
        xp[j] = x[j];
        for (size_t i = 0; i < r0.size(); ++i)
            J.at<double>(int(i), int(j)) = (rp[i] - rm[i]) / (2 * h);
    }
    return J;
}

LeastSquaresResult levenberg_marquardt(const ResidualFunction& f, std::vector<double> x0,
                                       int max_iterations) {
    LeastSquaresResult out;
    std::vector<double> r, trial_r;
    f(x0, r);
    out.x = x0;
    out.cost = sum_squares(r);
    out.residuals = int(r.size());
    const int p = int(x0.size());
    if (p == 0) return out;
    double lambda = 1e-3;
    for (int it = 0; it < max_iterations; ++it) {
        out.iterations = it + 1;
        const cv::Mat J = numeric_jacobian(f, out.x);
        const cv::Mat A = J.t() * J;
        const cv::Mat g = J.t() * cv::Mat(r);
        bool improved = false;
        // Raise the damping until a step lowers the cost (or the damping is hopeless).
        while (lambda < 1e12) {
            cv::Mat D = A.clone();
            for (int j = 0; j < p; ++j)
                D.at<double>(j, j) += lambda * std::max(A.at<double>(j, j), 1e-12);
            cv::Mat step;
            if (!cv::solve(D, -g, step, cv::DECOMP_CHOLESKY))
                cv::solve(D, -g, step, cv::DECOMP_SVD);
            std::vector<double> trial = out.x;
            for (int j = 0; j < p; ++j) trial[size_t(j)] += step.at<double>(j);
            f(trial, trial_r);
            const double cost = sum_squares(trial_r);
            if (cost < out.cost) {
                const double gain = out.cost - cost, before = out.cost;
                const double size = cv::norm(step);
                out.x = trial;
                r = trial_r;
                out.cost = cost;
                lambda = std::max(1e-12, lambda / 3);
                improved = true;
                // Converged once a step gains (almost) nothing or barely moves.
                if (gain <= 1e-10 * before || size < 1e-13) return out;
                break;
            }
            lambda *= 4;
        }
        if (!improved) break;
    }
    return out;
}

cv::Mat inverse_normal_matrix(const cv::Mat& J) {
    cv::Mat A = J.t() * J;
    double trace = 0;
    for (int j = 0; j < A.rows; ++j) trace += A.at<double>(j, j);
    const double ridge = 1e-14 * std::max(trace, 1e-300);
    for (int j = 0; j < A.rows; ++j) A.at<double>(j, j) += ridge;
    cv::Mat inv;
    cv::invert(A, inv, cv::DECOMP_SVD);
    return inv;
}

double residual_sigma(double cost, int residuals, int params, double prior) {
    const double fitted = residuals > params ? std::sqrt(cost / (residuals - params)) : 0.0;
    return std::max(prior, fitted);
}

glm::dmat3 rotation_exp(const glm::dvec3& w) {
    cv::Matx33d R;
    cv::Rodrigues(cv::Vec3d(w.x, w.y, w.z), R);
    glm::dmat3 out;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out[j][i] = R(i, j);
    return out;
}

glm::dvec3 rotation_log(const glm::dmat3& R) {
    cv::Matx33d M;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) M(i, j) = R[j][i];
    cv::Vec3d w;
    cv::Rodrigues(M, w);
    return glm::dvec3(w[0], w[1], w[2]);
}

}  // namespace dp::calib
