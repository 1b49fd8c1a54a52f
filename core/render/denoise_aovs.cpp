#include "render/denoise_aovs.h"

#include <tbb/parallel_for.h>

#include <stdexcept>

#include "assets/scattering.h"

namespace dp {

namespace {

constexpr int kMaxSpecularBounces = 4;

// Albedo seen along a camera ray: a diffuse surface's reflectance; through mirrors and glass,
// the reflectance of the diffuse surface seen in them times the mirror's colour or the glass's
// tint (OIDN's advice for specular surfaces), so that the guide keeps the reflected detail.
vec3 albedo_along(const RenderScene& s, Ray ray, Hit hit) {
    vec3 throughput(1.0f);
    for (int bounce = 0; hit; ++bounce) {
        const Surface& surface = *hit.surface;
        // A principled surface guides by its base colour, as a diffuse one does.
        const bool specular = surface.is_virtual && (surface.material.kind == Material::Kind::Mirror ||
                                                     surface.material.kind == Material::Kind::Glass);
        if (!specular) return throughput * surface.reflectance_at(hit.uv);
        if (bounce == kMaxSpecularBounces) break;
        vec3 dir;
        if (surface.material.kind == Material::Kind::Mirror) {
            throughput *= surface.material.reflectance;
            dir = reflect(ray.dir, facing_normal(hit.ng, ray.dir));
        } else {  // glass: the refracted branch unless it is totally reflected
            SpecularEvent reflected, refracted;
            split_glass(surface.material, hit, ray.dir, reflected, refracted);
            throughput *= surface.material.tint;
            dir = luminance(refracted.weight) > 0 ? refracted.dir : reflected.dir;
        }
        ray = Ray{s.offset_origin(hit, dir), dir};
        hit = s.intersect(ray);
    }
    return throughput;  // the probe, or a chain too long to follow: OIDN's "1 or the tint"
}

}  // namespace

DenoiseAovs denoise_aovs(const RenderScene& s, const std::atomic<bool>* cancel) {
    const int W = s.photo().width(), H = s.photo().height();
    DenoiseAovs out{Image(W, H), Image(W, H)};
    tbb::parallel_for(0, H, [&](int y) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return;
        for (int x = 0; x < W; ++x) {
            const Ray ray = s.camera_ray(float(x), float(y));
            const Hit hit = s.intersect(ray);
            if (!hit || hit.t > s.holdout_t(ray)) continue;  // held out: the photo stands
            const vec3 n = glm::dot(hit.ns, hit.ns) > 0 ? hit.ns : hit.ng;
            out.albedo.at(x, y) = glm::clamp(albedo_along(s, ray, hit), vec3(0), vec3(1));
            out.normal.at(x, y) = facing_normal(glm::normalize(n), ray.dir);
        }
    });
    if (cancel && cancel->load()) throw std::runtime_error("denoiser guides cancelled");
    return out;
}

}  // namespace dp
