#include "render/photon_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "base/rng.h"
#include "base/sampling.h"
#include "render/photographed_radiance.h"
#include "assets/real_gloss.h"
#include "assets/principled_scatter.h"
#include "assets/scattering.h"

namespace dp {

namespace {

constexpr int64_t kBlock = 1024;

/// A shadow photon's (all its flux at most 0); a light photon's flux is at least 0.
bool is_negative(const Photon& p) { return p.flux.x <= 0 && p.flux.y <= 0 && p.flux.z <= 0; }

/// Per-block output, merged in block order so the photon order is deterministic.
struct Block {
    std::vector<Photon> real, caustic;
    PhotonStats stats;
};

struct Tracer {
    const RenderScene& scene;
    PhotonEmitter emitter;
    int max_depth = 8;

    bool store_first_shadow = true;  ///< false: next-event estimation takes the first landing
    const DirectChange* direct = nullptr;
    PhotonMap probe_map;     ///< this pass's negative probe photons on real surfaces, for the emitters
    double inv_area = 0;     ///< 1 / (pi r^2) of probe_map's gathers
    double inv_light_count = 0;  ///< 1 / the number of light photons

    Tracer(const RenderScene& s, int64_t count, int64_t surround_count, const PhotonPassOptions& o)
        : scene(s), emitter(s, count, surround_count), max_depth(std::max(1, o.max_depth)),
          store_first_shadow(!o.direct_by_rays), direct(o.direct) {}

    /// Whether a shadow photon landing at `hr` (travelling along `dir`) is stored there: always
    /// without the split; under it only where the object nearest to `hr` on the line is glass
    /// (next-event estimation leaves light blocked by glass to the photons, see DirectChange).
    bool stores_first_shadow(const Hit& hr, const vec3& dir, Block& out) const {
        if (store_first_shadow) return true;
        if (!scene.has_transmissive()) return false;
        ++out.stats.rays;
        const Hit nearest = scene.intersect_virtual(Ray{scene.offset_origin(hr, -dir), -dir});
        return nearest && nearest.surface->transmits();
    }

    /// Follows a photon from a known first hit: stores on real surfaces (and caustics on
    /// virtual diffuse ones if `caustics`), bounces until absorbed. Negative photons die on
    /// virtual objects; their first landing is stored only if `store_first`.
    void follow(Hit hit, vec3 dir, vec3 flux, PhotonKind kind, Rng& rng, Block& out, bool caustics = true,
                bool store_first = true) const {
        const bool negative = kind == PhotonKind::Shadow;
        bool specular_only = !negative && caustics;
        const vec3 flux0 = glm::abs(flux);
        const float flux0_max = std::max({flux0.x, flux0.y, flux0.z});
        for (int depth = 0; depth < max_depth; ++depth) {
            if (depth > 0) {
                hit = scene.intersect(Ray{hit.p, dir});  // hit.p already offset below
                ++out.stats.rays;
                if (!hit) return;
            }
            const Surface& s = *hit.surface;
            bool diffuse = !s.is_virtual || s.material.kind == Material::Kind::Diffuse;
            if (!s.is_virtual) {
                if (depth > 0 || store_first) {
                    out.real.push_back({hit.p, flux, facing_normal(hit.ng, dir)});
                    ++out.stats.stored_real;
                }
            } else if (negative) {
                return;
            } else if (diffuse && specular_only && depth > 0) {
                out.caustic.push_back({hit.p, flux, facing_normal(hit.ng, dir)});
                ++out.stats.stored_caustic;
            }
            vec3 next;
            if (!s.is_virtual && s.gloss_f0 > 0) {
                // A glossy real surface reflects photons by its albedo and its gloss: the lamp a
                // varnished floor throws onto the wall, the sky an object no longer lets it.
                if (!glossy_bounce(hit, dir, flux, flux0_max, rng, next)) return;
                specular_only = false;
            } else if (diffuse) {
                vec3 rho = s.reflectance_at(hit.uv);
                float q = std::min(0.98f, std::max({rho.x, rho.y, rho.z}));
                if (q <= 0 || rng.uniform() >= q) return;
                flux *= rho / q;
                next = sample_diffuse(hit, dir, vec2(rng.uniform(), rng.uniform()));
                specular_only = false;
            } else {
                // Mirror, glass, principled: the photon stays on a "specular" chain (caustics),
                // as the camera gather does not gather photons on them either.
                SpecularEvent e = scatter_non_diffuse(s, hit, dir, rng, Transport::Importance);
                if (e.weight == vec3(0)) return;
                flux *= e.weight;
                next = e.dir;
                // Roulette on |flux| relative to the start, never on its signed value.
                vec3 a = glm::abs(flux);
                float q = std::min(1.0f, std::max({a.x, a.y, a.z}) / std::max(flux0_max, 1e-30f));
                if (q <= 0 || rng.uniform() >= q) return;
                flux /= q;
            }
            hit.p = scene.offset_origin(hit, next);
            dir = next;
        }
    }

