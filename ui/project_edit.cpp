#include "project_edit.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace dp::ui {

namespace {

bool same_geometry(const VirtualObject& a, const VirtualObject& b) {
    // The material source picks which textures are loaded with the assets: a rebuild, as for
    // a texture.
    return a.shape == b.shape && a.transform == b.transform && a.visible == b.visible &&
           a.material_source == b.material_source;
}

}  // namespace

Change classify(const Project& a, const Project& b) {
    if (a.photo != b.photo || a.probe.path != b.probe.path || a.probe.format != b.probe.format ||
        a.base_dir != b.base_dir)
        return Change::Assets;
    if (!(a.probe == b.probe) || !(a.camera == b.camera) || a.real != b.real || a.objects.size() != b.objects.size())
        return Change::Scene;
    bool material = false;
    for (size_t i = 0; i < a.objects.size(); ++i) {
        if (!same_geometry(a.objects[i], b.objects[i])) return Change::Scene;
        // Albedo textures are images loaded with the assets: a texture edit needs a rebuild.
        const Material &ma = a.objects[i].material, &mb = b.objects[i].material;
        if (ma.albedo.kind != mb.albedo.kind || ma.albedo.texture_path != mb.albedo.texture_path)
            return Change::Scene;
        material |= !(ma == mb);
    }
    if (material) return Change::Material;
    return a.render != b.render ? Change::Settings : Change::None;
}

bool edited_objects(const Project& a, const Project& b, std::vector<int>& edited) {
    edited.clear();
    if (classify(a, b) == Change::Assets || !(a.probe == b.probe) || !(a.camera == b.camera) || a.real != b.real ||
        a.render != b.render)
        return false;
    const size_t n = std::max(a.objects.size(), b.objects.size());
    for (size_t i = 0; i < n; ++i)
        if (i >= a.objects.size() || i >= b.objects.size() || !same_geometry(a.objects[i], b.objects[i]) ||
            !(a.objects[i].material == b.objects[i].material))
            edited.push_back(int(i));
    return true;
}

std::string unique_name(const Project& project, const std::string& base) {
    std::set<std::string> used;
    for (const VirtualObject& o : project.objects) used.insert(o.name);
    if (!used.count(base)) return base;
    for (int i = 2;; ++i) {
        std::string name = base + " " + std::to_string(i);
        if (!used.count(name)) return name;
    }
}

std::string unique_real_name(const Project& project, const std::string& base) {
    std::set<std::string> used;
    for (const RealProxy& r : project.real) used.insert(r.name);
    if (!used.count(base)) return base;
    for (int i = 2;; ++i) {
        std::string name = base + " " + std::to_string(i);
        if (!used.count(name)) return name;
    }
}

void bounding_sphere(const VirtualObject& o, vec3& center, float& radius, float mesh_radius) {
    center = o.transform.translation;
    const vec3 s = glm::abs(o.transform.scale);
    const float smax = std::max({s.x, s.y, s.z});
    switch (o.shape.kind) {
        case Shape::Kind::Sphere:
            radius = o.shape.radius * smax;
            break;
        case Shape::Kind::Box:
            radius = 0.5f * glm::length(o.shape.size * s);
            break;
        case Shape::Kind::Plane:
            radius = 0.5f * std::hypot(o.shape.size.x * s.x, o.shape.size.z * s.z);
            break;
        case Shape::Kind::Mesh:
            radius = mesh_radius * o.shape.unit_scale * smax;
            break;
    }
}

Project with_absolute_paths(const Project& p) {
    Project out = p;
    auto abs = [&](std::string& path) {
        if (!path.empty()) path = p.resolve(path).string();
    };
    abs(out.photo.path);
    abs(out.probe.path);
    for (RealProxy& r : out.real) {
        abs(r.shape.mesh_path);
        abs(r.albedo.texture_path);
    }
    for (VirtualObject& o : out.objects) {
        abs(o.shape.mesh_path);
        abs(o.material.albedo.texture_path);
    }
    return out;
}

}  // namespace dp::ui
