#pragma once
// The gloss layer of a real surface (Gloss in scene/project.h): a GGX reflection with Schlick's
// Fresnel over the diffuse albedo. The photograph already shows what the surface reflected;
// the renderers add the change of that reflection (docs/real-gloss.md).
#include "assets/microfacet.h"
#include "assets/render_scene.h"

namespace dp {

/// The gloss lobe at a real hit seen along `dir` (the ray travelling towards the surface).
class GlossLobe {
public:
    GlossLobe(const Hit& hit, const vec3& dir);
    /// The surface has a gloss layer, seen from its front.
    bool valid() const { return valid_; }
    /// BSDF times the cosine towards unit world direction `wi` (0 below the surface).
    float eval_cos(const vec3& wi) const;
    /// A direction by the visible normals: `weight` is eval_cos / pdf. False when it falls
    /// below the surface.
    bool sample(const vec2& u, vec3& wi, float& weight) const;
    /// The density with which sample() draws unit world direction `wi`.
    float pdf(const vec3& wi) const;
    /// The half-angle about the mirror direction holding all but about 1% of the lobe's
    /// reflected light (the half vectors within tan = 10 alpha).
    float cone_half_angle() const;
    /// The mirror direction of the view about the normal.
    vec3 mirror() const { return frame_.to_world(vec3(-wo_.x, -wo_.y, wo_.z)); }

private:
    Frame frame_;
    Ggx ggx_;
    float f0_ = 0;
    vec3 wo_{0};
    vec3 ng_{0};
    bool valid_ = false;
};

/// A glossy real surface whole: its albedo's Lambert lobe plus its gloss lobe, sampled from
/// the mixture of the two (half and half), for the paths that bounce off it (the reference
/// path tracer's, photons).
class GlossySurface {
public:
    GlossySurface(const Hit& hit, const vec3& dir);
    /// BSDF times the cosine towards unit world direction `w` (0 below the surface).
    vec3 eval_cos(const vec3& w) const;
    /// The mixture's density of `w`.
    float pdf(const vec3& w) const;
    /// A direction from the mixture: `pick` chooses the lobe, `u` the direction in it. False
    /// when it falls below the surface.
    bool sample(float pick, const vec2& u, vec3& w) const;
    /// The hit with its normals turned to the side the path arrives on.
    const Hit& facing() const { return facing_; }

private:
    GlossLobe lobe_;
    vec3 rho_{0};
    Hit facing_;
};

/// Whether a gloss lobe at `p` can reflect anything of the sphere (c, R): the sphere meets the
/// cone of `lobe.cone_half_angle()` about its mirror direction.
bool gloss_may_reflect(const GlossLobe& lobe, const vec3& p, const vec3& c, float R);

}  // namespace dp
