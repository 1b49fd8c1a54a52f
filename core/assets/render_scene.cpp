#include "assets/render_scene.h"
#include "base/error.h"
#include "base/euler.h"
#include "assets/microfacet.h"
#include "assets/principled_scatter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace dp {

namespace {

bool is_uniform(const vec3& s) {
    return std::abs(s.x - s.y) <= 1e-6f * std::abs(s.x) && std::abs(s.x - s.z) <= 1e-6f * std::abs(s.x);
}

/// Places a proxy's or object's shape in the world: an exact sphere when the scale is
/// uniform, otherwise a triangle mesh stored in `mesh_slot`.
void place_shape(const Shape& shape, const Transform& transform, const TriangleMesh* loaded, UpAxis file_up,
                 Surface& s, TriangleMesh& mesh_slot) {
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
    mesh.transform(m * shape.file_frame(file_up));  // a mesh file's axes and unit first
    mesh_slot = std::move(mesh);
    s.mesh = &mesh_slot;
}

/// Some surface, or part of one, transmits light (glass).
bool any_transmits(const std::vector<Surface>& surfaces) {
    for (const Surface& s : surfaces) {
        if (s.transmits()) return true;
        for (const Surface& p : s.parts)
            if (p.transmits()) return true;
    }
    return false;
}

PlacedShape placed(const Surface& s, bool present) {
    PlacedShape p;
    p.sphere = s.analytic_sphere;
    p.center = s.sphere_center;
    p.radius = s.sphere_radius;
    p.mesh = s.mesh;
    p.present = present;
    p.needs_uv = s.texture != nullptr || s.metallic_roughness != nullptr || s.normal_map != nullptr;
    return p;
}

/// The visible virtual objects whose material emits, as lights of their shape (the triangles a
/// file material covers do not emit: a file's emission is not read).
std::vector<EmissiveShape> emissive_shapes(const Project& project, const std::vector<Surface>& surfaces) {
    std::vector<EmissiveShape> out;
    for (size_t i = 0; i < surfaces.size() && i < project.objects.size(); ++i) {
        const Surface& s = surfaces[i];
        const vec3 L = emitted_radiance(s);
        if (!project.objects[i].visible || L == vec3(0)) continue;
        EmissiveShape e;
        e.object = int(i);
        e.radiance = L;
        if (s.analytic_sphere) {
            e.center = s.sphere_center;
            e.radius = s.sphere_radius;
            e.area = 4.0 * kPi * double(e.radius) * e.radius;
        } else if (s.mesh) {
            e.mesh = s.mesh;
            std::vector<double> areas;
            vec3 lo(INFINITY), hi(-INFINITY);
            for (size_t t = 0; t < s.mesh->triangles.size(); ++t) {
                if (&s.part(int(t)) != &s) continue;
                const glm::uvec3 tri = s.mesh->triangles[t];
                const vec3 &a = s.mesh->positions[tri.x], &b = s.mesh->positions[tri.y], &c = s.mesh->positions[tri.z];
                const double area = 0.5 * double(glm::length(glm::cross(b - a, c - a)));
                if (!(area > 0) || !std::isfinite(area)) continue;
                e.triangles.push_back(uint32_t(t));
                areas.push_back(area);
                e.area += area;
                for (const vec3& v : {a, b, c}) lo = glm::min(lo, v), hi = glm::max(hi, v);
            }
            if (e.triangles.empty()) continue;
            e.by_area = AliasTable(areas);
            e.center = 0.5f * (lo + hi);
            e.radius = 0.5f * glm::length(hi - lo);
        } else {
            continue;
        }
        e.power = 2.0 * kPi * e.area * luminance(dvec3(L));
        if (std::isfinite(e.power) && e.power > 0) out.push_back(std::move(e));
    }
    return out;
}

/// RenderScene::check_extent's test of surfaces placed from `project`, and of `camera`'s position.
void check_extent_of(const Project& project, const std::vector<Surface>& real, const std::vector<Surface>& virt,
                     const Camera& camera) {
    // 1e9 m leaves ray arithmetic (squares of coordinates, t * dir) nine orders of magnitude
    // below float's overflow; no photographed scene comes near it.
    constexpr float kMaxCoordinate = 1e9f;
    auto ok = [&](vec3 v) { return is_finite(v) && glm::all(glm::lessThanEqual(glm::abs(v), vec3(kMaxCoordinate))); };
    auto check = [&](const Surface& s) {
        bool good = true;
        if (s.analytic_sphere) {
            good = ok(s.sphere_center) && std::isfinite(s.sphere_radius) && s.sphere_radius <= kMaxCoordinate &&
                   ok(s.sphere_center + vec3(s.sphere_radius)) && ok(s.sphere_center - vec3(s.sphere_radius));
        } else if (s.mesh) {
            for (const vec3& p : s.mesh->positions)
                if (!ok(p)) {
                    good = false;
                    break;
                }
        }
        if (good) return;
        const std::string list = s.is_virtual ? "objects" : "real";
        const std::string& name = s.is_virtual ? project.objects[size_t(s.index)].name : project.real[size_t(s.index)].name;
        const Shape& shape = s.is_virtual ? project.objects[size_t(s.index)].shape : project.real[size_t(s.index)].shape;
        // The mesh file is named too: its own coordinates may be what is out of reach.
        const std::string mesh =
            shape.kind == Shape::Kind::Mesh ? " (mesh '" + shorten_path(shape.mesh_path) + "')" : std::string();
        throw InputError("", list + "[" + std::to_string(s.index) + "]",
                         "'" + name + "' reaches beyond 1e9 m from the origin (or is not finite) once placed" + mesh +
                             ": check its size, scale and translation");
    };
    for (const Surface& s : real) check(s);
    for (const Surface& s : virt) check(s);
    for (size_t i = 0; i < project.lights.size(); ++i) {
        const VirtualLight& l = project.lights[i];
        const float reach = std::max(l.size.x, l.size.y) * std::max({l.transform.scale.x, l.transform.scale.z, 1.0f});
        if (!ok(l.transform.translation) || !std::isfinite(reach) || reach > kMaxCoordinate)
            throw InputError("", "lights[" + std::to_string(i) + "]",
                             "'" + l.name + "' lies beyond 1e9 m from the origin (or is not finite): check its translation and size");
    }
    if (!ok(camera.position()))
        throw InputError("", "camera", "the camera position is not finite or beyond 1e9 m from the origin");
}

/// RenderScene::check_camera's test of `camera`, built from `spec`.
void check_camera_of(const CameraSpec& spec, const Camera& camera) {
    const bool look_at = spec.model == CameraSpec::Model::LookAt;
    char buf[256];
    auto check_axis = [&](const char* focal_field, float f, const char* centre_field, float c, int size) {
        // A look-at camera's focal length and principal point follow from vfov_deg alone.
        const std::string field = look_at ? "camera.vfov_deg" : focal_field;
        if (!(std::isfinite(f) && f > 0)) {
            std::snprintf(buf, sizeof(buf), "gives a focal length of %g pixels: it must be finite and > 0", double(f));
            throw InputError("", field, buf);
        }
        const double fov = 2.0 * std::atan(double(size) / (2.0 * double(f))) * 180.0 / std::numbers::pi;
        if (!(fov >= kMinFovDeg && fov <= kMaxFovDeg)) {
            std::snprintf(buf, sizeof(buf),
                          "a focal length of %g pixels gives a field of view of %g degrees across the %d pixels "
                          "of the photo: it must be within %g to %g degrees",
                          double(f), fov, size, kMinFovDeg, kMaxFovDeg);
            throw InputError("", field, buf);
        }
        const double offset = std::abs(double(c) - 0.5 * double(size - 1));
        if (!(offset <= kMaxPrincipalOffset * size)) {
            std::snprintf(buf, sizeof(buf),
                          "the principal point %g lies %g pixels from the centre of the %d pixels of the photo: "
                          "at most %g image sizes (%g pixels) are accepted",
                          double(c), offset, size, kMaxPrincipalOffset, kMaxPrincipalOffset * size);
            throw InputError("", look_at ? "camera" : centre_field, buf);
        }
    };
    check_axis("camera.fx", camera.fx(), "camera.cx", camera.cx(), camera.width());
    check_axis("camera.fy", camera.fy(), "camera.cy", camera.cy(), camera.height());
    // The distortion polynomial can overflow where the intrinsics alone are fine.
    const int W = camera.width(), H = camera.height();
    for (int j = 0; j <= 4; ++j)
        for (int i = 0; i <= 4; ++i) {
            const float px = -0.5f + float(W) * float(i) / 4.0f, py = -0.5f + float(H) * float(j) / 4.0f;
            const Ray ray = camera.generate_ray(px, py);
            if (is_finite(ray.dir) && is_finite(ray.org)) continue;
            std::snprintf(buf, sizeof(buf), "the camera's ray through pixel (%g, %g) is not finite%s", double(px),
                          double(py), camera.distortion().is_zero() ? "" : ": check the distortion coefficients");
            throw InputError("", camera.distortion().is_zero() ? "camera" : "camera.distortion", buf);
        }
}

}  // namespace