    /// The next direction of a photon at a real surface with a gloss layer, from the mixture
    /// of its Lambert and gloss lobes (half and half), with roulette on |flux| against the
    /// photon's first flux. False when it is absorbed.
    bool glossy_bounce(const Hit& hit, const vec3& dir, vec3& flux, float flux0_max, Rng& rng, vec3& next) const {
        const GlossySurface surface(hit, dir);
        const float pick = rng.uniform();
        if (!surface.sample(pick, vec2(rng.uniform(), rng.uniform()), next)) return false;
        const vec3 f = surface.eval_cos(next);
        const float pdf = surface.pdf(next);
        if (f == vec3(0) || !(pdf > 0)) return false;
        flux *= f / pdf;
        const vec3 a = glm::abs(flux);
        const float q = std::min(0.98f, std::max({a.x, a.y, a.z}) / std::max(flux0_max, 1e-30f));
        if (q <= 0 || rng.uniform() >= q) return false;
        flux /= q;
        return is_finite(flux);
    }

    void trace_one(Rng& rng, Block& out) const {
        ++out.stats.emitted;
        EmittedPhoton e = emitter.emit(rng);
        if (!e.valid) return;
        const vec3 w = -e.ray.dir, origin = e.ray.org, flux = e.flux;
        const Ray& down = e.ray;
        Hit hv = scene.intersect_virtual(down);
        ++out.stats.rays;
        if (!hv) return;
        Hit hr = scene.intersect_real(down);
        ++out.stats.rays;
        if (hr && hr.t < hv.t) return;  // real geometry shades this path already in the photo
        ++out.stats.rays;
        if (scene.occluded_real(Ray{origin, w})) return;  // the probe never lit this line
        ++out.stats.hit_virtual;
        if (hr) follow(hr, -w, -flux, PhotonKind::Shadow, rng, out, true, stores_first_shadow(hr, -w, out));
        follow(hv, -w, flux, PhotonKind::Light, rng, out);
    }

    /// A photon from a virtual light. All its light is new, so nothing is negative: where it
    /// first lands on a real surface is direct light, which next-event estimation takes (it is
    /// not stored there), and it bounces on from there and from the objects as light photons.
    void trace_light(Rng& rng, Block& out) const {
        ++out.stats.emitted;
        const LightPhoton e = scene.lights().emit(rng, inv_light_count, scene.ray_epsilon());
        if (!e.valid) return;
        const Hit hit = scene.intersect(e.ray);
        ++out.stats.rays;
        if (!hit) return;
        if (hit.surface->is_virtual) ++out.stats.hit_virtual;
        follow(hit, e.ray.dir, e.flux, PhotonKind::Light, rng, out, true, false);
    }

