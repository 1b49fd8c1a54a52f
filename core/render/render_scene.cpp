#include "render/render_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace dp {

namespace {

bool is_uniform(const vec3& s) {
    return std::abs(s.x - s.y) <= 1e-6f * std::abs(s.x) && std::abs(s.x - s.z) <= 1e-6f * std::abs(s.x);
}

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

/// Places a proxy's or object's shape in the world: an exact Embree sphere when the scale is
/// uniform, otherwise a triangle mesh stored in `mesh_slot`.
void place_shape(const Shape& shape, const Transform& transform, const TriangleMesh* loaded, Surface& s,
                 TriangleMesh& mesh_slot) {
    glm::mat4 m = transform.matrix();
    if (shape.kind == Shape::Kind::Sphere && is_uniform(transform.scale)) {
        s.analytic_sphere = true;
        s.sphere_center = vec3(m * glm::vec4(0, 0, 0, 1));
        s.sphere_radius = shape.radius * std::abs(transform.scale.x);
        return;
    }
    TriangleMesh mesh;
    switch (shape.kind) {
        case Shape::Kind::Plane: mesh = make_plane(shape.size.x, shape.size.z); break;
        case Shape::Kind::Box: mesh = make_box(shape.size); break;
        case Shape::Kind::Sphere: mesh = make_uv_sphere(shape.radius); break;
        case Shape::Kind::Mesh:
            if (loaded) mesh = *loaded;
            break;
    }
    mesh.transform(m);
    mesh_slot = std::move(mesh);
    s.mesh = &mesh_slot;
}

}  // namespace

vec3 Surface::reflectance_at(const vec2& uv) const {
    vec3 rho = albedo;
    if (texture && !texture->empty()) {
        float u = uv.x - std::floor(uv.x), v = uv.y - std::floor(uv.y);
        rho = texture->bilinear(u * texture->width() - 0.5f, v * texture->height() - 0.5f);
    }
    return glm::clamp(rho, vec3(0.0f), vec3(0.98f));
}

RenderScene::RenderScene(const Project& project, SceneAssets assets)
    : project_(project), assets_(std::move(assets)) {
    if (assets_.photo.empty()) throw std::invalid_argument("RenderScene: empty photograph");
    sanitize_images();
    camera_ = project_.camera.build(assets_.photo.width(), assets_.photo.height());
    probe_ = Probe(assets_.probe_latlong, euler_xyz_deg(project_.probe.rotation_deg), project_.probe.intensity);
    lights_ = ProbeLights(probe_);
    device_ = rtcNewDevice("");
    if (!device_) throw std::runtime_error("Embree: cannot create device");
    build_virtual();
    build_real();
    compute_scale();  // epsilons for everything after
    build_top_level();
    compute_clusters();
    estimate_albedos();
}

RenderScene::~RenderScene() {
    if (all_) rtcReleaseScene(all_);
    if (real_) rtcReleaseScene(real_);
    if (virtual_) rtcReleaseScene(virtual_);
    if (device_) rtcReleaseDevice(device_);
}

unsigned RenderScene::attach(RTCScene scene, const Surface& s, const TriangleMesh* mesh) {
    RTCGeometry geom;
    if (s.analytic_sphere) {
        geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                              RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
        v[0] = s.sphere_center.x;
        v[1] = s.sphere_center.y;
        v[2] = s.sphere_center.z;
        v[3] = s.sphere_radius;
    } else {
        geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, mesh->positions.data(), 0,
                                   sizeof(vec3), mesh->positions.size());
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh->triangles.data(), 0,
                                   sizeof(glm::uvec3), mesh->triangles.size());
    }
    rtcCommitGeometry(geom);
    unsigned id = rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    return id;
}

