#pragma once
// Fits of a camera to world-image point correspondences by reprojection error, and the
// uncertainty of such a fit (internal; shared by the rectangle, points and chessboard methods).
#include <functional>
#include <vector>

#include <opencv2/core.hpp>

#include "calibration/calibration.h"

namespace dp::calib {

/// Which intrinsics a fit estimates besides the pose.
enum class FreeIntrinsics {
    None,   ///< all given
    Focal,  ///< fx and fy scaled together, principal point held
    All,    ///< fx, fy, cx, cy
};

/// Projects a world point through `k` (with its distortion) and `pose`, in double precision.
ImagePoint project(const Intrinsics& k, const Pose& pose, const glm::dvec3& world);

/// The fit's parameters: a rotation vector w (R = exp([w]x) R0), the translation's change
/// relative to its size, and the free intrinsics as log focal lengths and principal point
/// shifts in units of the image size: all of order one for the solver.
struct ReprojectionParams {
    Intrinsics k0;
    Pose pose0;
    FreeIntrinsics free = FreeIntrinsics::None;

    int count() const;
    void apply(const std::vector<double>& x, Intrinsics& k, Pose& pose) const;
};

/// Refines `pose` (and the free intrinsics of `k`) by Levenberg-Marquardt on the reprojection
/// error of `world` onto `image`; returns the RMS error in pixels.
double refine_reprojection(const std::vector<glm::dvec3>& world,
                           const std::vector<ImagePoint>& image, Intrinsics& k, Pose& pose,
                           FreeIntrinsics free);

/// Uncertainty of a camera fitted to `world` -> `image` (at its optimum): the covariance
/// sigma^2 (J^T J)^-1 of the free parameters with sigma the residuals' own noise (never below
/// `prior_sigma_px`). `intrinsics_cov` (4x4 over fx, fy, cx, cy in pixels^2, optional) adds the
/// spread that intrinsics estimated elsewhere (other photos) carry into the pose.
Uncertainty reprojection_uncertainty(const std::vector<glm::dvec3>& world,
                                     const std::vector<ImagePoint>& image, const Intrinsics& k,
                                     const Pose& pose, FreeIntrinsics free,
                                     double prior_sigma_px, const cv::Mat& intrinsics_cov = {});

/// Fills the rotation and position parts of `u` from the covariance `cov` of parameters whose
/// first three are the rotation vector w: `position(x)` gives the camera centre for parameters
/// `x` (their optimum is `x0`), and `extra_position_cov` (m^2) adds what the parameters do not
/// carry (clicked scale points).
void pose_uncertainty(const cv::Mat& cov, const std::vector<double>& x0,
                      const std::function<glm::dvec3(const std::vector<double>&)>& position,
                      Uncertainty& u, const glm::dmat3& extra_position_cov = glm::dmat3(0.0));

}  // namespace dp::calib
