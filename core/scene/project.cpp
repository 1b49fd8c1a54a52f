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

glm::mat4 Shape::file_frame(UpAxis file_up) const {
    if (kind != Kind::Mesh) return glm::mat4(1.0f);
    // Columns are the images of the file's x, y and z axes; each is a proper rotation (a file
    // with +Z up has its front, -Y, turned towards +Z as exporters to +Y up do).
    glm::mat3 r(1.0f);
    switch (effective_up(file_up)) {
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
           camera == o.camera && real == o.real && objects == o.objects && lights == o.lights && holdouts == o.holdouts &&
           render == o.render &&
           display == o.display;
}

void for_each_input(Project& project,
                    const std::function<void(const InputRef&, std::string& path)>& visit) {
    auto item = [&](std::string field, std::string what, std::string& path) {
        if (!path.empty()) visit(InputRef{std::move(field), std::move(what)}, path);
    };
    auto quoted = [](const std::string& name) { return "\"" + name + "\""; };
    item("photo.path", "photo", project.photo.path);
    item("probe.path", "light probe", project.probe.path);
    for (size_t i = 0; i < project.real.size(); ++i) {
        RealProxy& r = project.real[i];
        const std::string at = "real[" + std::to_string(i) + "]";
        if (r.shape.kind == Shape::Kind::Mesh)
            item(at + ".shape.path", "mesh of proxy " + quoted(r.name), r.shape.mesh_path);
        if (r.albedo.kind == Albedo::Kind::Texture)
            item(at + ".albedo.texture", "texture of proxy " + quoted(r.name),
                 r.albedo.texture_path);
    }
    for (size_t i = 0; i < project.objects.size(); ++i) {
        VirtualObject& o = project.objects[i];
        const std::string at = "objects[" + std::to_string(i) + "]";
        if (o.shape.kind == Shape::Kind::Mesh)
            item(at + ".shape.path", "mesh of " + quoted(o.name), o.shape.mesh_path);
        if (o.material.albedo.kind == Albedo::Kind::Texture)
            item(at + ".material.albedo.texture", "texture of " + quoted(o.name),
                 o.material.albedo.texture_path);
        if (o.material.kind == Material::Kind::Principled) {
            PrincipledMaterial& m = o.material.principled;
            item(at + ".material.metallic_roughness_texture", "metallic-roughness texture of " + quoted(o.name),
                 m.metallic_roughness_texture);
            item(at + ".material.normal_texture", "normal map of " + quoted(o.name), m.normal_texture);
        }
    }
    for (size_t i = 0; i < project.holdouts.size(); ++i)
        item("holdouts[" + std::to_string(i) + "].mask", "mask of holdout " + quoted(project.holdouts[i].name),
             project.holdouts[i].mask);
}

void for_each_input(const Project& project,
                    const std::function<void(const InputRef&, const std::string& path)>& visit) {
    // The visitor above only hands the paths on; this one's `visit` cannot write through them.
    for_each_input(const_cast<Project&>(project),
                   [&](const InputRef& in, std::string& path) { visit(in, path); });
}

std::vector<std::pair<std::string, std::filesystem::path>> project_inputs(const Project& project) {
    std::vector<std::pair<std::string, std::filesystem::path>> in;
    for_each_input(project, [&](const InputRef& ref, const std::string& path) {
        in.emplace_back(ref.field, project.resolve(path));
    });
    return in;
}

bool is_mesh_field(const std::string& field) {
    const std::string suffix = ".shape.path";
    return field.size() > suffix.size() && field.compare(field.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace dp
