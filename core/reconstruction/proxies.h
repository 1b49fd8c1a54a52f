#pragma once
#include <string>
#include <vector>

#include "camera/camera.h"
#include "scene/project.h"

namespace dp {

/// World point where the camera ray through continuous pixel `pixel` meets the horizontal plane
/// y = `height` (the ground is y = 0, as calibration defines it). Throws InputError (labelled
/// with `field`) when the ray never reaches that plane: a point above the horizon for the
/// ground, or a camera on the wrong side of the plane.
vec3 point_on_plane_y(const Camera& camera, vec2 pixel, float height,
                      const std::string& field = "");

/// A proxy made from clicked image points, with how well the fitted shape explains the clicks.
struct ProxyFit {
    RealProxy proxy;
    /// World-space footprint corners on the ground (counter-clockwise seen from above).
    std::vector<vec3> footprint;
    /// RMS distance in pixels between the clicked points and the fitted footprint's corners
    /// (0 for the ground plane and for walls, whose two points are fitted exactly).
    float rms_error_px = 0;
};

/// The ground (y = 0) as a plane proxy that covers what the camera sees of it: the rays through
/// the image border are cut at `max_distance` (horizontal distance from the camera; 0 picks 20
/// times the camera's height) and the plane is the rectangle around them, turned to the
/// camera's heading. Throws InputError when the camera is not above the ground or sees none
/// of it.
ProxyFit ground_proxy(const Camera& camera, float max_distance = 0,
                      const std::string& name = "ground");

/// A wall from two clicked points at its base on the ground: a box `thickness` deep behind the
/// clicked line (away from the camera) and `height` tall. Throws InputError for points above
/// the horizon, coincident points and non-positive sizes.
ProxyFit wall_proxy(const Camera& camera, vec2 a, vec2 b, float height, float thickness,
                    const std::string& name = "wall");

/// A box from three or four clicked corners of its footprint on the ground (in order around it;
/// three are completed to a parallelogram) and a height. The footprint is fitted with a
/// rectangle whose sides follow the clicked edges on average. Throws InputError for other point
/// counts, points above the horizon, a degenerate or self-crossing footprint and a
/// non-positive height.
ProxyFit box_proxy(const Camera& camera, const std::vector<vec2>& corners, float height,
                   const std::string& name = "box");

/// Puts `proxy` into `project.real`: it replaces the proxy of the same name, which keeps its
/// albedo (a refitted shape does not undo what was estimated or set for it), or is appended.
/// Returns true when it replaced one.
bool add_or_replace_real_proxy(Project& project, RealProxy proxy);

}  // namespace dp
