#include "scene/project.h"

#include "base/euler.h"

#include <glm/gtc/matrix_transform.hpp>

namespace dp {

glm::mat4 Transform::matrix() const {
    // Column vectors: the rightmost factor acts first, so points are scaled, rotated about X,
    // then Y, then Z, and finally translated.
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translation) * glm::mat4(euler_xyz_deg(rotation_deg));
    return glm::scale(m, scale);
}

Camera CameraSpec::build(int width, int height) const {
    if (model == Model::Intrinsics)
        return Camera(width, height, fx, fy, cx, cy, distortion, rotation, translation);
    return Camera::look_at(width, height, eye, target, up, vfov_deg);
}

namespace {

bool same(const Distortion& a, const Distortion& b) {
    return a.k1 == b.k1 && a.k2 == b.k2 && a.p1 == b.p1 && a.p2 == b.p2 && a.k3 == b.k3;
}

}  // namespace

bool CameraSpec::operator==(const CameraSpec& o) const {
    // Only the active model's fields describe the camera; the other model's fields are unused
    // (and are not written to the project file), so they must not affect equality.
    if (model != o.model) return false;
    if (model == Model::Intrinsics) {
        return fx == o.fx && fy == o.fy && cx == o.cx && cy == o.cy &&
               same(distortion, o.distortion) && rotation == o.rotation &&
               translation == o.translation;
    }
    return eye == o.eye && target == o.target && up == o.up && vfov_deg == o.vfov_deg;
}

std::filesystem::path Project::resolve(const std::string& path) const {
    std::filesystem::path p(path);
    if (path.empty() || p.is_absolute()) return p;
    return base_dir / p;
}

bool Project::operator==(const Project& o) const {
    // base_dir records where the file was read from, not what it says.
    return schema_version == o.schema_version && photo == o.photo && probe == o.probe &&
           camera == o.camera && real == o.real && objects == o.objects && render == o.render;
}

}  // namespace dp
