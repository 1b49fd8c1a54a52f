#include "scene/project.h"
#include "base/text.h"

#include "base/error.h"

#include "base/euler.h"

#include <glm/gtc/matrix_transform.hpp>

namespace dp {

glm::mat4 Transform::matrix() const {
    // Column vectors: the rightmost factor acts first, so points are scaled, rotated about X,
    // then Y, then Z, and finally translated.
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translation) * glm::mat4(euler_xyz_deg(rotation_deg));
    return glm::scale(m, scale);
}

glm::mat4 Shape::file_frame() const {
    if (kind != Kind::Mesh) return glm::mat4(1.0f);
    // Columns are the images of the file's x, y and z axes; each is a proper rotation (a file
    // with +Z up has its front, -Y, turned towards +Z as exporters to +Y up do).
    glm::mat3 r(1.0f);
    switch (up_axis) {
        case UpAxis::Y: break;
        case UpAxis::Z: r = glm::mat3(vec3(1, 0, 0), vec3(0, 0, -1), vec3(0, 1, 0)); break;
        case UpAxis::NegY: r = glm::mat3(vec3(1, 0, 0), vec3(0, -1, 0), vec3(0, 0, -1)); break;
        case UpAxis::NegZ: r = glm::mat3(vec3(1, 0, 0), vec3(0, 0, 1), vec3(0, -1, 0)); break;
    }
    return glm::mat4(r * unit_scale);
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
           camera == o.camera && real == o.real && objects == o.objects && render == o.render &&
           display == o.display;
}

std::vector<std::pair<std::string, std::filesystem::path>> project_inputs(const Project& project) {
    std::vector<std::pair<std::string, std::filesystem::path>> in;
    auto add = [&](const std::string& field, const std::string& path) {
        if (!path.empty()) in.emplace_back(field, project.resolve(path));
    };
    add("photo.path", project.photo.path);
    add("probe.path", project.probe.path);
    for (size_t i = 0; i < project.real.size(); ++i) {
        const std::string at = "real[" + std::to_string(i) + "]";
        if (project.real[i].shape.kind == Shape::Kind::Mesh) add(at + ".shape.path", project.real[i].shape.mesh_path);
        add(at + ".albedo.texture", project.real[i].albedo.texture_path);
    }
    for (size_t i = 0; i < project.objects.size(); ++i) {
        const std::string at = "objects[" + std::to_string(i) + "]";
        if (project.objects[i].shape.kind == Shape::Kind::Mesh) add(at + ".shape.path", project.objects[i].shape.mesh_path);
        add(at + ".material.albedo.texture", project.objects[i].material.albedo.texture_path);
    }
    return in;
}

void refuse_overwriting_inputs(const std::string& output, const std::string& option, const Project& project,
                               const std::string& project_file) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path out = fs::weakly_canonical(fs::absolute(output, ec), ec);
    auto same = [&](const fs::path& p) {
        std::error_code e;
        return fs::exists(p, e) && fs::equivalent(out, p, e);
    };
    if (!project_file.empty() && same(project_file))
        throw InputError(output, option, "is the project file itself: choose another output");
    for (const auto& [field, path] : project_inputs(project))
        if (same(path))
            throw InputError(output, option,
                             "is the project's " + field + " ('" + shorten_path(path.string()) +
                                 "'): a render must not overwrite its input");
}

}  // namespace dp
