#include "geometry/scene_bvh.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dp {

namespace {

constexpr unsigned kRealInstance = 0, kVirtualInstance = 1;

RTCRayHit make_rayhit(const Ray& ray, float tnear, float tmax) {
    RTCRayHit rh;
    rh.ray.org_x = ray.org.x;
    rh.ray.org_y = ray.org.y;
    rh.ray.org_z = ray.org.z;
    rh.ray.dir_x = ray.dir.x;
    rh.ray.dir_y = ray.dir.y;
    rh.ray.dir_z = ray.dir.z;
    rh.ray.tnear = tnear;
    rh.ray.tfar = tmax;
    rh.ray.time = 0;
    rh.ray.mask = 0xFFFFFFFF;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

vec2 sphere_uv(const vec3& n) {
    float u = 0.5f + std::atan2(n.x, -n.z) / (2 * kPi);
    float v = std::acos(std::clamp(n.y, -1.0f, 1.0f)) / kPi;
    return vec2(u, v);
}

/// The hit's normals and texture coordinates from the shape it found.
ShapeHit finish_hit(const RTCRayHit& rh, const std::vector<PlacedShape>& shapes, bool is_virtual, const Ray& ray) {
    ShapeHit hit;
    const PlacedShape& s = shapes[rh.hit.geomID];
    hit.index = int(rh.hit.geomID);
    hit.is_virtual = is_virtual;
    hit.t = rh.ray.tfar;
    hit.p = ray.org + hit.t * ray.dir;
    if (s.sphere) {
        vec3 n = glm::normalize(hit.p - s.center);
        // Re-project onto the sphere: removes the error of org + t*dir at large t.
        hit.p = s.center + n * s.radius;
        hit.ng = hit.ns = n;
        if (s.needs_uv) hit.uv = sphere_uv(n);  // trigonometry only where a texture needs it
        return hit;
    }
    hit.ng = glm::normalize(vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    const TriangleMesh& m = *s.mesh;
    const glm::uvec3& tri = m.triangles[rh.hit.primID];
    hit.prim = int(rh.hit.primID);
    float u = rh.hit.u, v = rh.hit.v, w = 1 - u - v;
    hit.bary = vec2(u, v);
    hit.ns = hit.ng;
    if (!m.normals.empty()) {
        vec3 n = w * m.normals[tri.x] + u * m.normals[tri.y] + v * m.normals[tri.z];
        float len = glm::length(n);
        if (len > 0 && std::isfinite(len)) {
            n /= len;
            hit.ns = glm::dot(n, hit.ng) < 0 ? -n : n;
        }
    }
    if (!m.uvs.empty()) hit.uv = w * m.uvs[tri.x] + u * m.uvs[tri.y] + v * m.uvs[tri.z];
    return hit;
}

}  // namespace

SceneBVH::SceneBVH(const std::vector<PlacedShape>& real, const std::vector<PlacedShape>& virtual_shapes) {
    device_ = rtcNewDevice("");
    if (!device_) throw std::runtime_error("Embree: cannot create device");
    virtual_.shapes = virtual_shapes;
    real_.shapes = real;
    build(virtual_, true);
    build(real_, false);
    all_ = rtcNewScene(device_);
    const glm::mat4 identity(1.0f);
    for (const Layer* layer : {&real_, &virtual_}) {
        RTCGeometry inst = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(inst, layer->scene);
        rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &identity[0][0]);
        rtcCommitGeometry(inst);
        rtcAttachGeometryByID(all_, inst, layer == &virtual_ ? kVirtualInstance : kRealInstance);
        rtcReleaseGeometry(inst);
    }
    rtcCommitScene(all_);
}

SceneBVH::~SceneBVH() {
    if (all_) rtcReleaseScene(all_);
    if (real_.scene) rtcReleaseScene(real_.scene);
    if (virtual_.scene) rtcReleaseScene(virtual_.scene);
    if (device_) rtcReleaseDevice(device_);
}

void SceneBVH::build(Layer& layer, bool high_quality) {
    layer.scene = rtcNewScene(device_);
    if (high_quality) rtcSetSceneBuildQuality(layer.scene, RTC_BUILD_QUALITY_HIGH);
    // Every shape keeps its slot (geomID == index); hidden and empty ones get no triangles.
    for (const PlacedShape& s : layer.shapes) {
        const bool empty = !s.present || (!s.sphere && (!s.mesh || s.mesh->triangles.empty()));
        RTCGeometry geom;
        if (empty) {
            geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(vec3), 0);
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, sizeof(glm::uvec3), 0);
        } else if (s.sphere) {
            geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
            auto* v = static_cast<float*>(
                rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
            v[0] = s.center.x;
            v[1] = s.center.y;
            v[2] = s.center.z;
            v[3] = s.radius;
        } else {
            geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, s.mesh->positions.data(), 0,
                                       sizeof(vec3), s.mesh->positions.size());
            rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, s.mesh->triangles.data(), 0,
                                       sizeof(glm::uvec3), s.mesh->triangles.size());
        }
        rtcCommitGeometry(geom);
        rtcAttachGeometry(layer.scene, geom);
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(layer.scene);
}

