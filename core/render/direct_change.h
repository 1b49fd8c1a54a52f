#pragma once
#include <vector>

#include "base/rng.h"
#include "probe/probe_bounds.h"
#include "assets/render_scene.h"

namespace dp {

/// The directions from a point towards one emission cluster's bounding sphere: a cone, or the
/// hemisphere above the point when it lies inside the sphere.
struct ClusterCone {
    vec3 axis{0};              ///< unit, towards the sphere's centre
    double solid_angle = 0;    ///< of the cone (2 pi for a point inside the sphere)
    double one_minus_cos = 0;  ///< 1 - cos(half angle), kept apart for tiny cones
    float half_angle = 0;
    bool inside = false;
};

/// The change of *direct* light at a real surface point that the virtual objects make by
/// standing in its way (docs/method-notes.md, "The split"):
///   dE(x) = - integral of L_old(x, w) [a virtual object is first along w] cos(theta) dw,
/// where L_old is the light that arrived before: the probe where no real surface lies along w,
/// the photographed radiance of the real surface behind the object where one does. Estimated by
/// next-event estimation: a sample of the probe's sun, one of its sky (ProbeLights) and one of
/// the cones towards the clusters, combined by the power heuristic. Only directions inside a
/// cone can be blocked, so samples outside cost no ray. Light blocked by glass is left to the
/// photons, which carry the light it lets through as well.
class DirectChange {
public:
    /// `real_radiance_max`: a high radiance of the real surfaces seen in the photo, the bound's
    /// stand-in for what a real surface behind an object sends (0: the photo's 99th percentile).
    explicit DirectChange(const RenderScene& scene, float real_radiance_max = 0);

    /// The numbers of one estimate: the sun, sky and cone directions and the cone's cluster.
    struct Samples {
        vec2 sun{0}, sky{0}, cone{0};
        float pick = 0;
    };
    /// One estimate of dE (RGB irradiance, signed) at real hit `hit` whose lit side faces `n`.
    /// `real_only`: only the light of real surfaces behind the objects (the all-photon
    /// estimator's photons carry the probe's).
    dvec3 estimate(const Hit& hit, const vec3& n, const Samples& u, Rng& rng, bool real_only = false) const;

    /// Bound of |luminance(dE)| at a point with unit normal n: each cluster's solid angle above
    /// the horizon times the brightest light (probe in the cone, or a photographed real surface)
    /// that could come from it. Zero where no cluster rises above the horizon.
    double bound(const vec3& p, const vec3& n) const;

    /// The cones of all clusters seen from p (empty slots for clusters below the horizon).
    void cones(const vec3& p, const vec3& n, std::vector<ClusterCone>& out) const;

private:
    /// Cone-sampling pdf of direction w given the cones (mixture over clusters by solid angle).
    double cone_pdf(const std::vector<ClusterCone>& cones, const vec3& w, const vec3& n) const;
    /// The integrand without the cosine: L_old where a virtual object is first along w, else 0.
    vec3 blocked_radiance(const Hit& hit, const vec3& n, const vec3& w, Rng& rng, bool real_only) const;
    /// One light sample's weighted contribution -L cos / p, MIS-weighted against the cones.
    dvec3 light_sample(const Hit& hit, const vec3& n, const std::vector<ClusterCone>& cones,
                       const ProbeSample& s, Rng& rng, bool real_only) const;

    const RenderScene& scene_;
    ProbeMaxGrid probe_max_;
    float real_radiance_max_ = 0;  ///< a high photographed luminance of real surfaces
};

}  // namespace dp
