#pragma once
// A small dense Levenberg-Marquardt solver and the covariance of its estimate, for the
// calibration methods' few-parameter fits (internal).
#include <functional>
#include <vector>

#include <glm/glm.hpp>
#include <opencv2/core.hpp>

namespace dp::calib {

/// Fills `r` with the residuals at parameters `x` (the same count every call).
using ResidualFunction = std::function<void(const std::vector<double>& x, std::vector<double>& r)>;

struct LeastSquaresResult {
    std::vector<double> x;
    double cost = 0;  ///< sum of squared residuals at x
    int residuals = 0;
    int iterations = 0;
};

/// Minimises the sum of squared residuals from `x0` with Levenberg-Marquardt and a
/// central-difference Jacobian. Parameters should be of order one (scale them).
LeastSquaresResult levenberg_marquardt(const ResidualFunction& f, std::vector<double> x0,
                                       int max_iterations = 200);

/// Central-difference Jacobian (rows: residuals, columns: parameters), CV_64F.
cv::Mat numeric_jacobian(const ResidualFunction& f, const std::vector<double>& x,
                         double step = 1e-6);

/// (J^T J)^-1 with a tiny ridge, so that directions the data do not constrain come out with a
/// huge variance instead of the zero a pseudo-inverse would give them.
cv::Mat inverse_normal_matrix(const cv::Mat& J);

/// Noise of one residual: the fit's own estimate sum r^2 / (n - p) where it has redundancy,
/// never below `prior` (how precisely the points can be placed at all).
double residual_sigma(double cost, int residuals, int params, double prior);

/// Rotation matrix exp([w]x) of a rotation vector (axis times angle in radians).
glm::dmat3 rotation_exp(const glm::dvec3& w);
/// The rotation vector of a rotation matrix (inverse of rotation_exp).
glm::dvec3 rotation_log(const glm::dmat3& R);

}  // namespace dp::calib