ShapeHit SceneBVH::intersect_in(RTCSceneTy* scene, const Layer* layer, const Ray& ray, float tmax) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh = make_rayhit(ray, 0.0f, tmax);
    rtcIntersect1(scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return ShapeHit{};
    if (!layer) layer = rh.hit.instID[0] == kVirtualInstance ? &virtual_ : &real_;
    return finish_hit(rh, layer->shapes, layer == &virtual_, ray);
}

bool SceneBVH::occluded_in(RTCSceneTy* scene, const Ray& ray, float tmax) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r = make_rayhit(ray, 0.0f, tmax).ray;
    rtcOccluded1(scene, &ctx, &r);
    return r.tfar < 0;  // Embree sets tfar = -inf on a hit
}

ShapeHit SceneBVH::intersect_real(const Ray& ray, float tmax) const { return intersect_in(real_.scene, &real_, ray, tmax); }
ShapeHit SceneBVH::intersect_virtual(const Ray& ray, float tmax) const {
    return intersect_in(virtual_.scene, &virtual_, ray, tmax);
}
ShapeHit SceneBVH::intersect(const Ray& ray, float tmax) const { return intersect_in(all_, nullptr, ray, tmax); }
bool SceneBVH::occluded_real(const Ray& ray, float tmax) const { return occluded_in(real_.scene, ray, tmax); }
bool SceneBVH::occluded(const Ray& ray, float tmax) const { return occluded_in(all_, ray, tmax); }

bool SceneBVH::real_bounds(vec3& lo, vec3& hi) const {
    RTCBounds b;
    rtcGetSceneBounds(real_.scene, &b);
    if (!(b.lower_x <= b.upper_x)) return false;
    lo = vec3(b.lower_x, b.lower_y, b.lower_z);
    hi = vec3(b.upper_x, b.upper_y, b.upper_z);
    return true;
}

void SceneBVH::set_scale(float scale) {
    scale_ = std::max(scale, 1e-12f);
    epsilon_ = 1e-5f * scale_;
}

vec3 SceneBVH::offset_origin(const vec3& p, const vec3& ng, const vec3& dir) const {
    const float mag = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    const float eps = epsilon_ + mag * 4e-7f;
    return p + (glm::dot(dir, ng) >= 0 ? eps : -eps) * ng;
}

Ray SceneBVH::near_clipped(Ray r) const {
    const float mag = std::max({std::abs(r.org.x), std::abs(r.org.y), std::abs(r.org.z)});
    r.org += (epsilon_ + mag * 4e-7f) * r.dir;
    return r;
}

}  // namespace dp
