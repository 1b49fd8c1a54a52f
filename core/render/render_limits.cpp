#include "render/render_limits.h"
#include "base/text.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "base/error.h"
#include "render/photon_map.h"

namespace dp {
uint64_t pass_memory_bytes(const RenderScene& scene, const RenderSettings& settings) {
    // The probe's photons, a quarter more from the surroundings, as many again from the lights.
    const double per_pass = double(std::max<int64_t>(1, settings.photons_per_pass));
    const double photons = per_pass * (1.25 + (scene.lights().empty() ? 0.0 : 1.0));
    // A stored photon, its 16-byte grid entry and sort scratch; two stored per emitted at most.
    const double per_photon = 2.0 * (double(sizeof(Photon)) + 32.0);
    const double pixels = double(scene.camera().width()) * double(scene.camera().height());
    // Sums, odd-pass sums, plan and the pass's samples (128), and the photon balance's
    // per-pixel variance sums (32).
    const double per_pixel = 160.0;
    const double bytes = photons * per_photon + pixels * per_pixel;
    return bytes >= 1.8e19 ? UINT64_MAX : uint64_t(bytes);
}

void check_render_limits(const RenderScene& scene, const RenderSettings& settings) {
    const uint64_t need = pass_memory_bytes(scene, settings), have = usable_memory_bytes();
    if (have > 0 && double(need) > 0.8 * double(have))
        throw InputError("", "render.photons_per_pass",
                         std::to_string(settings.photons_per_pass) + " photons per pass need about " + format_bytes(double(need)) +
                             " of memory; " + format_bytes(double(have)) + " is usable here (the machine's memory, or its control group's limit where lower)" +
                             " (at most 80% is used): fewer photons per pass and more passes give the same image");
    if (settings.initial_radius) {
        const float r = *settings.initial_radius, scale = scene.scale();
        // The grid's cells are one gather diameter wide: 1e-6 of the scene keeps cell indices
        // within 64 bits; beyond the scene itself every gather holds every photon.
        if (!(r >= 1e-6f * scale) || !(r <= 10.0f * scale)) {
            char buf[160];
            std::snprintf(buf, sizeof(buf), "%g is outside %g to %g for this scene (1e-6 to 10 times its size, %g)",
                          double(r), double(1e-6f * scale), double(10.0f * scale), double(scale));
            throw InputError("", "render.initial_radius", buf);
        }
    }
}

}  // namespace dp
