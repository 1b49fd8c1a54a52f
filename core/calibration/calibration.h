#pragma once
// Camera matching from a photograph: the result every method returns and the conventions shared
// by all of them.
//
// World frame: Y up, the ground (or the calibration target's plane) is y = 0, units are metres.
// Pose: world-to-camera R, t in the OpenCV convention of camera/camera.h (x_cam = R x_world + t,
// camera looks along +Z, image +Y down). Lens distortion stays in the camera model (OpenCV's
// k1 k2 p1 p2 k3): the renderer's rays and every back-projection go through Camera, which
// applies it, so the photograph is never resampled.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "camera/camera.h"
#include "scene/project.h"

namespace dp {

/// A 2D image point in continuous pixel coordinates (pixel (i, j)'s centre at (i, j)).
using ImagePoint = glm::dvec2;

/// Intrinsics of a W x H photograph.
struct Intrinsics {
    int width = 0, height = 0;
    double fx = 0, fy = 0, cx = 0, cy = 0;
    Distortion distortion;

    /// fx = fy = `focal_px`, principal point at the image centre ((W - 1)/2, (H - 1)/2).
    static Intrinsics centred(int width, int height, double focal_px);
    /// Horizontal field of view in degrees.
    double hfov_deg() const;
};

/// World-to-camera pose.
struct Pose {
    glm::dmat3 R{1.0};
    glm::dvec3 t{0.0};
    /// Camera centre in world space, -R^T t.
    glm::dvec3 position() const { return -(glm::transpose(R) * t); }
};

/// One standard deviation of what a method estimated: the covariance of its fit (from the
/// Jacobian at the optimum, scaled by the noise of the points) carried to focal length,
/// principal point, rotation and camera position. What was given or held fixed has none.
struct Uncertainty {
    /// False for methods that give no figure to derive one from (EXIF, fSpy).
    bool known = false;
    bool focal_free = false, principal_free = false;
    double fx = 0, fy = 0, cx = 0, cy = 0;  ///< pixels
    /// RMS angle of the rotation error, degrees; and of the camera centre's error, metres.
    double rotation_deg = 0, position_m = 0;
    /// Noise of one clicked or detected point that the figures assume, pixels.
    double point_sigma_px = 0;
    /// Covariance of the small rotation w with R_true = exp([w]x) R (radians^2, camera
    /// frame), and of the camera centre (m^2).
    glm::dmat3 rotation_cov{0.0}, position_cov{0.0};
};

/// What a calibration method found: intrinsics, pose and the RMS reprojection error in pixels
/// of the points it was fitted to (for vanishing lines: the RMS distance of the segment
/// end points from the lines through the fitted vanishing points).
struct CalibrationResult {
    Intrinsics intrinsics;
    Pose pose;
    double rms_px = 0;
    Uncertainty uncertainty;
    /// World positions of the points the fit used, where the method defines them (board or
    /// rectangle corners in the frame it chose, the given points), in input order.
    std::vector<glm::dvec3> world_points;
    std::vector<std::string> warnings;

    /// The project's camera (model "opencv").
    CameraSpec camera_spec() const;
    Camera camera() const;
};

/// `r` for the same picture at `width` x `height` pixels (pixel edges scale, so centres map
/// as (c + 0.5) s - 0.5); `r` itself where the size is the same. Throws InputError naming
/// `file` and `field` (the photo's) when the aspect ratios differ by more than 1 %: another
/// picture, or the same one cropped or turned.
CalibrationResult scaled_to(const CalibrationResult& r, int width, int height,
                            const std::string& file, const std::string& field);

/// The checks every method's result gets, added to its warnings: an estimated focal length
/// uncertain by more than 5 % or wider than 120° across, a principal point outside the middle
/// half of the image, and an RMS error above `rms_limit_px` (pass infinity where the method
/// words its own).
void add_quality_warnings(CalibrationResult& r, double rms_limit_px = 2.0);

/// Throws InputError (`source`) when clicked input fits so badly that the camera cannot be
/// used: an RMS error above 5 px and above 0.5 % of the image diagonal. `what` says what to
/// check ("a corner is misplaced ...").
void check_usable_fit(const CalibrationResult& r, const std::string& source,
                      const std::string& field, const std::string& what);

/// The uncertainty in words, for the command line and the studio: "fx 495 ± 12 px (2.4 %),
/// rotation ± 0.41°, position ± 0.012 m"; "n/a" where the method gives none.
std::string uncertainty_text(const CalibrationResult& r);

/// Throws InputError (`source`, `field`) unless the focal length is finite and > 0.
void check_focal(double focal_px, const std::string& source, const std::string& field);

/// Throws InputError if the points are fewer than `min_count` or (nearly) collinear.
/// `what` names them in the message ("rectangle corners").
void check_image_points(const std::vector<ImagePoint>& points, size_t min_count,
                        const std::string& source, const std::string& field,
                        const std::string& what);

}  // namespace dp
