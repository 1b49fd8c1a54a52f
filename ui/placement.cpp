#include "placement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

#include "geometry/mesh.h"

namespace dp::ui {

namespace {

/// Smallest t > eps where the local ray o + t d meets the shape; false if none.
bool hit_local(const Shape& s, const vec3& o, const vec3& d, float& t) {
    const float eps = 1e-5f;
    switch (s.kind) {
        case Shape::Kind::Plane: {
            if (std::abs(d.y) < 1e-12f) return false;
            t = -o.y / d.y;
            const vec3 p = o + t * d;
            return t > eps && std::abs(p.x) <= 0.5f * s.size.x && std::abs(p.z) <= 0.5f * s.size.z;
        }
        case Shape::Kind::Box: {
            float t0 = -INFINITY, t1 = INFINITY;
            for (int a = 0; a < 3; ++a) {
                const float h = 0.5f * s.size[a];
                if (std::abs(d[a]) < 1e-12f) {
                    if (std::abs(o[a]) > h) return false;
                    continue;
                }
                float ta = (-h - o[a]) / d[a], tb = (h - o[a]) / d[a];
                if (ta > tb) std::swap(ta, tb);
                t0 = std::max(t0, ta);
                t1 = std::min(t1, tb);
            }
            if (t0 > t1) return false;
            t = t0 > eps ? t0 : t1;
            return t > eps;
        }
        case Shape::Kind::Sphere: {
            const float a = glm::dot(d, d), b = glm::dot(o, d);
            const float c = glm::dot(o, o) - s.radius * s.radius;
            const float disc = b * b - a * c;
            if (disc < 0 || a <= 0) return false;
            const float q = std::sqrt(disc);
            t = (-b - q) / a;
            if (t <= eps) t = (-b + q) / a;
            return t > eps;
        }
        case Shape::Kind::Mesh:
            return false;
    }
    return false;
}

std::array<vec3, 8> corners(const vec3& lo, const vec3& hi) {
    std::array<vec3, 8> c;
    for (int i = 0; i < 8; ++i)
        c[size_t(i)] = vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    return c;
}

}  // namespace

bool cast_real(const Project& project, const Ray& ray, SurfaceHit& hit) {
    float best = INFINITY;
    if (std::abs(ray.dir.y) > 1e-9f) {
        const float t = -ray.org.y / ray.dir.y;
        if (t > 1e-5f) best = t;
    }
    for (const RealProxy& r : project.real) {
        // Into the proxy's frame; an affine map keeps the ray parameter t.
        const glm::mat4 inv = glm::inverse(r.transform.matrix());
        const vec3 o = vec3(inv * glm::vec4(ray.org, 1.0f));
        const vec3 d = vec3(inv * glm::vec4(ray.dir, 0.0f));
        float t;
        if (hit_local(r.shape, o, d, t) && t < best) best = t;
    }
    if (!std::isfinite(best)) return false;
    hit.t = best;
    hit.point = ray.org + best * ray.dir;
    return true;
}

float surface_below(const Project& project, const vec3& from) {
    // Start a hair above: an object resting exactly on a surface finds that surface.
    Ray down;
    down.org = from + vec3(0, 1e-4f, 0);
    down.dir = vec3(0, -1, 0);
    SurfaceHit hit;
    if (cast_real(project, down, hit)) return hit.point.y;
    return std::min(from.y, 0.0f);
}

bool local_bounds(const Project& project, const VirtualObject& o, vec3& lo, vec3& hi) {
    switch (o.shape.kind) {
        case Shape::Kind::Sphere:
            lo = vec3(-o.shape.radius);
            hi = vec3(o.shape.radius);
            return true;
        case Shape::Kind::Box:
            hi = 0.5f * o.shape.size;
            lo = -hi;
            return true;
        case Shape::Kind::Plane:
            hi = vec3(0.5f * o.shape.size.x, 0, 0.5f * o.shape.size.z);
            lo = -hi;
            return true;
        case Shape::Kind::Mesh:
            break;
    }
    // Meshes are read on the UI thread only; a path's bounds do not change while it is open.
    struct FileBounds {
        vec3 lo, hi;
        UpAxis declared_up;
    };
    static std::map<std::string, FileBounds> cache;
    const std::string path = project.resolve(o.shape.mesh_path).string();
    auto it = cache.find(path);
    if (it == cache.end()) {
        try {
            const LoadedMesh m = load_mesh(path, "mesh");
            vec3 a, b;
            if (!m.mesh.bounds(a, b)) return false;
            it = cache.emplace(path, FileBounds{a, b, declared_up_axis(m.declared_up)}).first;
        } catch (const std::exception&) {
            return false;
        }
    }
    // The file's bounds in the shape's frame: its up axis turned to +Y and its unit applied.
    const glm::mat4 frame = o.shape.file_frame(it->second.declared_up);
    lo = vec3(INFINITY);
    hi = vec3(-INFINITY);
    for (const vec3& c : corners(it->second.lo, it->second.hi)) {
        const vec3 p = vec3(frame * glm::vec4(c, 1.0f));
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return true;
}

float object_bottom(const Project& project, const VirtualObject& o) {
    const glm::mat4 m = o.transform.matrix();
    if (o.shape.kind == Shape::Kind::Sphere) {
        // The lowest point of the ellipsoid: centre minus r times the length of M's y row.
        const vec3 row(m[0][1], m[1][1], m[2][1]);
        return m[3][1] - o.shape.radius * glm::length(row);
    }
    vec3 lo, hi;
    if (!local_bounds(project, o, lo, hi)) return o.transform.translation.y;
    float bottom = INFINITY;
    for (const vec3& c : corners(lo, hi)) bottom = std::min(bottom, (m * glm::vec4(c, 1.0f)).y);
    return bottom;
}

void world_sphere(const Project& project, const VirtualObject& o, vec3& centre, float& radius) {
    const vec3 s = glm::abs(o.transform.scale);
    if (o.shape.kind == Shape::Kind::Sphere) {
        centre = o.transform.translation;
        radius = o.shape.radius * std::max({s.x, s.y, s.z});
        return;
    }
    vec3 lo, hi;
    if (!local_bounds(project, o, lo, hi)) lo = hi = vec3(0);
    centre = vec3(o.transform.matrix() * glm::vec4(0.5f * (lo + hi), 1.0f));
    radius = 0.5f * glm::length((hi - lo) * s);
}

Transform dropped_to_surface(const Project& project, const VirtualObject& o) {
    Transform t = o.transform;
    const float bottom = object_bottom(project, o);
    // The surface under the object's footprint centre, looked for from its lowest point.
    const float below = surface_below(project, vec3(t.translation.x, bottom, t.translation.z));
    t.translation.y += below - bottom;
    return t;
}

Transform kept_on_base(const Project& project, const VirtualObject& before,
                       const Transform& after) {
    VirtualObject o = before;
    o.transform = after;
    Transform t = after;
    t.translation.y += object_bottom(project, before) - object_bottom(project, o);
    return t;
}

VisibleGround visible_ground(const Project& project, const Camera& camera) {
    VisibleGround g;
    const int w = camera.width(), h = camera.height();
    if (w <= 0 || h <= 0) return g;
    SurfaceHit centre;
    const bool centreHit =
        cast_real(project, camera.generate_ray(0.5f * (w - 1), 0.5f * (h - 1)), centre);
    const float eyeHeight = std::max(std::abs(camera.position().y), 0.1f);
    const float cap = centreHit ? centre.t : 10.0f * eyeHeight;
    constexpr int kCols = 33, kRows = 25;
    g.lo = vec3(INFINITY);
    g.hi = vec3(-INFINITY);
    for (int j = 0; j < kRows; ++j)
        for (int i = 0; i < kCols; ++i) {
            const float px = (w - 1) * float(i) / (kCols - 1),
                        py = (h - 1) * float(j) / (kRows - 1);
            SurfaceHit hit;
            if (!cast_real(project, camera.generate_ray(px, py), hit) || hit.t > cap * 1.0001f)
                continue;
            g.lo = glm::min(g.lo, hit.point);
            g.hi = glm::max(g.hi, hit.point);
            g.valid = true;
        }
    if (g.valid) g.extent = std::clamp(std::max(g.hi.x - g.lo.x, g.hi.z - g.lo.z), 0.2f, 500.0f);
    return g;
}

float grid_spacing(float extent) {
    if (!(extent > 0) || !std::isfinite(extent)) return 0.5f;
    const float target = 0.1f * extent;
    float decade = std::pow(10.0f, std::floor(std::log10(target)));
    if (10 * decade <= target * 1.0001f) decade *= 10;  // log10 rounded below a whole power
    if (decade > target * 1.0001f) decade /= 10;
    for (float m : {5.0f, 2.0f, 1.0f})
        if (m * decade <= target * 1.0001f) return m * decade;
    return decade;
}

GroundGrid ground_grid(const Project& project, const Camera& camera) {
    GroundGrid g;
    const VisibleGround v = visible_ground(project, camera);
    if (!v.valid) return g;  // nothing seen of the ground: half a metre round the origin
    g.spacing = grid_spacing(v.extent);
    const vec3 c = view_centre_point(project, camera);
    g.centre = vec3(std::round(c.x / g.spacing) * g.spacing, 0.0f, std::round(c.z / g.spacing) * g.spacing);
    // Enough lines to cover what is seen from the centre, not a horizon's worth.
    const float reach = std::max({std::abs(v.lo.x - g.centre.x), std::abs(v.hi.x - g.centre.x),
                                  std::abs(v.lo.z - g.centre.z), std::abs(v.hi.z - g.centre.z)});
    g.half_lines = std::clamp(int(std::ceil(reach / g.spacing)) + 1, 5, 40);
    return g;
}

float view_object_size(const Project& project, const Camera& camera) {
    const VisibleGround g = visible_ground(project, camera);
    return g.valid ? std::clamp(0.1f * g.extent, 0.02f, 50.0f) : 0.5f;
}

vec3 view_centre_point(const Project& project, const Camera& camera) {
    SurfaceHit hit;
    if (camera.width() > 0 &&
        cast_real(project,
                  camera.generate_ray(0.5f * (camera.width() - 1), 0.5f * (camera.height() - 1)),
                  hit))
        return hit.point;
    const vec3 at =
        project.camera.model == CameraSpec::Model::LookAt ? project.camera.target : vec3(0);
    return vec3(at.x, surface_below(project, vec3(at.x, 1e4f, at.z)), at.z);
}

void place_free(const Project& project, VirtualObject& o, const vec3& at, const Camera* camera) {
    vec3 c;
    float r;
    o.transform.translation = vec3(0);
    world_sphere(project, o, c, r);
    // The shape's centre goes to the spot (a mesh's own origin may be anywhere).
    const vec3 offset = c;
    std::vector<std::pair<vec3, float>> others;
    for (const VirtualObject& other : project.objects) {
        vec3 oc;
        float orad;
        world_sphere(project, other, oc, orad);
        others.emplace_back(oc, orad);
    }
    // Rests on the first real surface below a point a little above the target height: a spot
    // off a table top drops to the floor.
    const float from = at.y + std::max(2.0f * r, 0.01f);
    auto rest_at = [&](float x, float z) {
        VirtualObject probe = o;
        probe.transform.translation = vec3(x - offset.x, 0, z - offset.z);
        const float bottom = object_bottom(project, probe);
        probe.transform.translation.y = surface_below(project, vec3(x, from, z)) - bottom;
        return probe.transform;
    };
    auto free = [&](const Transform& t) {
        VirtualObject probe = o;
        probe.transform = t;
        vec3 pc;
        float pr;
        world_sphere(project, probe, pc, pr);
        for (const auto& [oc, orad] : others) {
            if (glm::length(pc - oc) < pr + orad) return false;
            if (!camera) continue;
            // Hidden: the line of sight to its centre passes within half its radius of another.
            const vec3 eye = camera->position();
            const float dist = glm::length(pc - eye);
            if (dist <= 0) continue;
            const vec3 dir = (pc - eye) / dist;
            const float s = std::clamp(glm::dot(oc - eye, dir), 0.0f, dist);
            if (glm::length(eye + s * dir - oc) < orad + 0.5f * pr) return false;
        }
        return true;
    };
    if (const Transform t = rest_at(at.x, at.z); free(t)) {
        o.transform = t;
        return;
    }
    // Rings a quarter radius apart, nearest first: the first free point is the nearest free
    // spot to that resolution.
    const float step = std::max(0.25f * r, 1e-3f);
    for (int ring = 1; ring <= 400; ++ring) {
        const float dist = step * float(ring);
        const int n = std::max(8, int(std::ceil(2.0f * kPi * float(ring))));
        for (int i = 0; i < n; ++i) {
            const float a = 2.0f * kPi * float(i) / float(n);
            const Transform t = rest_at(at.x + dist * std::cos(a), at.z + dist * std::sin(a));
            if (free(t)) {
                o.transform = t;
                return;
            }
        }
    }
    o.transform = rest_at(at.x, at.z);
}

VirtualObject new_primitive(const Project& project, const Camera& camera, Shape::Kind kind,
                            const std::string& name) {
    const float size = view_object_size(project, camera);
    VirtualObject o;
    o.name = name;
    o.shape.kind = kind;
    o.material.kind = Material::Kind::Diffuse;
    o.material.albedo.rgb = vec3(0.7f);
    switch (kind) {
        case Shape::Kind::Sphere:
            o.shape.radius = 0.5f * size;
            break;
        case Shape::Kind::Box:
            o.shape.size = vec3(size);
            break;
        case Shape::Kind::Plane:
            // A card standing upright, so that it is seen and casts a shadow.
            o.shape.size = vec3(size, 1.0f, 1.25f * size);
            o.transform.rotation_deg = vec3(90, 0, 0);
            break;
        case Shape::Kind::Mesh:
            break;
    }
    place_free(project, o, view_centre_point(project, camera), &camera);
    return o;
}

VirtualLight new_light(const Project& project, const Camera& camera, VirtualLight::Kind kind,
                       const std::string& name) {
    const VisibleGround g = visible_ground(project, camera);
    const float height = g.valid ? std::clamp(0.25f * g.extent, 0.3f, 50.0f) : 1.5f;
    VirtualLight l;
    l.name = name;
    l.kind = kind;
    l.transform.translation = view_centre_point(project, camera) + vec3(0, height, 0);
    // Irradiance falls with the distance squared: scaled so, the floor below is lit alike.
    l.power_w = std::min(150.0f * (height / 1.5f) * (height / 1.5f), kMaxLightPower);
    l.spot_angle_deg = 60.0f;
    l.size = vec2(height / 3.0f);
    return l;
}

UnitGuess guess_mesh_unit(float size) {
    // Objects put into photographs are mostly 0.1 to 10 m: the unit that brings the file's
    // numbers into that range is the likely one.
    if (size >= 100.0f) return {0.001f, "millimetres"};
    if (size >= 10.0f) return {0.01f, "centimetres"};
    return {1.0f, "metres"};
}

}  // namespace dp::ui
