#include "calibration/ground_frame.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "base/error.h"
#include "camera/camera.h"

namespace dp {

namespace {

std::string format(const char* fmt, auto... args) {
    char buf[256];
    std::snprintf(buf, sizeof(buf), fmt, args...);
    return buf;
}

double degrees(double radians) {
    return radians * 180.0 / std::numbers::pi;
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// A direction projected onto the plane at right angles to unit `n`, or a zero vector when
/// less than `min_length` of it is left (it runs too close to `n` to define a direction).
glm::dvec3 in_plane(const glm::dvec3& v, const glm::dvec3& n, double min_length) {
    const glm::dvec3 p = v - glm::dot(v, n) * n;
    const double len = glm::length(p);
    return len >= min_length ? p / len : glm::dvec3(0.0);
}

}  // namespace

glm::dvec3 up_from_camera(const CalibrationResult& r, const std::string& source) {
    // World +Y of the target frame (the plane's normal) in camera coordinates: R e_y.
    const glm::dvec3 normal = glm::normalize(r.pose.R[1]);
    // A camera without roll keeps its X axis level, so up is at right angles to it and lies
    // in the wall. (Image up projected onto the wall would lean sideways whenever the camera
    // looks down or up at a wall it does not face square on.)
    glm::dvec3 up = glm::cross(normal, glm::dvec3(1, 0, 0));
    const double len = glm::length(up);
    if (len < 0.1)
        throw InputError(source, "up",
                         format("the board's plane is seen nearly edge-on along the image's "
                                "horizontal (its normal %.0f° from the camera's X axis): the "
                                "camera's up says nothing about that wall; click the horizon "
                                "instead",
                                degrees(std::acos(std::min(1.0, std::abs(normal.x))))));
    up /= len;
    return up.y > 0 ? -up : up;  // towards the image's top (camera -Y)
}

glm::dvec3 up_from_horizon(const Intrinsics& k, ImagePoint a, ImagePoint b,
                           const std::string& source) {
    if (!std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) || !std::isfinite(b.y))
        throw InputError(source, "horizon",
                         "the horizon's points must be finite pixel coordinates");
    check_focal(k.fx, source, "focal");
    check_focal(k.fy, source, "focal");
    const double apart = glm::length(b - a);
    if (apart < 2.0)
        throw InputError(source, "horizon",
                         format("the two horizon points are %.1f px apart: drag along the "
                                "horizon across as much of the photo as it allows",
                                apart));
    // Undistorted rays through the two points; the plane they span through the camera centre
    // is parallel to the ground.
    const Camera lens(k.width, k.height, float(k.fx), float(k.fy), float(k.cx), float(k.cy),
                      k.distortion, glm::mat3(1.0f), vec3(0.0f));
    auto ray = [&](ImagePoint p) {
        const vec2 n = lens.undistort(vec2(float((p.x - k.cx) / k.fx), float((p.y - k.cy) / k.fy)));
        return glm::dvec3(n.x, n.y, 1.0);
    };
    const glm::dvec3 ra = ray(a), rb = ray(b);
    // The line's slope in undistorted pixels: near vertical, which side is up is ambiguous.
    const glm::dvec2 d((rb.x - ra.x) * k.fx, (rb.y - ra.y) * k.fy);
    const double tilt = degrees(std::atan2(std::abs(d.y), std::abs(d.x)));
    if (tilt > 80.0)
        throw InputError(source, "horizon",
                         format("the clicked horizon runs %.0f° from level in the photo: which "
                                "side is up is ambiguous; drag along the horizon, the line "
                                "where the ground meets the sky (or its far edge)",
                                tilt));
    glm::dvec3 n = glm::cross(ra, rb);
    // n . ray > 0 on one side of the line: make it the image's upper side (camera -Y).
    if (n.y > 0) n = -n;
    return glm::normalize(n);
}

CalibrationResult with_ground_from_up(const CalibrationResult& r, glm::dvec3 up_camera,
                                      double origin_height_m, const std::string& source) {
    if (!finite(up_camera) || glm::length(up_camera) < 1e-12)
        throw InputError(source, "up", "the up direction must be a finite, non-zero vector");
    if (!std::isfinite(origin_height_m) || origin_height_m < 0)
        throw InputError(source, "board height",
                         format("the board's height above the ground must be >= 0 metres "
                                "(got %g)",
                                origin_height_m));
    const glm::dvec3 u = glm::normalize(up_camera);
    const glm::dmat3& R = r.pose.R;
    // World X: the target's X made level; for a target turned with X nearly vertical, the
    // camera's right, else its forward (a camera rolled a quarter turn).
    glm::dvec3 x(0.0);
    for (const glm::dvec3& c : {R[0], glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1)})
        if ((x = in_plane(c, u, 0.1)) != glm::dvec3(0.0)) break;
    const glm::dvec3 z = glm::cross(x, u);
    CalibrationResult out = r;
    // New world-to-camera rotation: its columns are the new world axes in camera coordinates.
    out.pose.R = glm::dmat3(x, u, z);
    // The new origin sits origin_height_m below the old one, along up.
    out.pose.t = r.pose.t - origin_height_m * u;
    // Old world -> new world: p' = Q p + (0, h, 0).
    const glm::dmat3 Q = glm::transpose(out.pose.R) * R;
    for (glm::dvec3& p : out.world_points) p = Q * p + glm::dvec3(0, origin_height_m, 0);
    out.uncertainty.position_cov = Q * r.uncertainty.position_cov * glm::transpose(Q);

    const double camera_height = out.pose.position().y;
    if (camera_height <= 0)
        out.warnings.push_back(
            format("the camera is %.2f m below the ground: check the board's "
                   "height and which way is up",
                   -camera_height));
    const double tilt =
        degrees(std::asin(std::min(1.0, std::abs(glm::dot(glm::normalize(R[1]), u)))));
    if (tilt > 5.0)
        out.warnings.push_back(
            format("the board's plane is %.1f° from vertical against this "
                   "ground: the horizon may be misplaced, or the board is not "
                   "upright",
                   tilt));
    return out;
}

}  // namespace dp
