#pragma once
// Where the camera of a vanishing-line calibration stands: its rotation and intrinsics put the
// world origin under a clicked point and one known length sets the scale (internal).
#include <string>
#include <vector>

#include "calibration/vanishing.h"

namespace dp::calib {

/// Camera centre in world space for world-to-camera rotation `R` and intrinsics `k`: the
/// origin click on the ground and the scale (camera height, ground distance or vertical
/// length) of `in`. Throws InputError (naming `source`) for points above the horizon, a
/// scale <= 0, coinciding points or a vertical length whose top is not above its foot.
glm::dvec3 place_camera(const glm::dmat3& R, const Intrinsics& k, const VanishingInput& in,
                        const std::string& source);

/// The image points `in` uses for placement (origin, then the scale's two ends if any), and
/// `in` with them replaced, for propagating their click noise.
std::vector<ImagePoint> placement_points(const VanishingInput& in);
VanishingInput with_placement_points(VanishingInput in, const std::vector<ImagePoint>& points);

/// Warnings about the scale input for the fitted camera: a ground distance whose two points
/// line up with the vertical (perhaps a vertical length given as a distance), a vertical
/// length whose top is not straight above its foot. `sigma_px` is the click noise.
std::vector<std::string> scale_warnings(const glm::dmat3& R, const Intrinsics& k,
                                        const VanishingInput& in, double sigma_px);

}  // namespace dp::calib
