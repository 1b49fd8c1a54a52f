#pragma once
#include <glm/glm.hpp>

#include "base/math.h"

namespace dp {

/// OpenCV's five-coefficient lens distortion (k1 k2 p1 p2 k3).
struct Distortion {
    float k1 = 0, k2 = 0, p1 = 0, p2 = 0, k3 = 0;
    bool is_zero() const { return k1 == 0 && k2 == 0 && p1 == 0 && p2 == 0 && k3 == 0; }
};

/// Pinhole camera with OpenCV intrinsics, distortion and a world-to-camera pose
/// (x_cam = R * x_world + t; camera looks along +Z, +X right, +Y down in the image).
/// Continuous pixel coordinates put pixel (i, j)'s centre at (i, j), as OpenCV does.
class Camera {
public:
    Camera() = default;
    Camera(int width, int height, float fx, float fy, float cx, float cy, Distortion dist,
           const glm::mat3& R, const vec3& t);

    /// Camera at `eye` looking at `target` with world `up` (+Y), vertical field of view in
    /// degrees, principal point at the image centre, no distortion.
    static Camera look_at(int width, int height, const vec3& eye, const vec3& target,
                          const vec3& up, float vfov_deg);

    int width() const { return width_; }
    int height() const { return height_; }
    float fx() const { return fx_; }
    float fy() const { return fy_; }
    float cx() const { return cx_; }
    float cy() const { return cy_; }
    const Distortion& distortion() const { return dist_; }
    const glm::mat3& rotation() const { return R_; }
    const vec3& translation() const { return t_; }
    /// Camera centre in world space: -R^T t.
    vec3 position() const { return position_; }
    /// Unit viewing direction (+Z of the camera) in world space.
    vec3 forward() const;

    /// World ray through continuous pixel coordinates (px, py), distortion removed.
    Ray generate_ray(float px, float py) const;

    /// Projects a world point; returns false if it lies behind the camera (z <= 0).
    /// The pixel may fall outside the image; the caller checks bounds.
    bool project(const vec3& world, vec2& pixel) const;

    bool in_image(const vec2& pixel) const {
        return pixel.x >= -0.5f && pixel.y >= -0.5f && pixel.x < width_ - 0.5f && pixel.y < height_ - 0.5f;
    }

    /// Distorts normalised image coordinates (x/z, y/z) with the OpenCV model.
    vec2 distort(vec2 normalized) const;
    /// Inverts distort() by fixed-point iteration (as cv::undistortPoints does).
    vec2 undistort(vec2 distorted) const;

private:
    int width_ = 0, height_ = 0;
    float fx_ = 1, fy_ = 1, cx_ = 0, cy_ = 0;
    Distortion dist_;
    glm::mat3 R_{1.0f};
    vec3 t_{0.0f};
    vec3 position_{0.0f};
};

}  // namespace dp
