#include "reference/path_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "base/rng.h"
#include "base/sampling.h"
#include "render/light_estimate.h"
#include "assets/real_gloss.h"
#include "assets/principled_scatter.h"
#include "assets/scattering.h"

namespace dp {

namespace {

struct PathTracer {
    const RenderScene& scene;
    const ReferenceOptions& opt;

    Hit intersect(const Ray& r) const {
        return opt.include_virtual ? scene.intersect(r) : scene.intersect_real(r);
    }
    bool occluded(const Ray& r) const {
        return opt.include_virtual ? scene.occluded(r) : scene.occluded_real(r);
    }
    /// The virtual lights belong to the virtual scene: a render of the real proxies has none.
    bool lights() const { return opt.include_virtual && !scene.lights().empty(); }

    /// At a principled surface: the probe by next-event estimation (eval, MIS against the BSDF)
    /// added to L, then the path continued by sampling the BSDF. False when the path ends.
    bool principled(const Hit& hit, Ray& ray, vec3& beta, vec3& L, bool last, Rng& rng, float& bsdf_pdf) const {
        const PrincipledBsdf bsdf = principled_at(*hit.surface, hit);
        const Probe& probe = scene.probe();
        const ProbeSample ls = probe.sample(rng.uniform(), rng.uniform(), rng.uniform());
        if (ls.pdf > 0) {
            const vec3 f = eval_principled(bsdf, hit, ray.dir, ls.dir, Transport::Radiance);
            if (f != vec3(0) && !occluded(Ray{scene.offset_origin(hit, ls.dir), ls.dir})) {
                const float w = last ? 1.0f : power_heuristic(ls.pdf, pdf_principled(bsdf, hit, ray.dir, ls.dir));
                L += beta * f * ls.radiance * (w / ls.pdf);
            }
        }
        // The virtual lights by next-event estimation alone: a bounce off this surface never
        // counts their faces (as in the progressive renderer).
        if (lights())
            L += beta * reflected_light(scene, hit, rng, [&](const vec3& w) {
                return eval_principled(bsdf, hit, ray.dir, w, Transport::Radiance);
            });
        if (last) return false;
        const vec3 u(rng.uniform(), rng.uniform(), rng.uniform());
        const PrincipledEvent e = sample_principled(bsdf, hit, ray.dir, u, Transport::Radiance);
        if (e.weight == vec3(0)) return false;
        beta *= e.weight;
        bsdf_pdf = e.pdf;
        ray = Ray{scene.offset_origin(hit, e.dir), e.dir};
        return true;
    }

    /// At a real surface with a gloss layer: its albedo's Lambert lobe plus the gloss lobe, the
    /// probe by next-event estimation MIS-weighted against the mixture both are sampled from
    /// (half and half), the lights by next-event estimation alone, then the path continued
    /// from the mixture. False when the path ends.
    bool glossy_real(const Hit& hit, Ray& ray, vec3& beta, vec3& L, bool last, Rng& rng, float& bsdf_pdf) const {
        const GlossySurface surface(hit, ray.dir);
        const Hit& h = surface.facing();
        auto f_cos = [&](const vec3& w) { return surface.eval_cos(w); };
        const ProbeSample ls = scene.probe().sample(rng.uniform(), rng.uniform(), rng.uniform());
        if (ls.pdf > 0) {
            const vec3 f = f_cos(ls.dir);
            if (f != vec3(0) && !occluded(Ray{scene.offset_origin(h, ls.dir), ls.dir}))
                L += beta * f * ls.radiance * ((last ? 1.0f : power_heuristic(ls.pdf, surface.pdf(ls.dir))) / ls.pdf);
        }
        if (lights()) L += beta * reflected_light(scene, h, rng, f_cos);
        if (last) return false;
        vec3 wi;
        const float pick = rng.uniform();
        if (!surface.sample(pick, vec2(rng.uniform(), rng.uniform()), wi)) return false;
        bsdf_pdf = surface.pdf(wi);
        const vec3 f = f_cos(wi);
        if (!(bsdf_pdf > 0) || f == vec3(0)) return false;
        beta *= f / bsdf_pdf;
        ray = Ray{scene.offset_origin(h, wi), wi};
        return true;
    }

