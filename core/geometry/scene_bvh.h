#pragma once
#include <cmath>
#include <vector>

#include "base/math.h"
#include "geometry/mesh.h"

// Embree's handles, declared so that users of this header need not see Embree.
struct RTCDeviceTy;
struct RTCSceneTy;

namespace dp {

/// A shape placed in the world for ray queries: an exact sphere, or a world-space triangle
/// mesh that the caller keeps alive.
struct PlacedShape {
    bool sphere = false;
    vec3 center{0};
    float radius = 0;
    const TriangleMesh* mesh = nullptr;  ///< world space; used unless `sphere`
    bool present = true;                 ///< false: keeps its index but is never hit (hidden)
    bool needs_uv = false;               ///< sphere: compute texture coordinates at hits
};

/// Where a ray meets a shape. `ng` is the unit geometric normal as stored (not flipped), `ns`
/// the shading normal turned to the side of `ng`; `index` is the shape's position in its list.
struct ShapeHit {
    float t = 0;
    vec3 p{0}, ng{0}, ns{0};
    vec2 uv{0};
    vec2 bary{0};   ///< barycentric coordinates of the hit in triangle `prim` (of vertices 1 and 2)
    int index = -1;
    int prim = -1;  ///< the triangle hit, in the shape's mesh; -1 for an exact sphere
    bool is_virtual = false;
    explicit operator bool() const { return index >= 0; }
};

/// Real and virtual geometry in two Embree BVHs, and a top-level scene instancing both for
/// queries against everything in one traversal. A BVH knows no light, no material and no
/// photograph: it answers where rays go, with offsets for new rays that scale with the scene.
class SceneBVH {
public:
    SceneBVH(const std::vector<PlacedShape>& real, const std::vector<PlacedShape>& virtual_shapes);
    ~SceneBVH();
    SceneBVH(const SceneBVH&) = delete;
    SceneBVH& operator=(const SceneBVH&) = delete;

    ShapeHit intersect_real(const Ray& ray, float tmax = INFINITY) const;
    ShapeHit intersect_virtual(const Ray& ray, float tmax = INFINITY) const;
    /// Nearest of both.
    ShapeHit intersect(const Ray& ray, float tmax = INFINITY) const;
    bool occluded_real(const Ray& ray, float tmax = INFINITY) const;
    bool occluded(const Ray& ray, float tmax = INFINITY) const;

    /// Bounds of the real shapes; false when there are none.
    bool real_bounds(vec3& lo, vec3& hi) const;

    /// The characteristic length (metres) that ray offsets scale with, and the offset itself.
    void set_scale(float scale);
    float scale() const { return scale_; }
    float epsilon() const { return epsilon_; }
    /// Origin for a new ray leaving point `p` (geometric normal `ng`) towards `dir`, offset
    /// off the surface: scale-relative, plus a float-precision term for points far from the
    /// origin, so that millimetre and kilometre scenes behave alike.
    vec3 offset_origin(const vec3& p, const vec3& ng, const vec3& dir) const;
    /// Moves a camera ray's origin a scene-scaled epsilon in front of the eye (a near clip).
    Ray near_clipped(Ray ray) const;

private:
    struct Layer {
        RTCSceneTy* scene = nullptr;
        std::vector<PlacedShape> shapes;
    };
    void build(Layer& layer, bool high_quality);
    ShapeHit intersect_in(RTCSceneTy* scene, const Layer* layer, const Ray& ray, float tmax) const;
    bool occluded_in(RTCSceneTy* scene, const Ray& ray, float tmax) const;

    RTCDeviceTy* device_ = nullptr;
    Layer real_, virtual_;
    RTCSceneTy* all_ = nullptr;
    float scale_ = 1, epsilon_ = 1e-5f;
};

}  // namespace dp