vec3 texture_at(const Image& texture, const vec2& uv) {
    const float u = uv.x - std::floor(uv.x), v = uv.y - std::floor(uv.y);
    return texture.bilinear(u * texture.width() - 0.5f, v * texture.height() - 0.5f);
}

vec3 Surface::reflectance_at(const vec2& uv) const {
    const vec3 rho = texture && !texture->empty() ? texture_at(*texture, uv) : albedo;
    return glm::clamp(rho, vec3(0.0f), vec3(0.98f));
}

namespace {

/// The bent normal from a normal-map texel `c` (in [0, 1]^3) in the frame of normal `n` (the
/// map's +Z), the direction of growing u and that towards the image's top; `n` where they give
/// no frame.
vec3 bend(const vec3& n, const vec3& dpdu, const vec3& towards_top, const vec3& c, float scale) {
    const vec3 t = dpdu - n * glm::dot(n, dpdu);
    const float tl = glm::length(t);
    if (!(tl > 0) || !std::isfinite(tl)) return n;
    const vec3 tangent = t / tl;
    vec3 bitangent = glm::cross(n, tangent);
    if (glm::dot(bitangent, towards_top) < 0) bitangent = -bitangent;
    const vec3 m = c * 2.0f - 1.0f;
    const vec3 bent = tangent * (m.x * scale) + bitangent * (m.y * scale) + n * std::max(m.z, 0.0f);
    const float len = glm::length(bent);
    return len > 0 && std::isfinite(len) ? bent / len : n;
}

}  // namespace

