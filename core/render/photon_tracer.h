#pragma once
#include <atomic>
#include <cstdint>
#include <vector>

#include "base/rng.h"
#include "render/direct_change.h"
#include "render/photon_map.h"
#include "assets/render_scene.h"

namespace dp {

/// Counters of one photon pass, for progress reports and benchmarks.
struct PhotonStats {
    uint64_t emitted = 0;        ///< photons shot at the clusters' disks and from the lights
    uint64_t hit_virtual = 0;    ///< probe and light photons whose first hit is a virtual object
    uint64_t surround_hit_virtual = 0;  ///< photons from the real surroundings that meet one
    uint64_t stored_real = 0;    ///< signed photons stored on real surfaces
    uint64_t stored_caustic = 0; ///< caustic photons stored on virtual diffuse surfaces
    uint64_t rays = 0;           ///< Embree queries issued (intersect and occlusion)
};

/// The photons of one pass: signed photons on real surfaces, and caustic photons (probe ->
/// specular virtual surfaces -> virtual diffuse surface) on virtual surfaces.
struct PhotonPass {
    std::vector<Photon> real;
    std::vector<Photon> caustic;
    PhotonStats stats;
};

/// A photon's start: the ray from outside all clusters towards the objects, and its flux.
struct EmittedPhoton {
    Ray ray;         ///< travels along -w from outside every cluster
    vec3 flux{0};    ///< RGB flux through the cluster's cross-section, per photon
    bool valid = false;  ///< false: a black pixel, or a line an earlier cluster owns
};

/// Samples photon starts (docs/method-notes.md, "Photons"): a cluster by cross-section, a
/// probe pixel by the luminance of its flux, a direction inside it, a point on the cluster's
/// disk; lines crossing several clusters belong to the first one.
class PhotonEmitter {
public:
    /// `count` probe photons and `surround_count` photons from the real surroundings per pass.
    PhotonEmitter(const RenderScene& scene, int64_t count, int64_t surround_count = 0);
    EmittedPhoton emit(Rng& rng) const;

    /// A line towards the objects for light from the real surroundings: a cluster by
    /// cross-section, a direction `w` uniform on the sphere, a point on the cluster's disk
    /// (through its centre, across `w`). `origin` is where the line enters the sphere around all
    /// clusters on the `w` side; the emitter is the first real surface beyond the first virtual
    /// object that the line meets from there. A photon's flux is its radiance times
    /// `flux_per_radiance`.
    struct SurroundLine {
        vec3 through{0}, w{0}, origin{0};
        double flux_per_radiance = 0;
        bool valid = false;  ///< false: a line an earlier cluster owns
    };
    SurroundLine emit_surround_line(Rng& rng) const;

private:
    /// A line through several clusters is owned by the first one it crosses.
    bool owned_by_earlier_cluster(size_t k, const vec3& point, const vec3& w) const;
    /// The point where the line through `point` along `w` leaves the sphere around all clusters
    /// on the `w` side (plus an epsilon): from there a ray along -w meets every virtual object.
    vec3 outside_all_clusters(const vec3& point, const vec3& w) const;

    const RenderScene& scene_;
    AliasTable cluster_table_;
    vec3 global_center_{0};
    float global_radius_ = 0;
    double inv_count_ = 1, inv_surround_count_ = 0;
};

/// Photons from the real surroundings per probe photon: light that real surfaces send at the
/// objects, reflected onto other real surfaces or blocked from them (past the paper).
inline constexpr int64_t kSurroundPhotonDivisor = 4;

/// What a photon pass carries.
struct PhotonPassOptions {
    int max_depth = 8;  ///< segments a photon path may have
    /// False leaves the surroundings' photons out (tests of the probe photons).
    bool from_surroundings = true;
    /// True under the split estimator: the light a virtual object blocks from the first real
    /// surface behind it is left to next-event estimation (DirectChange), so shadow photons are
    /// not stored where they first land; they still bounce on, carrying the indirect change.
    bool direct_by_rays = false;
    /// The light a real surface sends at the objects is its radiance now, not as photographed:
    /// the photograph plus the light the pass's negative probe photons take away there
    /// (gathered with this radius; 0 leaves them out; positive ones bounce on to the objects by
    /// themselves) and, with `direct`, the direct change by rays (under the
    /// all-photon estimator only the light of real surfaces the objects block, the probe's
    /// being in the probe photons).
    float emitter_radius = 0;
    const DirectChange* direct = nullptr;
};

/// Shoots `count` photons from the probe at the emission clusters and traces their change to
/// the light (docs/method-notes.md, "Photons"), `count` photons from the virtual lights (when
/// there are any; docs/lights.md), then count / kSurroundPhotonDivisor photons
/// of light from the real surroundings at the same clusters (their photographed radiance where
/// they are blocked, their radiance as the probe photons and rays change it where an object
/// reflects it on).
/// The result depends only on (seed, pass), not on the number of threads. Checks `cancel`
/// between blocks of photons.
PhotonPass trace_photons(const RenderScene& scene, uint64_t seed, uint64_t pass, int64_t count,
                         const std::atomic<bool>* cancel = nullptr, PhotonPassOptions options = {});

}  // namespace dp
