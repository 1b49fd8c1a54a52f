#include "render/change_region.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace dp {

namespace {

/// Distance from `c` to the half-line from `p` along unit `dir`.
float distance_to_half_line(const vec3& c, const vec3& p, const vec3& dir) {
    const float t = std::max(0.0f, glm::dot(c - p, dir));
    return glm::length(c - (p + t * dir));
}

/// Distance from `c` to the segment from `p` to `q`.
float distance_to_segment(const vec3& c, const vec3& p, const vec3& q) {
    const vec3 d = q - p;
    const float len2 = glm::dot(d, d);
    const float t = len2 > 0 ? std::clamp(glm::dot(c - p, d) / len2, 0.0f, 1.0f) : 0.0f;
    return glm::length(c - (p + t * d));
}

}  // namespace

std::vector<uint8_t> change_region(const RenderScene& scene, const std::vector<EditedBounds>& edited,
                                   float reach, int step) {
    step = std::max(1, step);
    const int W = (scene.photo().width() + step - 1) / step, H = (scene.photo().height() + step - 1) / step;
    const float half = 0.5f * float(step - 1);
    std::vector<uint8_t> mask(size_t(W) * H, 0);
    if (edited.empty()) return mask;
    // The sun's direction: the middle of its table. Its shadow and caustics of an edited
    // object lie along it, however far.
    const ProbeLights& lights = scene.probe_lights();
    const bool sun = lights.has_sun();
    const vec3 to_sun = sun ? glm::normalize(lights.sample_sun(vec2(0.5f)).dir) : vec3(0, 1, 0);
    // The virtual lights: an edited object's shadow from one lies between it and the light.
    std::vector<std::pair<vec3, float>> lamps(scene.lights().size());
    for (size_t i = 0; i < lamps.size(); ++i) scene.lights().bounds(i, lamps[i].first, lamps[i].second);
    tbb::parallel_for(tbb::blocked_range<int>(0, H), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < W; ++x) {
                const Ray ray = scene.camera_ray(float(x * step) + half, float(y * step) + half);
                const Hit hit = scene.intersect(ray);
                bool in = false;
                // What the pixel saw before or sees now: an edited object's sphere on its ray.
                // The scene is the new state's, so a pixel that saw the object at its old place
                // and now sees a far surface is found only this way.
                for (const EditedBounds& b : edited)
                    in |= distance_to_half_line(b.center, ray.org, ray.dir) <= b.radius;
                if (hit) {
                    // A virtual mirror or glass may show an edited object, wherever it is.
                    in |= hit.surface->is_virtual && hit.surface->material.kind != Material::Kind::Diffuse;
                    // Any surface, real or virtual, in an edited object's reach or sun shadow.
                    for (const EditedBounds& b : edited) {
                        in |= glm::length(hit.p - b.center) <= reach * b.radius;
                        in |= sun && distance_to_half_line(b.center, hit.p, to_sun) <= 1.25f * b.radius;
                        for (const auto& [centre, radius] : lamps)
                            in |= distance_to_segment(b.center, hit.p, centre) <= 1.25f * b.radius + radius;
                    }
                }
                mask[size_t(y) * W + x] = in;
            }
    });
    return mask;
}

}  // namespace dp