vec3 normal_mapped(const Surface& s, const ShapeHit& hit) {
    if (!s.normal_map || s.normal_map->empty()) return hit.ns;
    const vec3 texel = texture_at(*s.normal_map, hit.uv);
    if (s.analytic_sphere) {
        // sphere_uv: u grows with atan2(n.x, -n.z), v with the polar angle from +y.
        const vec3 n = hit.ng;
        return bend(n, vec3(-n.z, 0.0f, n.x), vec3(0, 1, 0), texel, s.normal_scale);
    }
    if (!s.mesh || hit.prim < 0 || size_t(hit.prim) >= s.mesh->triangles.size() || s.mesh->uvs.empty())
        return hit.ns;
    const TriangleMesh& m = *s.mesh;
    const glm::uvec3& tri = m.triangles[size_t(hit.prim)];
    const vec3 e1 = m.positions[tri.y] - m.positions[tri.x], e2 = m.positions[tri.z] - m.positions[tri.x];
    const vec2 d1 = m.uvs[tri.y] - m.uvs[tri.x], d2 = m.uvs[tri.z] - m.uvs[tri.x];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(det) > 1e-20f)) return hit.ns;  // no UV area: no tangent frame
    const vec3 dpdu = (d2.y * e1 - d1.y * e2) / det, dpdv = (d1.x * e2 - d2.x * e1) / det;
    // The normal as the file orients it (hit.ns was turned to the side of ng): the map's +Z.
    vec3 n = hit.ns;
    bool turned = false;
    if (!m.normals.empty()) {
        const float b1 = hit.bary.x, b2 = hit.bary.y;
        const vec3 file_n = (1 - b1 - b2) * m.normals[tri.x] + b1 * m.normals[tri.y] + b2 * m.normals[tri.z];
        turned = glm::dot(file_n, hit.ns) < 0;
        if (turned) n = -n;
    }
    // +Y of the map points to the top of the image: our v grows downwards (mesh.h).
    const vec3 bent = bend(n, dpdu, -dpdv, texel, s.normal_scale);
    return turned ? -bent : bent;
}

RenderScene::RenderScene(const Project& project, SceneAssets assets)
    : RenderScene(project, std::move(assets), nullptr) {}

RenderScene::RenderScene(const Project& project, SceneAssets assets, std::shared_ptr<const LitProbe> probe)
    : project_(project), assets_(std::make_shared<SceneAssets>(std::move(assets))), lit_(std::move(probe)) {
    project_.render = RenderSettings{};
    if (assets_->photo.empty()) throw std::invalid_argument("RenderScene: empty photograph");
    sanitize_images();
    camera_ = project_.camera.build(assets_->photo.width(), assets_->photo.height());
    if (!lit_)
        lit_ = std::make_shared<const LitProbe>(assets_->probe_latlong, euler_xyz_deg(project_.probe.rotation_deg),
                                                project_.probe.gain());
    place_surfaces();
    has_transmissive_ = any_transmits(virtual_surfaces_);
    check_extent();
    check_camera();
    lights_ = LightSet(project_.lights, emissive_shapes(project_, virtual_surfaces_));
    std::vector<PlacedShape> real, virt;
    for (const Surface& s : real_surfaces_) real.push_back(placed(s, true));
    for (size_t i = 0; i < virtual_surfaces_.size(); ++i)
        virt.push_back(placed(virtual_surfaces_[i], project_.objects[i].visible));
    bvh_ = std::make_shared<SceneBVH>(real, virt);
    compute_scale();  // epsilons for everything after
    compute_clusters();
    estimate_albedos();
}

