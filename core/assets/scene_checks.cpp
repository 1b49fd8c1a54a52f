#include "assets/scene_checks.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "base/error.h"

namespace dp {

namespace {

/// Directions spread evenly over the sphere (Fibonacci lattice), deterministic.
std::vector<vec3> sphere_directions(int count) {
    std::vector<vec3> dirs;
    const float golden = kPi * (3.0f - std::sqrt(5.0f));
    for (int i = 0; i < count; ++i) {
        float y = 1.0f - 2.0f * (float(i) + 0.5f) / float(count);
        float r = std::sqrt(std::max(0.0f, 1.0f - y * y));
        float phi = golden * float(i);
        dirs.push_back(vec3(r * std::cos(phi), y, r * std::sin(phi)));
    }
    return dirs;
}

std::string proxy_label(const Project& p, int index) {
    const std::string& name = p.real[size_t(index)].name;
    return name.empty() ? "real[" + std::to_string(index) + "]" : name;
}

}  // namespace

void check_scene(const RenderScene& scene, const std::string& file_for_errors) {
    const Project& project = scene.project();
    if (project.real.empty()) return;
    const vec3 eye = scene.camera().position();
    // Surfaces are closed and outward-facing by convention (counter-clockwise seen from
    // outside, as Embree's geometric normal assumes); an open plane never encloses the eye.
    std::map<int, int> hits_per_proxy;
    for (const vec3& dir : sphere_directions(64)) {
        Hit hit = scene.intersect_real(Ray{eye, dir});
        if (!hit || glm::dot(hit.ng, dir) <= 0.0f) return;  // escapes, or sees a front face
        ++hits_per_proxy[hit.surface->index];
    }
    const int worst = std::max_element(hits_per_proxy.begin(), hits_per_proxy.end(),
                                       [](const auto& a, const auto& b) {
                                           return a.second < b.second;
                                       })->first;
    const char* field =
        project.camera.model == CameraSpec::Model::LookAt ? "camera.eye" : "camera.translation";
    throw InputError(file_for_errors, field,
                     "the camera is inside real geometry '" + proxy_label(project, worst) +
                         "' (every ray from the camera hits the inside of a real proxy)");
}

}  // namespace dp
