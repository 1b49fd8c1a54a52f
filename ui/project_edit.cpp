#include "project_edit.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace dp::ui {

std::string unique_name(const Project& project, const std::string& base) {
    std::set<std::string> used;
    for (const VirtualObject& o : project.objects) used.insert(o.name);
    if (!used.count(base)) return base;
    for (int i = 2;; ++i) {
        std::string name = base + " " + std::to_string(i);
        if (!used.count(name)) return name;
    }
}

std::string unique_light_name(const Project& project, const std::string& base) {
    std::set<std::string> used;
    for (const VirtualLight& l : project.lights) used.insert(l.name);
    if (!used.count(base)) return base;
    for (int i = 2;; ++i) {
        std::string name = base + " " + std::to_string(i);
        if (!used.count(name)) return name;
    }
}

const char* light_kind_label(VirtualLight::Kind kind) {
    static const char* labels[] = {"Point", "Spot", "Area (rectangle)", "Area (disk)"};
    return labels[int(kind)];
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
    for_each_input(out, [&](const InputRef&, std::string& path) { abs(path); });
    return out;
}

}  // namespace dp::ui