    vec3 radiance(Ray ray, Rng& rng) const {
        vec3 L(0), beta(1);
        bool specular_bounce = true;  // the camera ray counts as specular for MIS
        float last_bsdf_pdf = 0;
        const Probe& probe = scene.probe();
        for (int depth = 0; depth < opt.max_depth; ++depth) {
            Hit hit = intersect(ray);
            // An area light's face seen by the camera or through mirrors and glass ends the path
            // there, as in the progressive renderer. After diffuse and principled vertices its
            // light was sampled by next-event estimation: counting the face too would double it.
            if (specular_bounce && lights()) {
                const vec3 Le = scene.lights().emitted(ray, hit ? hit.t : INFINITY);
                if (Le != vec3(0)) {
                    L += beta * Le;
                    break;
                }
            }
            if (!hit) {
                if (depth == 0) return opt.show_probe ? probe.radiance(ray.dir) : vec3(0);
                vec3 Le = probe.radiance(ray.dir);
                float w = specular_bounce ? 1.0f : power_heuristic(last_bsdf_pdf, probe.pdf(ray.dir));
                L += beta * Le * w;
                break;
            }
            const Surface& s = *hit.surface;
            bool diffuse = !s.is_virtual || s.material.kind == Material::Kind::Diffuse;
            // An emissive object is one of the lights: after a diffuse or principled vertex its
            // light was sampled there, so only the camera and mirrors and glass see it here.
            if (specular_bounce || !lights()) L += beta * emitted_radiance(s);
            if (!s.is_virtual && s.gloss_f0 > 0) {
                if (!glossy_real(hit, ray, beta, L, depth + 1 >= opt.max_depth, rng, last_bsdf_pdf)) break;
                specular_bounce = false;
            } else if (s.is_virtual && s.material.kind == Material::Kind::Principled) {
                const bool last = depth + 1 >= opt.max_depth;
                if (!principled(hit, ray, beta, L, last, rng, last_bsdf_pdf)) break;
                specular_bounce = false;
            } else if (!diffuse) {
                SpecularEvent e = scatter_specular(s.material, hit, ray.dir, rng.uniform());
                beta *= e.weight;
                ray = Ray{scene.offset_origin(hit, e.dir), e.dir};
                specular_bounce = true;
            } else {
                vec3 rho = s.reflectance_at(hit.uv);
                vec3 n = facing_normal(hit.ns, ray.dir);
                vec3 ng = facing_normal(hit.ng, ray.dir);
                // At the depth limit no bounce ray follows to pick up its MIS share of the
                // probe: next-event estimation then takes all of it.
                const bool last = depth + 1 >= opt.max_depth;
                ProbeSample ls = probe.sample(rng.uniform(), rng.uniform(), rng.uniform());
                float cos_l = glm::dot(n, ls.dir);
                if (ls.pdf > 0 && cos_l > 0 && glm::dot(ng, ls.dir) > 0) {
                    Hit h = hit;
                    h.ng = ng;
                    if (!occluded(Ray{scene.offset_origin(h, ls.dir), ls.dir}))
                        L += beta * rho * kInvPi * ls.radiance * (cos_l / ls.pdf) *
                             (last ? 1.0f : power_heuristic(ls.pdf, cos_l * kInvPi));
                }
                Hit h = hit;
                h.ng = ng;
                h.ns = n;
                // Real surfaces too: their change by a light is rho/pi * E of its light.
                if (lights())
                    L += beta * rho * reflected_light(scene, h, rng, [&](const vec3& w) {
                        const float c = glm::dot(n, w);
                        return c > 0 && glm::dot(ng, w) > 0 ? vec3(c * kInvPi) : vec3(0);
                    });
                if (last) break;
                vec3 d = sample_diffuse(h, -ng, vec2(rng.uniform(), rng.uniform()));
                last_bsdf_pdf = std::max(0.0f, glm::dot(n, d)) * kInvPi;
                beta *= rho;  // rho/pi * cos / pdf
                ray = Ray{scene.offset_origin(h, d), d};
                specular_bounce = false;
            }
            if (depth >= 3) {  // Russian roulette on the path's throughput
                float q = std::min(0.95f, std::max({beta.x, beta.y, beta.z}));
                if (q <= 0 || rng.uniform() >= q) break;
                beta /= q;
            }
        }
        return L;
    }
};

}  // namespace

Ray reference_camera_ray(const RenderScene& scene, uint64_t seed, int x, int y, uint64_t sample) {
    const uint64_t pixel = uint64_t(y) * uint64_t(scene.camera().width()) + uint64_t(x);
    Rng shift_rng = rng_stream::reference_pixel_shift(seed, pixel);
    const vec2 shift(shift_rng.uniform(), shift_rng.uniform());
    const vec2 j = r2_point(sample, shift) - vec2(0.5f);
    return scene.camera_ray(float(x) + j.x, float(y) + j.y);
}

vec3 reference_radiance(const RenderScene& scene, const ReferenceOptions& options, const Ray& ray,
                        uint64_t pixel, int sample) {
    Rng rng = rng_stream::reference_second_path(options.seed, pixel, uint64_t(sample));
    return PathTracer{scene, options}.radiance(ray, rng);
}

Image render_reference(const RenderScene& scene, const ReferenceOptions& options,
                       const std::atomic<bool>* cancel, const std::function<void(int, int)>& progress) {
    const int W = scene.camera().width(), H = scene.camera().height();
    Image out(W, H);
    std::atomic<int> rows_done{0};
    PathTracer pt{scene, options};
    tbb::parallel_for(tbb::blocked_range<int>(0, H, 1), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
            if (cancel && cancel->load(std::memory_order_relaxed)) return;
            for (int x = 0; x < W; ++x) {
                uint64_t pixel = uint64_t(y) * W + x;
                dvec3 sum(0);
                for (int s = 0; s < options.samples_per_pixel; ++s) {
                    // A row at thousands of samples per pixel takes seconds: Ctrl-C answers
                    // within a batch of 64 paths.
                    if ((s & 63) == 0 && cancel && cancel->load(std::memory_order_relaxed)) return;
                    Rng rng = rng_stream::reference_path(options.seed, pixel, uint64_t(s));
                    const Ray ray = reference_camera_ray(scene, options.seed, x, y, uint64_t(s));
                    vec3 L = pt.radiance(ray, rng);
                    if (is_finite(L)) sum += dvec3(L);
                }
                out.at(x, y) = vec3(sum / double(std::max(1, options.samples_per_pixel)));
            }
            int done = ++rows_done;
            if (progress) progress(done, H);
        }
    });
    return out;
}

}  // namespace dp