    /// How much a real point's radiance towards -dir has changed, as far as no photon carries
    /// that change on by itself: the direct light the objects block there (rays, one estimate)
    /// and the pass's negative probe photons (which die at the objects). The photo shows a
    /// floor under an object unshadowed, and it must not light the object's underside as if it
    /// were sunlit. Positive photons (a glass ball's caustic) bounce on to the objects alone.
    vec3 emitter_change(const Hit& x, const vec3& dir, Rng& rng, Block& out) const {
        const vec3 n = facing_normal(x.ng, dir);
        dvec3 E(0);
        if (direct) {
            DirectChange::Samples u;
            u.sun = vec2(rng.uniform(), rng.uniform());
            u.sky = vec2(rng.uniform(), rng.uniform());
            u.cone = vec2(rng.uniform(), rng.uniform());
            u.pick = rng.uniform();
            E += direct->estimate(x, n, u, rng, store_first_shadow);
            out.stats.rays += 4;  // about: the samples that reach a cone cost one or two rays
        }
        if (!probe_map.empty()) E += probe_map.gather(x.p, n) * inv_area;
        // Nor the virtual lights' light: their photons go on from real surfaces to the objects.
        if (E == dvec3(0)) return vec3(0);
        return vec3(dvec3(x.surface->reflectance_at(x.uv)) * double(kInvPi) * E);
    }

