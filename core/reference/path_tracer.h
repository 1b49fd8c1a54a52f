#pragma once
#include <atomic>
#include <cstdint>
#include <functional>

#include "image/image.h"
#include "assets/render_scene.h"

namespace dp {

/// Options of the reference path tracer.
struct ReferenceOptions {
    int samples_per_pixel = 64;
    int max_depth = 8;
    uint64_t seed = 1;
    /// false: real proxies only (a synthetic photograph); true: with the virtual objects and
    /// the virtual lights.
    bool include_virtual = true;
    /// Camera rays that miss everything see the probe (true) or black (false).
    bool show_probe = true;
};

/// Unbiased path tracing of the whole scene: real proxies with their albedo lit by the probe,
/// and the virtual objects with their materials. Next-event estimation of the probe with
/// multiple importance sampling on diffuse surfaces. The virtual lights by next-event
/// estimation alone at diffuse and principled vertices; an area light's face is seen only by
/// the camera and through mirrors and glass (as in the progressive renderer, whose conventions
/// these are: the face ends the path). Makes synthetic photographs and ground truth. The image depends only on the options, not on the thread count.
/// `progress(done_rows, total_rows)` is called from worker threads.
Image render_reference(const RenderScene& scene, const ReferenceOptions& options,
                       const std::atomic<bool>* cancel = nullptr,
                       const std::function<void(int, int)>& progress = {});

/// Camera ray of sample `sample` in pixel (x, y): sub-pixel positions from the R2 sequence with
/// a per-pixel random shift (r2_point), so a pixel's samples cover it evenly.
Ray reference_camera_ray(const RenderScene& scene, uint64_t seed, int x, int y, uint64_t sample);

/// Radiance along one camera ray (exposed for tests and the per-pixel debugger).
vec3 reference_radiance(const RenderScene& scene, const ReferenceOptions& options, const Ray& ray,
                        uint64_t pixel, int sample);

}  // namespace dp
