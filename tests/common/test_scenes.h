#pragma once
// Small scenes built in memory for the render tests: no files, known radiance.
#include <memory>

#include "probe/probe.h"
#include "probe/synthetic_probe.h"
#include "assets/render_scene.h"
#include "scene/project.h"

namespace dp::test {

/// A 1024x512 probe that is black but one pixel: a directional light ("the sun").
struct SunProbe {
    int width = 1024, height = 512, px = 768, py = 128;
    vec3 radiance{20000.0f};
    Image image() const { return make_single_pixel_probe(width, height, px, py, radiance); }
    /// World direction towards the sun (probe not rotated).
    vec3 direction() const { return latlong_direction((px + 0.5f) / width, (py + 0.5f) / height); }
    /// Irradiance on a surface facing the sun.
    double normal_irradiance() const {
        Probe p(image(), glm::mat3(1.0f), 1.0f);
        return double(radiance.x) * p.pixel_solid_angle(py);
    }
};

inline RealProxy ground_plane(vec3 albedo, float size = 40.0f) {
    RealProxy g;
    g.name = "ground";
    g.shape.kind = Shape::Kind::Plane;
    g.shape.size = vec3(size, 1, size);
    g.albedo.rgb = albedo;
    return g;
}

/// A real wall: a 4 x 2 x 0.1 m box standing on the ground, centred at z = `z`.
inline RealProxy wall_proxy(float z, vec3 albedo) {
    RealProxy wall;
    wall.name = "wall";
    wall.shape.kind = Shape::Kind::Box;
    wall.shape.size = vec3(4, 2, 0.1f);
    wall.transform.translation = vec3(0, 1, z);
    wall.albedo.rgb = albedo;
    return wall;
}

/// Distance from `center` to the line through `x` along unit direction `dir` (how far a ground
/// point is from the shadow axis of a sphere).
inline float distance_to_line(vec3 center, vec3 x, vec3 dir) {
    const vec3 oc = center - x;
    return glm::length(oc - glm::dot(oc, dir) * dir);
}

inline VirtualObject sphere(vec3 center, float radius, Material m) {
    VirtualObject o;
    o.name = "sphere";
    o.shape.kind = Shape::Kind::Sphere;
    o.shape.radius = radius;
    o.transform.translation = center;
    o.material = m;
    return o;
}

inline Material diffuse(vec3 albedo) {
    Material m;
    m.kind = Material::Kind::Diffuse;
    m.albedo.rgb = albedo;
    return m;
}
inline Material mirror(vec3 reflectance = vec3(1.0f)) {
    Material m;
    m.kind = Material::Kind::Mirror;
    m.reflectance = reflectance;
    return m;
}
inline Material principled(vec3 base, float metallic, float roughness, float specular = 1.0f) {
    Material m;
    m.kind = Material::Kind::Principled;
    m.albedo.rgb = base;
    m.principled.metallic = metallic;
    m.principled.roughness = roughness;
    m.principled.specular = specular;
    return m;
}
inline Material glass(float ior, vec3 tint = vec3(1.0f)) {
    Material m;
    m.kind = Material::Kind::Glass;
    m.ior = ior;
    m.tint = tint;
    return m;
}

inline Project look_at_project(vec3 eye, vec3 target, float vfov) {
    Project p;
    p.camera.model = CameraSpec::Model::LookAt;
    p.camera.eye = eye;
    p.camera.target = target;
    p.camera.up = vec3(0, 1, 0);
    p.camera.vfov_deg = vfov;
    return p;
}

/// Photo of a lone ground plane under a directional light: rho/pi * E * cos(theta) where the
/// camera sees the plane, black elsewhere (the probe is black but the sun).
inline Image analytic_ground_photo(const Project& p, int w, int h, const SunProbe& sun, vec3 albedo) {
    Camera cam = p.camera.build(w, h);
    Image photo(w, h);
    vec3 l = sun.direction();
    const float E = float(sun.normal_irradiance() * std::max(0.0f, l.y));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Ray r = cam.generate_ray(float(x), float(y));
            if (r.dir.y >= 0 || cam.position().y <= 0) continue;
            photo.at(x, y) = albedo * kInvPi * E;
        }
    return photo;
}

/// Render settings: `base` (a project's, or the defaults) with a photon count and a seed.
inline RenderSettings settings(int64_t photons, uint64_t seed, RenderSettings base = {}) {
    base.photons_per_pass = photons;
    base.seed = seed;
    return base;
}

inline std::shared_ptr<RenderScene> build(const Project& p, Image photo, Image probe) {
    SceneAssets a;
    a.photo = std::move(photo);
    a.probe_latlong = std::move(probe);
    return std::make_shared<RenderScene>(p, std::move(a));
}

/// A glass ball and a clay ball on a grey floor under a sun and sky: every path kind (caustic,
/// shadow, bounce) in a small frame, for tests that compare whole renders bit for bit.
inline std::shared_ptr<RenderScene> glass_and_clay_scene() {
    Project p = look_at_project(vec3(0, 2.5f, 4), vec3(0, 0.5f, 0), 45);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.objects.push_back(sphere(vec3(-0.6f, 0.5f, 0), 0.5f, glass(1.5f)));
    p.objects.push_back(sphere(vec3(0.6f, 0.5f, 0), 0.5f, diffuse(vec3(0.8f, 0.3f, 0.2f))));
    Image probe = make_sun_sky_probe(128, 64, glm::normalize(vec3(1, 1.2f, 0.5f)), vec3(3000.0f), 2.0f,
                                     vec3(0.3f, 0.5f, 1.0f), vec3(0.8f, 0.9f, 1.0f));
    return build(p, Image(80, 60, vec3(0.3f)), probe);
}

}  // namespace dp::test