void RenderScene::build_virtual() {
    virtual_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(virtual_, RTC_BUILD_QUALITY_HIGH);
    const auto& objs = project_.objects;
    virtual_world_meshes_.resize(objs.size());
    virtual_surfaces_.clear();
    for (size_t i = 0; i < objs.size(); ++i) {
        const VirtualObject& o = objs[i];
        Surface s;
        s.is_virtual = true;
        s.index = int(i);
        s.material = o.material;
        s.albedo = o.material.albedo.rgb;
        if (i < assets_.object_textures.size() && !assets_.object_textures[i].empty())
            s.texture = &assets_.object_textures[i];
        const TriangleMesh* loaded = i < assets_.object_meshes.size() ? &assets_.object_meshes[i] : nullptr;
        place_shape(o.shape, o.transform, loaded, s, virtual_world_meshes_[i]);
        virtual_surfaces_.push_back(s);
    }
    for (const Surface& s : virtual_surfaces_) {
        if (s.material.kind != Material::Kind::Diffuse) has_specular_ = true;
        if (s.transmits()) has_transmissive_ = true;
    }
    // Hidden objects keep their slot (geomID == index) but get no geometry.
    for (size_t i = 0; i < objs.size(); ++i) {
        const Surface& s = virtual_surfaces_[i];
        bool empty_mesh = !s.analytic_sphere && (!s.mesh || s.mesh->triangles.empty());
        if (!objs[i].visible || empty_mesh) {
            RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(vec3), 0);
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, sizeof(glm::uvec3), 0);
            rtcCommitGeometry(g);
            rtcAttachGeometry(virtual_, g);
            rtcReleaseGeometry(g);
        } else {
            attach(virtual_, s, s.mesh);
        }
    }
    rtcCommitScene(virtual_);
}

void RenderScene::compute_scale() {
    // The virtual objects' extent and their distance to the camera. Without a virtual object
    // (a synthetic photograph) the real proxies' extent stands in: offsets must never fall to
    // the float rounding of the points alone.
    vec3 lo = camera_.position(), hi = lo;
    auto grow = [&](vec3 a, vec3 b) {
        lo = glm::min(lo, a);
        hi = glm::max(hi, b);
    };
    bool any = false;
    for (const Surface& s : virtual_surfaces_) {
        vec3 a, b;
        if (s.analytic_sphere) {
            grow(s.sphere_center - s.sphere_radius, s.sphere_center + s.sphere_radius);
            any = true;
        } else if (s.mesh && s.mesh->bounds(a, b)) {
            grow(a, b);
            any = true;
        }
    }
    if (!any) {
        RTCBounds b;
        rtcGetSceneBounds(real_, &b);
        if (b.lower_x <= b.upper_x) grow(vec3(b.lower_x, b.lower_y, b.lower_z), vec3(b.upper_x, b.upper_y, b.upper_z));
    }
    scale_ = std::max(glm::length(hi - lo), 1e-12f);
    epsilon_ = 1e-5f * scale_;
}

void RenderScene::build_real() {
    real_ = rtcNewScene(device_);
    const auto& real = project_.real;
    real_world_meshes_.resize(real.size());
    real_surfaces_.clear();
    for (size_t i = 0; i < real.size(); ++i) {
        const RealProxy& r = real[i];
        Surface s;
        s.index = int(i);
        s.albedo = r.albedo.rgb;
        if (i < assets_.real_textures.size() && !assets_.real_textures[i].empty())
            s.texture = &assets_.real_textures[i];
        const TriangleMesh* loaded = i < assets_.real_meshes.size() ? &assets_.real_meshes[i] : nullptr;
        place_shape(r.shape, r.transform, loaded, s, real_world_meshes_[i]);
        real_surfaces_.push_back(s);
    }
    for (const Surface& s : real_surfaces_) attach(real_, s, s.mesh);
    rtcCommitScene(real_);
}

void RenderScene::update_materials(const Project& project) {
    if (project.objects.size() != project_.objects.size())
        throw std::invalid_argument("update_materials: object count changed");
    for (size_t i = 0; i < project.objects.size(); ++i) {
        project_.objects[i].material = project.objects[i].material;
        virtual_surfaces_[i].material = project.objects[i].material;
        virtual_surfaces_[i].albedo = project.objects[i].material.albedo.rgb;
    }
    has_specular_ = std::any_of(virtual_surfaces_.begin(), virtual_surfaces_.end(),
                                [](const Surface& s) { return s.material.kind != Material::Kind::Diffuse; });
    has_transmissive_ = std::any_of(virtual_surfaces_.begin(), virtual_surfaces_.end(),
                                    [](const Surface& s) { return s.transmits(); });
}

