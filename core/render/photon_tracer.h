#pragma once
#include <atomic>
#include <cstdint>
#include <vector>

#include "render/photon_map.h"
#include "render/render_scene.h"

namespace dp {

/// Counters of one photon pass, for progress reports and benchmarks.
struct PhotonStats {
    uint64_t emitted = 0;        ///< photons shot at the clusters' disks
    uint64_t hit_virtual = 0;    ///< photons whose first hit is a virtual object
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

/// Shoots `count` photons from the probe at the emission clusters and traces their change to
/// the light (method.md, "Photon distribution"). The result depends only on (seed, pass), not
/// on the number of threads. Checks `cancel` between blocks of photons.
PhotonPass trace_photons(const RenderScene& scene, uint64_t seed, uint64_t pass, int64_t count,
                         const std::atomic<bool>* cancel = nullptr);

}  // namespace dp
