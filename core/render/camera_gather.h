#pragma once
#include "base/rng.h"
#include "base/sobol.h"
#include "render/direct_change.h"
#include "render/photon_map.h"
#include "assets/render_scene.h"

namespace dp {

class GlossLobe;

/// The photon maps of one pass, gathered with the pass's radius.
struct PassMaps {
    PhotonMap real;     ///< signed photons on real surfaces
    PhotonMap caustic;  ///< caustic photons on virtual diffuse surfaces
    float radius = 0;
};

/// What one camera sample sees, as a change against the photo pixel.
struct SampleResult {
    vec3 pixel_change{0};  ///< L' - L_photo(pixel): what the pixel gains or loses
    vec3 dL{0};      ///< change of radiance on a real surface seen directly (signed)
    float alpha = 0; ///< 1 if the sample sees a virtual object first
    float photon = 0; ///< luminance of the part of pixel_change the pass's photons estimated
};

/// Estimates per camera sample on virtual diffuse surfaces, the noisiest pixels: chosen so that
/// their shading costs about a quarter of the pass's photon tracing (a sample casts about as
/// many rays as a photon path), between 2 and 8. On the sun-shadow benchmark scene (256x144,
/// 100,000 photons) more samples lowered the error at equal time: relative RMSE over changed
/// pixels after 10 s 0.080 with 2, 0.073 with 4, 0.067 with 6, 0.063 with this rule.
int camera_diffuse_samples(int64_t photons_per_pass, size_t pixels_near_virtual);

/// The numbers of one direct-light estimate at a real point (DirectChange::estimate) and its
/// weight: 1, or 1/p for a pixel that Russian roulette kept with probability p.
struct DirectSamples {
    DirectChange::Samples u;
    double weight = 1;
    static DirectSamples from(Rng& rng) {
        DirectSamples d;
        d.u.sun = vec2(rng.uniform(), rng.uniform());
        d.u.sky = vec2(rng.uniform(), rng.uniform());
        d.u.cone = vec2(rng.uniform(), rng.uniform());
        d.u.pick = rng.uniform();
        return d;
    }
    static DirectSamples from(PixelSampler& s, double weight) {
        DirectSamples d;
        d.u.sun = s.next2d();
        d.u.sky = s.next2d();
        d.u.cone = s.next2d();
        d.u.pick = s.next1d();
        d.weight = weight;
        return d;
    }
};

/// What a camera sample on a real surface estimates this pass.
struct CameraWork {
    bool gather = true;          ///< the pass's photons can reach the pixel
    double direct_weight = 1;    ///< 0: no direct-light estimate this pass (roulette)
};

/// The camera pass: gathers one pass's photon maps (and the direct change) where camera rays
/// meet real surfaces, and shades the virtual ones (docs/method-notes.md, "Display").
/// With a DirectChange (the split estimator) the direct light the objects block at real
/// points is estimated by rays and the photons carry the rest; without one, photons carry all.
class CameraGather {
public:
    /// `camera_diffuse_samples`: estimates averaged per camera sample on a virtual diffuse
    /// surface (see camera_diffuse_samples()).
    CameraGather(const RenderScene& scene, const PassMaps& maps, int camera_diffuse_samples = 2,
                 const DirectChange* direct = nullptr, int max_depth = 8);

    /// One jittered sample at continuous pixel coordinates (px, py) of pixel (x, y). The first
    /// bounce's numbers come from `sampler` (the pixel's low-discrepancy stream for this pass),
    /// deeper ones from `rng`.
    SampleResult shade_camera(int x, int y, float px, float py, PixelSampler& sampler, Rng& rng,
                              const CameraWork& work = {}) const;

    /// dL at a real hit seen from direction `dir`: rho/pi (dE_direct + sum(phi) / (pi r^2)).
    /// `direct` null leaves the direct-light estimate out (or there is no DirectChange).
    /// `photon`, if given, gets the luminance of the photons' part.
    vec3 real_dL(const Hit& hit, const vec3& dir, Rng& rng, const DirectSamples* direct,
                    bool gather = true, float* photon = nullptr) const;
    /// The change of what a glossy real surface (a proxy with a Gloss layer) reflects towards
    /// -dir, 0 for a matte one: the virtual lights' highlights by next-event estimation, and
    /// along one direction from the lobe (`u`) an object's radiance less what it hides there,
    /// or the change of the real surface reflected (docs/real-gloss.md).
    /// `depth`: of the path that reaches the surface (0 from the camera); the object seen in
    /// the gloss is shaded one deeper.
    vec3 gloss_change(const Hit& hit, const vec3& dir, const vec2& u, Rng& rng, int depth = 0) const;
    /// The probe's sun that a glossy real surface reflected in the photo and an object now
    /// hides, by sampling the sun (MIS-weighted against the lobe): the sun is too small and
    /// bright to be left to the lobe's samples. To be subtracted.
    vec3 hidden_sun(const Hit& hit, const GlossLobe& lobe, Rng& rng) const;
    /// Radiance leaving a real point towards -dir in the augmented scene: the photo where the
    /// camera sees the point, rho E / pi elsewhere, plus dL, plus on a glossy surface the change
    /// of what its gloss reflects (the object above it, where it reflected the sky), up to
    /// kDiffuseGatherDepth deep.
    vec3 real_radiance(const Hit& hit, const vec3& dir, Rng& rng, int depth = 0) const;
    /// Radiance leaving a virtual diffuse point towards -dir, averaging `samples` estimates
    /// of the probe and bounce light (caustic photons are gathered once). With `sampler`, the
    /// estimates are samples index * samples + k of the pixel's stream.
    vec3 virtual_diffuse_radiance(const Hit& hit, const vec3& dir, Rng& rng, int depth, int samples,
                                  const PixelSampler* sampler = nullptr) const;
    /// Radiance arriving along a ray after a specular interaction or a gather bounce.
    /// `from_diffuse`: light from the probe through specular chains is in the caustic map.
    vec3 incoming(const Ray& ray, Rng& rng, int depth, bool from_diffuse, int splits) const;

    /// Radiance arriving along `ray` whose first hit is already known (`hit` may be empty), or
    /// the face of a virtual area light before it. `lights_sampled`: the ray leaves a point whose
    /// next-event estimation took the lights, so their faces add nothing.
    vec3 radiance_at(const Hit& hit, const Ray& ray, Rng& rng, int depth, bool from_diffuse, int splits,
                     bool lights_sampled = false) const;

    /// Radiance leaving a virtual principled point towards -dir: its emission (unless the
    /// lights were sampled where the path comes from, or it comes from a diffuse gather), the probe by
    /// next-event estimation (MIS against the BSDF; none from a diffuse gather, whose caustic
    /// map has it), and one BSDF-sampled continuation followed like a specular chain. With
    /// `sampler`, the first numbers come from the pixel's stream.
    vec3 principled_radiance(const Hit& hit, const vec3& dir, Rng& rng, int depth, bool from_diffuse, int splits,
                             PixelSampler* sampler = nullptr, bool lights_sampled = false) const;

private:
    vec3 specular_radiance(const Hit& hit, const vec3& dir, Rng& rng, int depth, bool from_diffuse,
                           int splits) const;

    const RenderScene& scene_;
    const PassMaps& maps_;
    const DirectChange* direct_;
    int camera_diffuse_samples_;
    double inv_area_;  // 1 / (pi r^2)
    int max_depth_;
};

}  // namespace dp