void RenderScene::place_surfaces() {
    const auto& objs = project_.objects;
    virtual_world_meshes_ = std::make_shared<std::vector<TriangleMesh>>(objs.size());
    for (size_t i = 0; i < objs.size(); ++i) {
        const VirtualObject& o = objs[i];
        Surface s;
        s.is_virtual = true;
        s.index = int(i);
        s.material = o.material;
        s.albedo = o.material.albedo.rgb;
        if (i < assets_->object_textures.size() && !assets_->object_textures[i].empty())
            s.texture = &assets_->object_textures[i];
        if (i < assets_->object_metallic_roughness.size() && !assets_->object_metallic_roughness[i].empty())
            s.metallic_roughness = &assets_->object_metallic_roughness[i];
        if (i < assets_->object_normal_maps.size() && !assets_->object_normal_maps[i].empty())
            s.normal_map = &assets_->object_normal_maps[i];
        s.normal_scale = o.material.principled.normal_scale;
        const TriangleMesh* loaded = i < assets_->object_meshes.size() ? &assets_->object_meshes[i] : nullptr;
        const UpAxis up = i < assets_->object_mesh_up.size() ? assets_->object_mesh_up[i] : UpAxis::Y;
        place_shape(o.shape, o.transform, loaded, up, s, (*virtual_world_meshes_)[i]);
        // A mesh drawn with its file's materials: a part per material, found per triangle.
        if (o.material_source == MaterialSource::File && s.mesh &&
            !s.mesh->triangle_materials.empty() && i < assets_->object_file_materials.size()) {
            const Surface base = s;
            for (const FileMaterialAsset& f : assets_->object_file_materials[i]) {
                Surface part = base;
                part.material = f.material;
                part.albedo = f.material.albedo.rgb;
                part.texture = f.texture.empty() ? nullptr : &f.texture;
                part.metallic_roughness = f.metallic_roughness.empty() ? nullptr : &f.metallic_roughness;
                part.normal_map = f.normal.empty() || !s.mesh || s.mesh->uvs.empty() ? nullptr : &f.normal;
                part.normal_scale = f.normal_scale;
                s.parts.push_back(std::move(part));
            }
        }
        virtual_surfaces_.push_back(std::move(s));
    }
    const auto& real = project_.real;
    real_world_meshes_ = std::make_shared<std::vector<TriangleMesh>>(real.size());
    for (size_t i = 0; i < real.size(); ++i) {
        const RealProxy& r = real[i];
        Surface s;
        s.index = int(i);
        s.albedo = r.albedo.rgb;
        if (r.gloss.specular > 0) {
            s.gloss_f0 = std::min(r.gloss.specular, 1.0f);
            s.gloss_alpha = ggx_alpha(std::max(r.gloss.roughness, kSpecularRoughness));
        }
        if (i < assets_->real_textures.size() && !assets_->real_textures[i].empty())
            s.texture = &assets_->real_textures[i];
        const TriangleMesh* loaded = i < assets_->real_meshes.size() ? &assets_->real_meshes[i] : nullptr;
        const UpAxis up = i < assets_->real_mesh_up.size() ? assets_->real_mesh_up[i] : UpAxis::Y;
        place_shape(r.shape, r.transform, loaded, up, s, (*real_world_meshes_)[i]);
        real_surfaces_.push_back(s);
    }
}

void RenderScene::check_extent() const { check_extent_of(project_, real_surfaces_, virtual_surfaces_, camera_); }

void RenderScene::check_camera() const { check_camera_of(project_.camera, camera_); }