    /// Light from a real surface at the objects: reflected on (positive photons) and blocked
    /// from the real surface behind them (negative: indirect shadows). No caustic photons: the
    /// display's final gather already sees real surfaces through specular chains.
    void trace_surround(Rng& rng, Block& out) const {
        ++out.stats.emitted;
        const PhotonEmitter::SurroundLine line = emitter.emit_surround_line(rng);
        if (!line.valid) return;
        const vec3 down = -line.w;
        // The first object on the line, then the first real surface beyond it towards +w: the
        // emitter. Searching from the disk instead would miss every line whose disk point lies
        // behind a wall or under a floor that cuts through the cluster's sphere.
        const Hit hv = scene.intersect_virtual(Ray{line.origin, down});
        ++out.stats.rays;
        if (!hv) return;
        // From just inside the object (the search ignores it): a real surface that touches the
        // object, such as the floor under a box standing on it, is still the emitter.
        const float eps = scene.ray_epsilon();
        const Hit x = scene.intersect_real(Ray{hv.p - line.w * eps, line.w});
        ++out.stats.rays;
        if (!x) return;  // the probe: the probe photons carry that light
        // Blocked: the radiance the emitter had (the photograph). Reflected: what it has now.
        const vec3 old_radiance = photographed_radiance(scene, x, line.w, rng);
        const vec3 new_radiance = old_radiance + emitter_change(x, line.w, rng, out);
        if (!is_finite(old_radiance) || !is_finite(new_radiance)) return;
        const Hit hr = scene.intersect_real(Ray{hv.p + down * eps, down});
        ++out.stats.rays;
        ++out.stats.surround_hit_virtual;
        if (hr && old_radiance != vec3(0))
            follow(hr, down, -vec3(dvec3(old_radiance) * line.flux_per_radiance), PhotonKind::Shadow, rng, out, true,
                   stores_first_shadow(hr, down, out));
        if (new_radiance != vec3(0))
            follow(hv, down, vec3(dvec3(new_radiance) * line.flux_per_radiance), PhotonKind::Light, rng, out, false);
    }
};

}  // namespace

PhotonEmitter::PhotonEmitter(const RenderScene& scene, int64_t count, int64_t surround_count)
    : scene_(scene),
      inv_count_(1.0 / double(std::max<int64_t>(1, count))),
      inv_surround_count_(surround_count > 0 ? 1.0 / double(surround_count) : 0.0) {
    std::vector<double> w;
    for (const EmissionCluster& c : scene.clusters()) w.push_back(double(c.radius) * c.radius);
    cluster_table_ = AliasTable(w);
    const auto& cl = scene.clusters();
    if (cl.empty()) return;
    global_center_ = cl[0].center;
    global_radius_ = cl[0].radius;
    for (size_t i = 1; i < cl.size(); ++i)
        enclose(global_center_, global_radius_, cl[i].center, cl[i].radius, global_center_, global_radius_);
}

EmittedPhoton PhotonEmitter::emit(Rng& rng) const {
    EmittedPhoton e;
    size_t k = cluster_table_.sample(rng.uniform_double());
    const EmissionCluster& c = scene_.clusters()[k];
    const Probe& probe = scene_.probe();
    ProbeSample ps = probe.sample(rng.uniform(), rng.uniform(), rng.uniform());
    if (ps.pdf <= 0) return e;
    double pmf = probe.pixel_pmf(ps.pixel) * cluster_table_.pmf(k);
    if (pmf <= 0) return e;
    // Flux through the cluster's cross-section from this probe pixel, per photon.
    int row = int(ps.pixel / size_t(probe.width()));
    double scale = probe.pixel_solid_angle(row) * kPi * double(c.radius) * c.radius * inv_count_ / pmf;
    e.flux = vec3(dvec3(ps.radiance) * scale);
    const vec3 w = ps.dir;
    Frame frame(w);
    vec2 d = sample_concentric_disk(vec2(rng.uniform(), rng.uniform())) * c.radius;
    vec3 disk = c.center + c.radius * w + frame.t * d.x + frame.b * d.y;
    const vec3 origin = outside_all_clusters(disk, w);
    if (owned_by_earlier_cluster(k, origin, w)) return e;
    e.ray = Ray{origin, -w};
    e.valid = true;
    return e;
}

vec3 PhotonEmitter::outside_all_clusters(const vec3& point, const vec3& w) const {
    const vec3 oc = point - global_center_;
    const float b = glm::dot(oc, w), cc = glm::dot(oc, oc) - global_radius_ * global_radius_;
    const float s_exit = -b + std::sqrt(std::max(0.0f, b * b - cc));
    return point + w * (std::max(0.0f, s_exit) + scene_.ray_epsilon());
}

bool PhotonEmitter::owned_by_earlier_cluster(size_t k, const vec3& point, const vec3& w) const {
    for (size_t j = 0; j < k; ++j) {
        const vec3 to_c = scene_.clusters()[j].center - point;
        const vec3 perp = to_c - glm::dot(to_c, w) * w;
        if (glm::dot(perp, perp) < scene_.clusters()[j].radius * scene_.clusters()[j].radius) return true;
    }
    return false;
}

PhotonEmitter::SurroundLine PhotonEmitter::emit_surround_line(Rng& rng) const {
    SurroundLine line;
    const size_t k = cluster_table_.sample(rng.uniform_double());
    const EmissionCluster& c = scene_.clusters()[k];
    const double pmf = cluster_table_.pmf(k);
    if (pmf <= 0) return line;
    line.w = sample_uniform_sphere(vec2(rng.uniform(), rng.uniform()));
    const Frame frame(line.w);
    const vec2 d = sample_concentric_disk(vec2(rng.uniform(), rng.uniform())) * c.radius;
    line.through = c.center + frame.t * d.x + frame.b * d.y;
    if (owned_by_earlier_cluster(k, line.through, line.w)) return line;
    line.origin = outside_all_clusters(line.through, line.w);
    // Radiance L through the disk (area pi R^2) from a direction of pdf 1 / (4 pi).
    line.flux_per_radiance = 4.0 * kPi * kPi * double(c.radius) * c.radius * inv_surround_count_ / pmf;
    line.valid = true;
    return line;
}

PhotonPass trace_photons(const RenderScene& scene, uint64_t seed, uint64_t pass, int64_t count,
                         const std::atomic<bool>* cancel, PhotonPassOptions options) {
    PhotonPass result;
    if (count <= 0) return result;
    // Probe photons need objects to meet; light photons only lights.
    const bool objects = scene.has_virtual() && scene.probe().total_luminance_power() > 0;
    const int64_t probe = objects ? count : 0;
    const int64_t lights = scene.lights().total_power() > 0 ? count : 0;
    const int64_t surround = objects && options.from_surroundings ? count / kSurroundPhotonDivisor : 0;
    if (probe + lights == 0) return result;
    Tracer tracer(scene, count, surround, options);
    tracer.inv_light_count = lights > 0 ? 1.0 / double(lights) : 0.0;
    // Blocks in order: the probe photons, the light photons, the surroundings' photons (never
    // two kinds in one block). Photon i of the pass is numbered across all three.
    auto blocks = [](int64_t n) { return (n + kBlock - 1) / kBlock; };
    const int64_t probe_blocks = blocks(probe), light_blocks = blocks(lights);
    std::vector<Block> out(size_t(probe_blocks + light_blocks + blocks(surround)));
    auto run = [&](int64_t first_block, int64_t last_block) {
        tbb::parallel_for(tbb::blocked_range<int64_t>(first_block, last_block, 1), [&](const tbb::blocked_range<int64_t>& r) {
            for (int64_t b = r.begin(); b < r.end(); ++b) {
                if (cancel && cancel->load(std::memory_order_relaxed)) return;
                const int kind = b < probe_blocks ? 0 : b < probe_blocks + light_blocks ? 1 : 2;
                const int64_t first = kind == 0 ? 0 : kind == 1 ? probe : probe + lights;
                const int64_t n = kind == 0 ? probe : kind == 1 ? lights : surround;
                const int64_t local = b - (kind == 0 ? 0 : kind == 1 ? probe_blocks : probe_blocks + light_blocks);
                const int64_t begin = first + local * kBlock, end = first + std::min(n, (local + 1) * kBlock);
                for (int64_t i = begin; i < end; ++i) {
                    Rng rng = rng_stream::photon(seed, uint64_t(pass), uint64_t(i));
                    if (kind == 0)
                        tracer.trace_one(rng, out[b]);
                    else if (kind == 1)
                        tracer.trace_light(rng, out[b]);
                    else
                        tracer.trace_surround(rng, out[b]);
                }
            }
        });
    };
    run(0, probe_blocks + light_blocks);
    if (surround > 0 && options.emitter_radius > 0) {
        // The probe photons first: the surroundings' emitters see the change they make. Only
        // the negative ones: they die at the objects, while a positive photon bounces on to
        // them by itself and an emitter sending its light too counted it twice (the floor in
        // a gold ball's shadow came out 1% bright, docs/method-notes.md).
        std::vector<Photon> first_real;
        for (int64_t b = 0; b < probe_blocks; ++b)
            for (const Photon& ph : out[b].real)
                if (is_negative(ph)) first_real.push_back(ph);
        tracer.probe_map.build(std::move(first_real), options.emitter_radius);
        tracer.inv_area = 1.0 / (double(kPi) * options.emitter_radius * options.emitter_radius);
    }
    run(probe_blocks + light_blocks, int64_t(out.size()));
    // Merge blocks in order (deterministic), copying in parallel into precomputed offsets.
    const int64_t merged = int64_t(out.size());
    std::vector<size_t> real_at(merged + 1, 0), caustic_at(merged + 1, 0);
    for (int64_t b = 0; b < merged; ++b) {
        real_at[b + 1] = real_at[b] + out[b].real.size();
        caustic_at[b + 1] = caustic_at[b] + out[b].caustic.size();
        result.stats.emitted += out[b].stats.emitted;
        result.stats.hit_virtual += out[b].stats.hit_virtual;
        result.stats.surround_hit_virtual += out[b].stats.surround_hit_virtual;
        result.stats.stored_real += out[b].stats.stored_real;
        result.stats.stored_caustic += out[b].stats.stored_caustic;
        result.stats.rays += out[b].stats.rays;
    }
    result.real.resize(real_at[merged]);
    result.caustic.resize(caustic_at[merged]);
    tbb::parallel_for(int64_t(0), merged, [&](int64_t b) {
        std::copy(out[b].real.begin(), out[b].real.end(), result.real.begin() + real_at[b]);
        std::copy(out[b].caustic.begin(), out[b].caustic.end(), result.caustic.begin() + caustic_at[b]);
    });
    return result;
}

}  // namespace dp
