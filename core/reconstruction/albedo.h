#pragma once
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "assets/render_scene.h"
#include "image/image.h"

namespace dp {

/// Settings of the per-texel albedo estimate.
struct AlbedoTextureOptions {
    /// Texture size; 0 derives it from `max_resolution` and the proxy's aspect (planes).
    int width = 0, height = 0;
    int max_resolution = 256;
    /// Points per texel side: each texel is sampled at n x n points, each projected into the
    /// photo (nearest pixel) and given its own share of the probe samples.
    int subsamples = 3;
    /// Probe samples per texel for the irradiance E (split among the texel's points), half
    /// drawn by the probe's flux and half cosine-distributed.
    int probe_samples = 512;
    /// Cosine-distributed rays per texel for the light other real surfaces reflect onto the
    /// texel (0: probe light only, the paper's E). A diffuse surface sends the same radiance in
    /// every direction, so where the camera sees the surface hit, that radiance is the photo's
    /// pixel; elsewhere it is the proxy's constant albedo times its direct irradiance over pi.
    int bounce_samples = 64;
    /// Photo value (after the project's exposure) at or above which a channel counts as
    /// clipped; infinity for an HDR photo.
    float clip_level = INFINITY;
    /// Texels whose irradiance is below this fraction of the median texel's are "unlit": the
    /// photo there is too dark to divide by.
    float min_irradiance_fraction = 1e-3f;
    uint64_t seed = 1;
};

/// An estimated albedo texture, the mask of the texels that carry no estimate of their own, and
/// how well the estimate went.
struct AlbedoTexture {
    /// rho = pi L / E per texel in the proxy's UV layout, clamped to [0, 0.98]; flagged texels
    /// are filled from their valid neighbours.
    Image albedo;
    /// Why a texel carries no estimate of its own, per texel: red 1 = every photo pixel it
    /// projects to is clipped; green 1 = the camera does not see it (outside the photo, facing
    /// away, hidden by real geometry, or only in pixels that also show another surface or the
    /// background); blue 1 = unlit (E too small). All zero for a texel estimated from the photo.
    Image mask;
    /// Texel counts: estimated, and flagged red, green and blue in `mask`.
    size_t valid = 0, clipped = 0, unseen = 0, unlit = 0;
    /// Mean relative Monte Carlo standard error of the probe part of E over the valid texels
    /// (the photo's own noise is not in it).
    double irradiance_rel_error = 0;
    /// Share of the valid texels' summed E that other real surfaces reflect (0 without bounces).
    double bounce_fraction = 0;
    /// Mean rho over the valid texels, per channel, each texel counted once.
    vec3 mean_albedo{0.0f};
};

/// Estimates the albedo texture of real proxy `proxy` (index into project.real) from the
/// scene's photo and probe: for every texel centre-region point of the proxy's UV layout (every
/// face of a box maps onto the whole texture, so a box texel gathers all its faces), the world
/// point is projected into the photo and rho = pi * sum(L) / sum(E), with E the probe
/// irradiance under real-geometry visibility plus (`bounce_samples`) the light reflected by the
/// other real surfaces. Throws InputError (field "real[i]") for a sphere proxy, a mesh without
/// UVs, or a proxy the photo never sees lit.
AlbedoTexture estimate_albedo_texture(const RenderScene& scene, int proxy,
                                      const AlbedoTextureOptions& options = {});

/// Indices into `project.real` of the proxies an albedo texture can be estimated for: planes,
/// boxes and meshes (a sphere has no texture layout).
std::vector<size_t> texturable_real_proxies(const Project& project);

/// Fills texels whose `mask` pixel is non-zero from their valid neighbours, ring by ring.
/// Returns false when there is no valid texel at all (nothing is changed then).
bool fill_flagged_texels(Image& image, const Image& mask);

/// The files attach_albedo_texture writes for proxy `proxy` beside `project_file`: the texture
/// "<project stem>_<proxy name>_albedo.exr" and its mask "..._albedo_mask.exr", absolute.
struct AlbedoTextureFiles {
    std::filesystem::path texture, mask;
};
AlbedoTextureFiles albedo_texture_files(const Project& project, int proxy,
                                        const std::filesystem::path& project_file);

/// Writes an estimated texture (and its mask) next to a project file as
/// "<project stem>_<proxy name>_albedo.exr" (and "..._albedo_mask.exr") and points proxy
/// `proxy` of `project` at it: by its name alone when the project resolves paths in that
/// folder or is about to be saved to `project_file` (`saved_there`), by its absolute path
/// otherwise. Returns the path as written into the project.
std::string attach_albedo_texture(Project& project, int proxy, const AlbedoTexture& texture,
                                  const std::filesystem::path& project_file,
                                  bool saved_there = false);

}  // namespace dp
