#pragma once
#include <vector>

#include "base/math.h"
#include "base/rng.h"
#include "geometry/mesh.h"
#include "probe/probe.h"
#include "scene/project.h"

namespace dp {

/// A virtual light placed in world space, in the radiometric terms the renderers use.
struct PlacedLight {
    VirtualLight::Kind kind = VirtualLight::Kind::Point;
    int index = 0;        ///< in project.lights
    vec3 position{0};     ///< a point or spot's position, an area light's centre
    vec3 axis{0, -1, 0};  ///< unit: where it shines
    vec3 u{0}, v{0};      ///< area kinds: half extents along the local x and z (a disk's radii)
    float area = 0;       ///< area kinds: of the emitting face (one side)
    vec3 intensity{0};    ///< point, spot: radiant intensity (W/sr) on the axis
    vec3 radiance{0};     ///< area kinds: radiance of the emitting face (W/(m^2 sr))
    float cos_half = -1;  ///< spot: cosine of half the cone's angle
    float smooth = 0;     ///< spot: 1 / width of the soft edge in cosine (0: a hard edge)
    bool visible = true;  ///< area kinds: the face is seen by camera rays and specular chains
    double power = 0;     ///< luminance of the flux it sends (W), what photons are shared by

    bool is_area() const { return kind == VirtualLight::Kind::Rect || kind == VirtualLight::Kind::Disk; }
    /// Spot: the share of the axis intensity sent along unit `w` (Blender's smoothstep edge); 1
    /// for a point.
    float spot_falloff(const vec3& w) const;
};

/// A virtual object whose principled material emits: a light of its own shape. Both sides of its
/// faces emit, as the camera sees them.
struct EmissiveShape {
    int object = 0;                       ///< in project.objects
    vec3 radiance{0};                     ///< its emission
    const TriangleMesh* mesh = nullptr;   ///< world space; null for an analytic sphere
    std::vector<uint32_t> triangles;      ///< the emitting triangles of `mesh`
    AliasTable by_area;                   ///< over `triangles`
    vec3 center{0};                       ///< an analytic sphere's, or the bounding sphere's
    float radius = 0;
    double area = 0;
    double power = 0;                     ///< luminance of its flux, 2 pi A L (W)
};

/// One direction towards a light, drawn from a shaded point.
struct LightSample {
    vec3 dir{0};     ///< unit, from the shaded point towards the light
    float dist = 0;  ///< to the sampled point of the light
    /// Incident radiance over the direction's density (for a point or spot, I / d^2): times the
    /// BSDF and the cosine at the shaded point, one estimate of the light it reflects.
    vec3 weight{0};
    /// Solid-angle density of `dir` (0 for a point or spot, which nothing else can sample):
    /// for weighting against BSDF sampling.
    float pdf = 0;
};

/// A light photon's start.
struct LightPhoton {
    Ray ray;
    vec3 flux{0};
    bool valid = false;
};

/// The project's virtual lights (VirtualLight), placed, and its emissive objects, with their
/// sampling: next-event estimation from a shaded point, photon emission by power, and the area
/// lights' faces for rays that see them. Lamps are not in the BVH: they cast no shadow and a ray
/// passes through them. Lights 0 .. lights().size() - 1 are the lamps, the rest the emitters.
class LightSet {
public:
    LightSet() = default;
    explicit LightSet(const std::vector<VirtualLight>& lights, std::vector<EmissiveShape> emitters = {});

    bool empty() const { return lights_.empty() && emitters_.empty(); }
    size_t size() const { return lights_.size() + emitters_.size(); }
    const std::vector<PlacedLight>& lights() const { return lights_; }
    const std::vector<EmissiveShape>& emitters() const { return emitters_; }
    /// Some virtual object emits: its emission, seen along a path, is this set's light.
    bool has_emitters() const { return !emitters_.empty(); }

    /// A direction from `x` towards light `i` (an area light's face sampled by area), with its
    /// weight; weight 0 where `x` gets nothing from it (behind an area light, outside a spot's
    /// cone, a light of no power).
    LightSample sample(size_t i, const vec3& x, const vec2& u) const;

    /// The radiance of the nearest visible area light face that `ray` meets from its emitting
    /// side before `tmax` (0 where none does); `t`, if given, gets its distance, `pdf` the
    /// density with which sample() of that light draws the ray's direction from its origin.
    vec3 emitted(const Ray& ray, float tmax, float* t = nullptr, float* pdf = nullptr) const;

    /// The emitter of virtual object `object` (index into emitters()), or -1.
    int emitter_of(int object) const {
        return object >= 0 && size_t(object) < emitter_of_.size() ? emitter_of_[size_t(object)] : -1;
    }
    /// The density with which sample() of emitter `e` draws the direction of a ray from
    /// `origin` that meets it at distance `t`, where the geometric normal is `ng`.
    float emitter_pdf(int e, const vec3& origin, const vec3& dir, float t, const vec3& ng) const;

    /// A photon from a light picked by power: its flux is the light's flux over `count` photons
    /// and the pick's probability. `offset`: how far off an area light's face the ray starts.
    LightPhoton emit(Rng& rng, double inv_count, float offset) const;
    /// Luminance of all lights' flux (W).
    double total_power() const { return table_.total(); }

    /// Bound of the luminance of the irradiance the lights send to p (unit normal n), with no
    /// occluder: 0 where none can light it (behind them, outside a spot's cone).
    double irradiance_bound(const vec3& p, const vec3& n) const;

    /// A sphere around light i (a point or spot: radius 0), for what an edit of it can change.
    void bounds(size_t i, vec3& center, float& radius) const;

private:
    LightSample sample_emitter(const EmissiveShape& e, const vec3& x, const vec2& u) const;
    LightPhoton emit_emitter(const EmissiveShape& e, Rng& rng, double scale, float offset) const;

    std::vector<PlacedLight> lights_;
    std::vector<EmissiveShape> emitters_;
    std::vector<int> emitter_of_;  ///< per object index
    AliasTable table_;  ///< by power, lamps then emitters
};

}  // namespace dp
