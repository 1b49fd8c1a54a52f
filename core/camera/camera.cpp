#include "camera/camera.h"

#include <cmath>

namespace dp {

Camera::Camera(int width, int height, float fx, float fy, float cx, float cy, Distortion dist,
               const glm::mat3& R, const vec3& t)
    : width_(width), height_(height), fx_(fx), fy_(fy), cx_(cx), cy_(cy), dist_(dist), R_(R), t_(t) {
    position_ = -(glm::transpose(R_) * t_);
}

Camera Camera::look_at(int width, int height, const vec3& eye, const vec3& target, const vec3& up,
                       float vfov_deg) {
    vec3 forward = glm::normalize(target - eye);
    vec3 right = glm::normalize(glm::cross(forward, up));
    vec3 down = glm::cross(forward, right);
    // glm is column-major: R's rows are the camera axes expressed in world space.
    glm::mat3 R = glm::transpose(glm::mat3(right, down, forward));
    float f = 0.5f * float(height) / std::tan(0.5f * glm::radians(vfov_deg));
    vec3 t = -(R * eye);
    return Camera(width, height, f, f, 0.5f * float(width - 1), 0.5f * float(height - 1), {}, R, t);
}

vec3 Camera::forward() const { return glm::transpose(R_) * vec3(0, 0, 1); }

vec2 Camera::distort(vec2 p) const {
    if (dist_.is_zero()) return p;
    float r2 = p.x * p.x + p.y * p.y;
    float radial = 1 + r2 * (dist_.k1 + r2 * (dist_.k2 + r2 * dist_.k3));
    float dx = 2 * dist_.p1 * p.x * p.y + dist_.p2 * (r2 + 2 * p.x * p.x);
    float dy = dist_.p1 * (r2 + 2 * p.y * p.y) + 2 * dist_.p2 * p.x * p.y;
    return vec2(p.x * radial + dx, p.y * radial + dy);
}

vec2 Camera::undistort(vec2 d) const {
    if (dist_.is_zero()) return d;
    vec2 p = d;
    for (int i = 0; i < 20; ++i) {
        float r2 = p.x * p.x + p.y * p.y;
        float radial = 1 + r2 * (dist_.k1 + r2 * (dist_.k2 + r2 * dist_.k3));
        float dx = 2 * dist_.p1 * p.x * p.y + dist_.p2 * (r2 + 2 * p.x * p.x);
        float dy = dist_.p1 * (r2 + 2 * p.y * p.y) + 2 * dist_.p2 * p.x * p.y;
        if (radial == 0) break;
        p = vec2((d.x - dx) / radial, (d.y - dy) / radial);
    }
    return p;
}

Ray Camera::generate_ray(float px, float py) const {
    vec2 n = undistort(vec2((px - cx_) / fx_, (py - cy_) / fy_));
    vec3 dir_cam = glm::normalize(vec3(n.x, n.y, 1.0f));
    return Ray{position_, glm::normalize(glm::transpose(R_) * dir_cam)};
}

bool Camera::project(const vec3& world, vec2& pixel) const {
    vec3 c = R_ * world + t_;
    if (c.z <= 0) return false;
    vec2 d = distort(vec2(c.x / c.z, c.y / c.z));
    pixel = vec2(fx_ * d.x + cx_, fy_ * d.y + cy_);
    return true;
}

}  // namespace dp