void check_placement(const Project& project, int width, int height) {
    std::vector<Surface> real(project.real.size()), virt(project.objects.size());
    std::vector<TriangleMesh> meshes(real.size() + virt.size());
    for (size_t i = 0; i < real.size(); ++i) {
        real[i].index = int(i);
        place_shape(project.real[i].shape, project.real[i].transform, nullptr, UpAxis::Y, real[i], meshes[i]);
    }
    for (size_t i = 0; i < virt.size(); ++i) {
        virt[i].is_virtual = true;
        virt[i].index = int(i);
        place_shape(project.objects[i].shape, project.objects[i].transform, nullptr, UpAxis::Y, virt[i], meshes[real.size() + i]);
    }
    const Camera camera = project.camera.build(width, height);
    check_extent_of(project, real, virt, camera);
    check_camera_of(project.camera, camera);
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
    vec3 a, b;
    if (!any && bvh_->real_bounds(a, b)) grow(a, b);
    bvh_->set_scale(glm::length(hi - lo));
}

std::shared_ptr<const RenderScene> RenderScene::with_materials(const Project& project) const {
    if (project.objects.size() != project_.objects.size())
        throw std::invalid_argument("with_materials: object count changed");
    // A copy of the surfaces and the project; the assets, world meshes and BVH are shared (the
    // copied surfaces point into them, and nothing changes them after construction).
    std::shared_ptr<RenderScene> v(new RenderScene(*this));
    for (size_t i = 0; i < project.objects.size(); ++i) {
        v->project_.objects[i].material = project.objects[i].material;
        v->virtual_surfaces_[i].material = project.objects[i].material;
        v->virtual_surfaces_[i].albedo = project.objects[i].material.albedo.rgb;
        v->virtual_surfaces_[i].normal_scale = project.objects[i].material.principled.normal_scale;
        // Parts keep their file materials: only the triangles without one take the project's.
    }
    v->has_transmissive_ = any_transmits(v->virtual_surfaces_);
    v->project_.lights = project.lights;
    v->lights_ = LightSet(project.lights, emissive_shapes(v->project_, v->virtual_surfaces_));
    return v;
}

Hit RenderScene::to_hit(const ShapeHit& h) const {
    Hit hit;
    static_cast<ShapeHit&>(hit) = h;
    if (h) {
        const Surface& s =
            h.is_virtual ? virtual_surfaces_[size_t(h.index)] : real_surfaces_[size_t(h.index)];
        hit.surface = &s.part(h.prim);
        if (hit.surface->normal_map) hit.ns = normal_mapped(*hit.surface, hit);
    }
    return hit;
}

Hit RenderScene::intersect_real(const Ray& ray, float tmax) const { return to_hit(bvh_->intersect_real(ray, tmax)); }
Hit RenderScene::intersect_virtual(const Ray& ray, float tmax) const { return to_hit(bvh_->intersect_virtual(ray, tmax)); }
Hit RenderScene::intersect(const Ray& ray, float tmax) const { return to_hit(bvh_->intersect(ray, tmax)); }
bool RenderScene::occluded_real(const Ray& ray, float tmax) const { return bvh_->occluded_real(ray, tmax); }
bool RenderScene::occluded(const Ray& ray, float tmax) const { return bvh_->occluded(ray, tmax); }

Ray RenderScene::camera_ray(float px, float py) const { return bvh_->near_clipped(camera_.generate_ray(px, py)); }

float RenderScene::holdout_t(const Ray& ray) const {
    if (assets_->holdouts.empty()) return INFINITY;
    vec2 px;
    const float cos_axis = glm::dot(ray.dir, camera_.forward());
    if (cos_axis <= 0 || !camera_.project(camera_.position() + ray.dir, px)) return INFINITY;
    // Pixel centres are whole numbers (OpenCV's convention): pixel 0 spans [-0.5, 0.5).
    const float u = (px.x + 0.5f) / float(camera_.width()), v = (px.y + 0.5f) / float(camera_.height());
    float t = INFINITY;
    for (const HoldoutMask& h : assets_->holdouts)
        if (h.covers(u, v)) t = std::min(t, h.depth / cos_axis);
    return t;
}

bool RenderScene::camera_sees(const vec3& p, const vec3& ng, vec2* pixel) const {
    const vec3 to_cam = camera_.position() - p;
    vec2 px;
    if (glm::dot(ng, to_cam) == 0 || !camera_.project(p, px) || !camera_.in_image(px)) return false;
    const float dist = glm::length(to_cam);
    const vec3 d = to_cam / dist;
    const vec3 n = glm::dot(ng, d) > 0 ? ng : -ng;
    if (bvh_->occluded_real(Ray{bvh_->offset_origin(p, n, d), d}, dist * (1 - 1e-4f))) return false;
    if (!assets_->holdouts.empty() && dist > holdout_t(Ray{camera_.position(), -d})) return false;
    if (pixel) *pixel = px;
    return true;
}

}  // namespace dp
