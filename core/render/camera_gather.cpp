#include "render/camera_gather.h"

#include <algorithm>
#include <cmath>

#include "render/light_estimate.h"
#include "render/photographed_radiance.h"
#include "assets/real_gloss.h"
#include "assets/principled_scatter.h"
#include "assets/scattering.h"

namespace dp {

namespace {
// Glass is split into both branches for the first few interfaces (less noise on the glass
// itself), then chosen by Russian roulette.
constexpr int kGlassSplits = 2;
constexpr int kDiffuseGatherDepth = 3;

}  // namespace

int camera_diffuse_samples(int64_t photons_per_pass, size_t pixels_near_virtual) {
    const double balanced = double(photons_per_pass) / (4.0 * double(std::max<size_t>(1, pixels_near_virtual)));
    return int(std::clamp(std::floor(balanced), 2.0, 8.0));
}

CameraGather::CameraGather(const RenderScene& scene, const PassMaps& maps, int camera_diffuse_samples,
                           const DirectChange* direct, int max_depth)
    : scene_(scene), maps_(maps), direct_(direct), camera_diffuse_samples_(std::max(1, camera_diffuse_samples)),
      max_depth_(std::max(1, max_depth)) {
    inv_area_ = maps.radius > 0 ? 1.0 / (double(kPi) * maps.radius * maps.radius) : 0.0;
}

vec3 CameraGather::real_dL(const Hit& hit, const vec3& dir, Rng& rng, const DirectSamples* direct, bool gather,
                           float* photon) const {
    const vec3 n = facing_normal(hit.ng, dir);
    dvec3 E(0), E_photons(0);
    if (direct_ && direct && direct->weight > 0)
        E += direct_->estimate(hit, n, direct->u, rng) * direct->weight;
    // The virtual lights' direct light: all of it is a change (the photo never had it).
    if (direct && direct->weight > 0 && !scene_.lights().empty())
        E += dvec3(light_irradiance(scene_, hit, n, rng)) * direct->weight;
    if (gather && !maps_.real.empty()) E_photons = maps_.real.gather(hit.p, n) * inv_area_;
    if (E == dvec3(0) && E_photons == dvec3(0)) return vec3(0);
    const dvec3 rho_over_pi = dvec3(hit.surface->reflectance_at(hit.uv)) * double(kInvPi);
    if (photon) *photon = float(luminance(rho_over_pi * E_photons));
    return vec3(rho_over_pi * (E + E_photons));
}

vec3 CameraGather::gloss_change(const Hit& hit, const vec3& dir, const vec2& u, Rng& rng, int depth) const {
    const GlossLobe lobe(hit, dir);
    if (!lobe.valid()) return vec3(0);
    vec3 dL(0);
    // The lights' highlights: next-event estimation and the sampled ray, by MIS.
    auto lobe_pdf = [&](const vec3& w) { return lobe.pdf(w); };
    if (!scene_.lights().empty())
        dL += reflected_light(scene_, hit, rng, [&](const vec3& w) { return vec3(lobe.eval_cos(w)); }, lobe_pdf);
    dL -= hidden_sun(hit, lobe, rng);  // whether or not the lobe's own sample below is drawn
    vec3 wi;
    float weight = 0;
    if (!lobe.sample(u, wi, weight)) return dL;
    const Ray ray{scene_.offset_origin(hit, wi), wi};
    const Hit hv = scene_.intersect_virtual(ray), hr = scene_.intersect_real(ray);
    const Hit& first = hv && (!hr || hv.t < hr.t) ? hv : hr;
    vec3 change = lights_seen(scene_, ray, first, lobe.pdf(wi));
    if (hv && (!hr || hv.t < hr.t)) {
        // An object now, where the photo shows what is behind it reflected.
        const vec3 now = radiance_at(hv, ray, rng, depth + 1, false, kGlassSplits, true);
        vec3 before;
        if (hr) {
            before = photographed_radiance(scene_, hr, wi, rng);
        } else {
            // The probe; in its sun, shared with hidden_sun's samples by MIS.
            const float sun = scene_.probe_lights().sun_pdf(wi);
            before = scene_.probe().radiance(wi) * (sun > 0 ? power_heuristic(lobe.pdf(wi), sun) : 1.0f);
        }
        change += now - before;
    } else if (hr) {
        const DirectSamples direct = DirectSamples::from(rng);
        change += real_dL(hr, wi, rng, &direct);  // a shadow or caustic on the real surface reflected
    }
    if (is_finite(change)) dL += weight * change;
    return dL;
}

vec3 CameraGather::hidden_sun(const Hit& hit, const GlossLobe& lobe, Rng& rng) const {
    const ProbeLights& lights = scene_.probe_lights();
    if (!lights.has_sun()) return vec3(0);
    const ProbeSample ls = lights.sample_sun(vec2(rng.uniform(), rng.uniform()));
    const float f = ls.pdf > 0 ? lobe.eval_cos(ls.dir) : 0.0f;
    if (!(f > 0)) return vec3(0);
    // The photo reflects the sun here unless a real surface hides it; now an object may.
    const Ray ray{scene_.offset_origin(hit, ls.dir), ls.dir};
    if (!scene_.intersect_virtual(ray) || scene_.occluded_real(ray)) return vec3(0);
    const vec3 v = ls.radiance * (f / ls.pdf * power_heuristic(ls.pdf, lobe.pdf(ls.dir)));
    return is_finite(v) ? v : vec3(0);
}

vec3 CameraGather::real_radiance(const Hit& hit, const vec3& dir, Rng& rng, int depth) const {
    const DirectSamples direct = DirectSamples::from(rng);
    vec3 L = photographed_radiance(scene_, hit, dir, rng) + real_dL(hit, dir, rng, &direct);
    // The photo's gloss reflected the sky where the object now stands over the floor: seen
    // from the object's underside, the floor must reflect the object (a clay ball's bottom
    // came out 2.5% bright on the polished-floor benchmark scene without it).
    if (hit.surface->gloss_f0 > 0 && depth < kDiffuseGatherDepth)
        L += gloss_change(hit, dir, vec2(rng.uniform(), rng.uniform()), rng, depth);
    return L;
}

vec3 CameraGather::virtual_diffuse_radiance(const Hit& hit, const vec3& dir, Rng& rng, int depth, int samples,
                                      const PixelSampler* sampler) const {
    const Surface& s = *hit.surface;
    const vec3 rho = s.reflectance_at(hit.uv);
    const vec3 n = facing_normal(hit.ns, dir);
    const vec3 ng = facing_normal(hit.ng, dir);
    const Probe& probe = scene_.probe();
    const ProbeLights& lights = scene_.probe_lights();
    const bool bounce = depth < kDiffuseGatherDepth;
    Hit h = hit;
    h.ng = ng;
    h.ns = n;
    vec3 sum(0);
    for (int k = 0; k < samples; ++k) {
        vec2 u_sun, u_sky, u_bounce;
        if (sampler) {
            PixelSampler sk = sampler->with_index(sampler->index() * uint32_t(samples) + uint32_t(k));
            u_sun = sk.next2d();
            u_sky = sk.next2d();
            u_bounce = sk.next2d();
        } else {
            u_sun = vec2(rng.uniform(), rng.uniform());
            u_sky = vec2(rng.uniform(), rng.uniform());
            u_bounce = vec2(rng.uniform(), rng.uniform());
        }
        // The sun and the sky by next-event estimation, each MIS-weighted against the cosine
        // bounce below (the only other strategy that reaches their directions).
        for (const ProbeSample& ls : {lights.sample_sun(u_sun), lights.sample_sky(u_sky)}) {
            const float cos_l = glm::dot(n, ls.dir);
            if (ls.pdf <= 0 || cos_l <= 0 || glm::dot(ng, ls.dir) <= 0) continue;
            if (scene_.occluded(Ray{scene_.offset_origin(h, ls.dir), ls.dir})) continue;
            const float weight = bounce ? power_heuristic(ls.pdf, cos_l * kInvPi) : 1.0f;
            sum += ls.radiance * (cos_l / ls.pdf) * weight * kInvPi;
        }
        // The virtual lights, each by next-event estimation alone.
        if (!scene_.lights().empty())
            sum += reflected_light(scene_, h, rng, [&](const vec3& w) {
                const float c = glm::dot(n, w);
                return c > 0 && glm::dot(ng, w) > 0 ? vec3(c * kInvPi) : vec3(0);
            });
        if (!bounce) continue;
        // One cosine-weighted bounce: real surroundings (the photo), other virtual objects, probe.
        vec3 d = sample_diffuse(h, -ng, u_bounce);
        Ray ray{scene_.offset_origin(h, d), d};
        Hit next = scene_.intersect(ray);
        if (!next) {
            float bsdf_pdf = std::max(0.0f, glm::dot(n, d)) * kInvPi;
            sum += probe.radiance(d) * power_heuristic(bsdf_pdf, lights.pdf(d));
        } else {
            sum += radiance_at(next, ray, rng, depth + 1, true, kGlassSplits);
        }
    }
    vec3 L = rho * sum / float(samples);
    // Caustics arriving through virtual glass and mirrors (once: it does not depend on samples).
    if (!maps_.caustic.empty())
        L += vec3(dvec3(rho) * (double(kInvPi) * inv_area_) * maps_.caustic.gather(hit.p, ng));
    return L;
}

vec3 CameraGather::incoming(const Ray& ray, Rng& rng, int depth, bool from_diffuse, int splits) const {
    return radiance_at(scene_.intersect(ray), ray, rng, depth, from_diffuse, splits);
}

vec3 CameraGather::radiance_at(const Hit& hit, const Ray& ray, Rng& rng, int depth, bool from_diffuse,
                         int splits, bool lights_sampled) const {
    // An area light's face in front of the surface (the lights are not in the BVH). After a
    // diffuse bounce the caustic map carries the lights' light through specular chains.
    if (!from_diffuse && !lights_sampled && !scene_.lights().empty()) {
        const vec3 Le = scene_.lights().emitted(ray, hit ? hit.t : INFINITY);
        if (Le != vec3(0)) return Le;
    }
    if (!hit) return from_diffuse ? vec3(0) : scene_.probe().radiance(ray.dir);
    if (!hit.surface->is_virtual) return real_radiance(hit, ray.dir, rng, depth);
    if (hit.surface->material.kind == Material::Kind::Diffuse)
        return virtual_diffuse_radiance(hit, ray.dir, rng, depth, 1);
    if (hit.surface->material.kind == Material::Kind::Principled)
        return principled_radiance(hit, ray.dir, rng, depth, from_diffuse, splits, nullptr, lights_sampled);
    return specular_radiance(hit, ray.dir, rng, depth, from_diffuse, splits);
}

vec3 CameraGather::specular_radiance(const Hit& hit, const vec3& dir, Rng& rng, int depth, bool from_diffuse,
                               int splits) const {
    if (depth >= max_depth_) return vec3(0);
    const Material& m = hit.surface->material;
    auto follow = [&](const SpecularEvent& e, int splits_left) {
        if (e.weight == vec3(0)) return vec3(0);
        Ray r{scene_.offset_origin(hit, e.dir), e.dir};
        return e.weight * incoming(r, rng, depth + 1, from_diffuse, splits_left);
    };
    if (m.kind == Material::Kind::Glass && splits > 0) {
        SpecularEvent refl, refr;
        split_glass(m, hit, dir, refl, refr);
        return follow(refl, splits - 1) + follow(refr, splits - 1);
    }
    return follow(scatter_specular(m, hit, dir, rng.uniform()), 0);
}

vec3 CameraGather::principled_radiance(const Hit& hit, const vec3& dir, Rng& rng, int depth, bool from_diffuse,
                                       int splits, PixelSampler* sampler, bool lights_sampled) const {
    // Emission is a light (LightSet's emitters): seen where the lights' faces are, taken by
    // next-event estimation and the light photons elsewhere.
    vec3 L = from_diffuse || lights_sampled ? vec3(0) : emitted_radiance(*hit.surface);
    if (depth >= max_depth_) return L;
    const PrincipledBsdf bsdf = principled_at(*hit.surface, hit);
    const ProbeLights& lights = scene_.probe_lights();
    auto next2 = [&] { return sampler ? sampler->next2d() : vec2(rng.uniform(), rng.uniform()); };
    const vec2 u_sun = next2(), u_sky = next2(), u_pick = next2(), u_dir = next2();
    if (!from_diffuse) {
        for (const ProbeSample& ls : {lights.sample_sun(u_sun), lights.sample_sky(u_sky)}) {
            if (ls.pdf <= 0) continue;
            const vec3 f = eval_principled(bsdf, hit, dir, ls.dir, Transport::Radiance);
            if (f == vec3(0) || scene_.occluded(Ray{scene_.offset_origin(hit, ls.dir), ls.dir})) continue;
            const float w = power_heuristic(ls.pdf, pdf_principled(bsdf, hit, dir, ls.dir));
            L += f * ls.radiance * (w / ls.pdf);
        }
        L += reflected_light(
            scene_, hit, rng, [&](const vec3& w) { return eval_principled(bsdf, hit, dir, w, Transport::Radiance); },
            [&](const vec3& w) { return pdf_principled(bsdf, hit, dir, w); });
    }
    const PrincipledEvent e = sample_principled(bsdf, hit, dir, vec3(u_dir, u_pick.x), Transport::Radiance);
    if (e.weight == vec3(0)) return L;
    const Ray ray{scene_.offset_origin(hit, e.dir), e.dir};
    const Hit next = scene_.intersect(ray);
    if (!from_diffuse) L += e.weight * lights_seen(scene_, ray, next, e.pdf);  // MIS with the lights' samples
    if (!next) {
        if (!from_diffuse) L += e.weight * scene_.probe().radiance(e.dir) * power_heuristic(e.pdf, lights.pdf(e.dir));
        return L;
    }
    // The lights were sampled above (or are in the caustic map): their faces add nothing here.
    const vec3 Li = radiance_at(next, ray, rng, depth + 1, from_diffuse, splits, true);
    return is_finite(Li) ? L + e.weight * Li : L;
}

SampleResult CameraGather::shade_camera(int x, int y, float px, float py, PixelSampler& sampler, Rng& rng,
                                  const CameraWork& work) const {
    SampleResult r;
    const Ray ray = scene_.camera_ray(px, py);
    const Hit hit = scene_.intersect(ray);
    // A holdout's occluder hides what lies beyond it: the photo, which shows the occluder, stands.
    const float t_hold = scene_.holdout_t(ray);
    if (!scene_.lights().empty()) {
        // An area light's face, seen directly: its glare replaces the photo like an object.
        const vec3 Le = scene_.lights().emitted(ray, std::min(hit ? hit.t : INFINITY, t_hold));
        if (Le != vec3(0)) {
            r.alpha = 1;
            r.pixel_change = Le - scene_.photo().at(x, y);
            return r;
        }
    }
    if (!hit || hit.t > t_hold) return r;  // nothing modelled here, or held out: the photo stands
    if (!hit.surface->is_virtual) {
        const DirectSamples direct = DirectSamples::from(sampler, work.direct_weight);
        r.dL = real_dL(hit, ray.dir, rng, work.direct_weight > 0 ? &direct : nullptr, work.gather, &r.photon);
        if (work.direct_weight > 0 && hit.surface->gloss_f0 > 0)
            r.dL += gloss_change(hit, ray.dir, sampler.next2d(), rng) * float(work.direct_weight);
        r.pixel_change = r.dL;
        return r;
    }
    r.alpha = 1;
    const Material::Kind kind = hit.surface->material.kind;
    const vec3 L = kind == Material::Kind::Diffuse
                       ? virtual_diffuse_radiance(hit, ray.dir, rng, 0, camera_diffuse_samples_, &sampler)
                   : kind == Material::Kind::Principled
                       ? principled_radiance(hit, ray.dir, rng, 0, false, kGlassSplits, &sampler)
                       : specular_radiance(hit, ray.dir, rng, 0, false, kGlassSplits);
    r.pixel_change = L - scene_.photo().at(x, y);
    return r;
}

}  // namespace dp
