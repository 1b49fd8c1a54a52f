#pragma once
#include <atomic>

#include "assets/render_scene.h"
#include "image/image.h"

namespace dp {

/// The denoiser's guides for a scene at the photo's size (denoise_change in image/denoise.h).
struct DenoiseAovs {
    Image albedo;  ///< per pixel, in [0, 1]; 0 where the centre ray hits nothing
    Image normal;  ///< per pixel, unit world-space shading normal facing the camera; 0 for none
};

/// One ray through each pixel centre (as build_frame_plan traces): noise-free, so the denoiser
/// can trust them. Albedo: a real proxy's or virtual diffuse object's reflectance at the hit;
/// for mirrors and glass, that of the diffuse surface seen in them (up to four specular
/// bounces) times the mirror's reflectance or the glass's tint, or just those where the chain
/// leaves the scene. Normal: the first hit's. `cancel` becoming true stops the work between
/// rows (std::runtime_error), so that an edit does not wait for the guides of a stale scene.
DenoiseAovs denoise_aovs(const RenderScene& scene, const std::atomic<bool>* cancel = nullptr);

}  // namespace dp