Hit RenderScene::finish_hit(const RTCRayHit& rh, const std::vector<Surface>& surfaces, const Ray& ray) const {
    Hit hit;
    const Surface& s = surfaces[rh.hit.geomID];
    hit.surface = &s;
    hit.t = rh.ray.tfar;
    hit.p = ray.org + hit.t * ray.dir;
    if (s.analytic_sphere) {
        vec3 n = glm::normalize(hit.p - s.sphere_center);
        // Re-project onto the sphere: removes the error of org + t*dir at large t.
        hit.p = s.sphere_center + n * s.sphere_radius;
        hit.ng = hit.ns = n;
        if (s.texture) hit.uv = sphere_uv(n);  // trigonometry only where a texture needs it
        return hit;
    }
    hit.ng = glm::normalize(vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    const TriangleMesh& m = *s.mesh;
    const glm::uvec3& tri = m.triangles[rh.hit.primID];
    float u = rh.hit.u, v = rh.hit.v, w = 1 - u - v;
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

Hit RenderScene::intersect_in(RTCScene scene, const std::vector<Surface>& surfaces, const Ray& ray,
                              float tmax) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh = make_rayhit(ray, 0.0f, tmax);
    rtcIntersect1(scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return Hit{};
    return finish_hit(rh, surfaces, ray);
}

bool RenderScene::occluded_in(RTCScene scene, const Ray& ray, float tmax) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r = make_rayhit(ray, 0.0f, tmax).ray;
    rtcOccluded1(scene, &ctx, &r);
    return r.tfar < 0;  // Embree sets tfar = -inf on a hit
}

Hit RenderScene::intersect_real(const Ray& ray, float tmax) const {
    return intersect_in(real_, real_surfaces_, ray, tmax);
}
Hit RenderScene::intersect_virtual(const Ray& ray, float tmax) const {
    return intersect_in(virtual_, virtual_surfaces_, ray, tmax);
}
Hit RenderScene::intersect(const Ray& ray, float tmax) const {
    // One traversal of the top-level scene that instances both BVHs.
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh = make_rayhit(ray, 0.0f, tmax);
    rtcIntersect1(all_, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return Hit{};
    return finish_hit(rh, rh.hit.instID[0] == kVirtualInstance ? virtual_surfaces_ : real_surfaces_, ray);
}
bool RenderScene::occluded_real(const Ray& ray, float tmax) const { return occluded_in(real_, ray, tmax); }
bool RenderScene::occluded(const Ray& ray, float tmax) const { return occluded_in(all_, ray, tmax); }

void RenderScene::build_top_level() {
    if (!all_) all_ = rtcNewScene(device_);
    const glm::mat4 identity(1.0f);
    for (RTCScene scene : {real_, virtual_}) {
        RTCGeometry inst = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(inst, scene);
        rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &identity[0][0]);
        rtcCommitGeometry(inst);
        rtcAttachGeometryByID(all_, inst, scene == virtual_ ? kVirtualInstance : kRealInstance);
        rtcReleaseGeometry(inst);
    }
    rtcCommitScene(all_);
}

Ray RenderScene::camera_ray(float px, float py) const {
    Ray r = camera_.generate_ray(px, py);
    float mag = std::max({std::abs(r.org.x), std::abs(r.org.y), std::abs(r.org.z)});
    r.org += (epsilon_ + mag * 4e-7f) * r.dir;
    return r;
}

vec3 RenderScene::offset_origin(const Hit& hit, const vec3& dir) const {
    // Scale-relative offset, plus a float-precision term for points far from the origin.
    float mag = std::max({std::abs(hit.p.x), std::abs(hit.p.y), std::abs(hit.p.z)});
    float eps = epsilon_ + mag * 4e-7f;
    return hit.p + (glm::dot(dir, hit.ng) >= 0 ? eps : -eps) * hit.ng;
}

}  // namespace dp
