#include "scene/project_io.h"
#include "base/atomic_file.h"

#include <functional>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <string_view>

#include "base/error.h"
#include "scene/json_reader.h"

namespace dp {
namespace {

// The project schema (docs/project-format.md) over the general JSON reader.
using json = nlohmann::json;

Transform parse_transform(const JsonReader& r, const json& j, const std::string& path) {
    r.object(j, path, {"translation", "rotation_deg", "scale"});
    Transform t;
    if (auto* v = r.optional(j, "translation"))
        t.translation = r.vector3(*v, json_join(path, "translation"));
    if (auto* v = r.optional(j, "rotation_deg"))
        t.rotation_deg = r.vector3(*v, json_join(path, "rotation_deg"));
    if (auto* v = r.optional(j, "scale")) t.scale = r.positive3(*v, json_join(path, "scale"));
    return t;
}

Shape parse_shape(const JsonReader& r, const json& j, const std::string& path) {
    if (!j.is_object()) r.wrong_type(j, path, "an object");
    Shape s;
    s.kind =
        r.choice<Shape::Kind>(r.required(j, path, "type"), json_join(path, "type"), "shape type",
                              kShapeKinds);
    std::string ctx = " for shape type '" + j["type"].get<std::string>() + "'";
    switch (s.kind) {
        case Shape::Kind::Plane:
            r.object(j, path, {"type", "size"}, ctx);
            s.size = r.positive3(r.required(j, path, "size"), json_join(path, "size"), 2);
            break;
        case Shape::Kind::Box:
            r.object(j, path, {"type", "size"}, ctx);
            s.size = r.positive3(r.required(j, path, "size"), json_join(path, "size"));
            break;
        case Shape::Kind::Sphere: {
            r.object(j, path, {"type", "radius"}, ctx);
            std::string p = json_join(path, "radius");
            s.radius = r.real(r.required(j, path, "radius"), p);
            r.check(s.radius > 0, p, "must be > 0 (got " + shortest_decimal(s.radius) + ")");
            break;
        }
        case Shape::Kind::Mesh: {
            r.object(j, path, {"type", "path", "up_axis", "unit_scale"}, ctx);
            s.mesh_path = r.string(r.required(j, path, "path"), json_join(path, "path"));
            if (auto* v = r.optional(j, "up_axis"))
                s.up_axis = r.choice<UpAxis>(*v, json_join(path, "up_axis"), "up axis", kUpAxes);
            if (auto* v = r.optional(j, "unit_scale")) {
                const std::string p = json_join(path, "unit_scale");
                s.unit_scale = r.real(*v, p);
                r.check(s.unit_scale > 0, p,
                        "must be > 0 metres per file unit (got " + shortest_decimal(s.unit_scale) + ")");
            }
            break;
        }
    }
    return s;
}

/// [r, g, b] | {"texture": path} | "estimate" (the last only where `allow_estimate`).
Albedo parse_albedo(const JsonReader& r, const json& j, const std::string& path,
                    bool allow_estimate) {
    Albedo a;
    const char* forms = allow_estimate ? "[r, g, b], {\"texture\": path} or \"estimate\""
                                       : "[r, g, b] or {\"texture\": path}";
    if (j.is_array()) {
        a.rgb = r.colour(j, path);
    } else if (j.is_object()) {
        r.object(j, path, {"texture"});
        a.kind = Albedo::Kind::Texture;
        a.texture_path = r.string(r.required(j, path, "texture"), json_join(path, "texture"));
    } else if (j.is_string()) {
        std::string s = j.get<std::string>();
        if (s == "estimate" && !allow_estimate)
            r.fail(path,
                   "\"estimate\" is only valid for real proxies; expected " + std::string(forms));
        if (s != "estimate") r.fail(path, "unknown albedo '" + s + "' (expected " + forms + ")");
        a.kind = Albedo::Kind::Estimate;
    } else {
        r.wrong_type(j, path, forms);
    }
    return a;
}

/// A number in [lo, hi] (an out-of-range value names the field and the range).
float bounded(const JsonReader& r, const json& j, const std::string& path, float lo, float hi) {
    const float v = r.real(j, path);
    r.check(v >= lo && v <= hi, path,
            "must be in [" + shortest_decimal(lo) + ", " + shortest_decimal(hi) + "] (got " + shortest_decimal(v) +
                ")");
    return v;
}

/// The principled material's fields other than its type (docs/project-format.md).
void parse_principled(const JsonReader& r, const json& j, const std::string& path, Material& m) {
    PrincipledMaterial& p = m.principled;
    if (auto* v = r.optional(j, "base_colour")) m.albedo = parse_albedo(r, *v, json_join(path, "base_colour"), false);
    auto unit = [&](const char* key, float& out) {
        if (auto* v = r.optional(j, key)) out = bounded(r, *v, json_join(path, key), 0.0f, 1.0f);
    };
    unit("metallic", p.metallic);
    unit("roughness", p.roughness);
    unit("specular", p.specular);
    unit("transmission", p.transmission);
    if (auto* v = r.optional(j, "ior"))
        p.ior = bounded(r, *v, json_join(path, "ior"), kMinPrincipledIor, kMaxPrincipledIor);
    if (auto* v = r.optional(j, "metallic_roughness_texture"))
        p.metallic_roughness_texture = r.string(*v, json_join(path, "metallic_roughness_texture"));
    if (auto* v = r.optional(j, "normal_texture")) p.normal_texture = r.string(*v, json_join(path, "normal_texture"));
    if (auto* v = r.optional(j, "normal_scale"))
        p.normal_scale = bounded(r, *v, json_join(path, "normal_scale"), 0.0f, 10.0f);
    if (auto* v = r.optional(j, "emission")) {
        const std::string e = json_join(path, "emission");
        p.emission = r.vector3(*v, e);
        for (int i = 0; i < 3; ++i)
            r.check(p.emission[i] >= 0, json_at(e, size_t(i)),
                    "must be >= 0 (got " + shortest_decimal(p.emission[i]) + ")");
    }
}

Material parse_material(const JsonReader& r, const json& j, const std::string& path) {
    if (!j.is_object()) r.wrong_type(j, path, "an object");
    Material m;
    m.kind = r.choice<Material::Kind>(r.required(j, path, "type"), json_join(path, "type"),
                                      "material type",
                                      {{"diffuse", Material::Kind::Diffuse},
                                       {"mirror", Material::Kind::Mirror},
                                       {"glass", Material::Kind::Glass},
                                       {"principled", Material::Kind::Principled}});
    std::string ctx = " for material type '" + j["type"].get<std::string>() + "'";
    switch (m.kind) {
        case Material::Kind::Diffuse:
            r.object(j, path, {"type", "albedo"}, ctx);
            if (auto* v = r.optional(j, "albedo"))
                m.albedo = parse_albedo(r, *v, json_join(path, "albedo"), false);
            break;
        case Material::Kind::Mirror:
            r.object(j, path, {"type", "reflectance"}, ctx);
            if (auto* v = r.optional(j, "reflectance"))
                m.reflectance = r.colour(*v, json_join(path, "reflectance"));
            break;
        case Material::Kind::Glass:
            r.object(j, path, {"type", "ior", "tint"}, ctx);
            if (auto* v = r.optional(j, "ior")) {
                m.ior = r.real(*v, json_join(path, "ior"));
                r.check(m.ior > 0, json_join(path, "ior"),
                        "must be > 0 (got " + shortest_decimal(m.ior) + ")");
            }
            if (auto* v = r.optional(j, "tint")) m.tint = r.colour(*v, json_join(path, "tint"));
            break;
        case Material::Kind::Principled:
            r.object(j, path,
                     {"type", "base_colour", "metallic", "roughness", "ior", "specular", "transmission", "emission",
                      "metallic_roughness_texture", "normal_texture", "normal_scale"},
                     ctx);
            parse_principled(r, j, path, m);
            break;
    }
    return m;
}

std::string parse_name(const JsonReader& r, const json& j, const std::string& path) {
    auto* v = r.optional(j, "name");
    return v ? r.string(*v, json_join(path, "name"), false) : std::string();
}

RealProxy parse_real(const JsonReader& r, const json& j, const std::string& path) {
    r.object(j, path, {"name", "shape", "transform", "albedo", "gloss"});
    RealProxy p;
    p.name = parse_name(r, j, path);
    p.shape = parse_shape(r, r.required(j, path, "shape"), json_join(path, "shape"));
    if (auto* v = r.optional(j, "transform"))
        p.transform = parse_transform(r, *v, json_join(path, "transform"));
    if (auto* v = r.optional(j, "albedo"))
        p.albedo = parse_albedo(r, *v, json_join(path, "albedo"), true);
    if (auto* v = r.optional(j, "gloss")) {
        const std::string g = json_join(path, "gloss");
        r.object(*v, g, {"specular", "roughness"});
        if (auto* x = r.optional(*v, "specular")) p.gloss.specular = bounded(r, *x, json_join(g, "specular"), 0.0f, 1.0f);
        if (auto* x = r.optional(*v, "roughness")) p.gloss.roughness = bounded(r, *x, json_join(g, "roughness"), 0.0f, 1.0f);
    }
    return p;
}

VirtualObject parse_object(const JsonReader& r, const json& j, const std::string& path) {
    r.object(j, path, {"name", "shape", "transform", "material", "material_source", "visible"});
    VirtualObject o;
    o.name = parse_name(r, j, path);
    o.shape = parse_shape(r, r.required(j, path, "shape"), json_join(path, "shape"));
    if (auto* v = r.optional(j, "material_source")) {
        const std::string p = json_join(path, "material_source");
        o.material_source = r.choice<MaterialSource>(*v, p, "material source", kMaterialSources);
        r.check(o.material_source == MaterialSource::Project || o.shape.kind == Shape::Kind::Mesh,
                p,
                "\"file\" takes the materials of a mesh file, and this shape is a " +
                    std::string(shape_kind_name(o.shape.kind)));
    }
    if (auto* v = r.optional(j, "transform"))
        o.transform = parse_transform(r, *v, json_join(path, "transform"));
    if (auto* v = r.optional(j, "material"))
        o.material = parse_material(r, *v, json_join(path, "material"));
    if (auto* v = r.optional(j, "visible")) o.visible = r.boolean(*v, json_join(path, "visible"));
    return o;
}

Holdout parse_holdout(const JsonReader& r, const json& j, const std::string& path) {
    if (!j.is_object()) r.wrong_type(j, path, "an object");
    r.object(j, path, {"name", "mask", "depth"});
    Holdout h;
    h.name = parse_name(r, j, path);
    h.mask = r.string(r.required(j, path, "mask"), json_join(path, "mask"));
    const std::string p = json_join(path, "depth");
    h.depth = r.real(r.required(j, path, "depth"), p);
    r.check(h.depth > 0 && h.depth <= kMaxHoldoutDepth, p,
            "must be in (0, " + shortest_decimal(kMaxHoldoutDepth) + "] metres from the camera (got " +
                shortest_decimal(h.depth) + ")");
    return h;
}

VirtualLight parse_light(const JsonReader& r, const json& j, const std::string& path) {
    if (!j.is_object()) r.wrong_type(j, path, "an object");
    VirtualLight l;
    l.kind = r.choice<VirtualLight::Kind>(r.required(j, path, "type"), json_join(path, "type"), "light type",
                                          kLightKinds);
    const std::string ctx = " for light type '" + j["type"].get<std::string>() + "'";
    if (l.kind == VirtualLight::Kind::Point)
        r.object(j, path, {"name", "type", "transform", "colour", "power_w"}, ctx);
    else if (l.kind == VirtualLight::Kind::Spot)
        r.object(j, path, {"name", "type", "transform", "colour", "power_w", "spot_angle_deg", "spot_blend"}, ctx);
    else
        r.object(j, path, {"name", "type", "transform", "colour", "power_w", "size", "visible"}, ctx);
    l.name = parse_name(r, j, path);
    if (auto* v = r.optional(j, "transform")) l.transform = parse_transform(r, *v, json_join(path, "transform"));
    if (auto* v = r.optional(j, "colour")) l.colour = r.colour(*v, json_join(path, "colour"));
    if (auto* v = r.optional(j, "power_w")) l.power_w = bounded(r, *v, json_join(path, "power_w"), 0.0f, kMaxLightPower);
    if (auto* v = r.optional(j, "spot_angle_deg")) {
        const std::string p = json_join(path, "spot_angle_deg");
        l.spot_angle_deg = bounded(r, *v, p, 0.0f, 180.0f);
        r.check(l.spot_angle_deg > 0, p, "must be > 0 (got 0)");
    }
    if (auto* v = r.optional(j, "spot_blend")) l.spot_blend = bounded(r, *v, json_join(path, "spot_blend"), 0.0f, 1.0f);
    if (auto* v = r.optional(j, "size")) {
        const std::string p = json_join(path, "size");
        const size_t n = l.kind == VirtualLight::Kind::Disk ? 1 : 2;
        r.check(!v->is_array() || v->size() == n, p,
                n == 1 ? "a disk's size is one number, its diameter: [d]" : "a rect's size is two numbers: [x, z]");
        const std::vector<float> s = r.numbers(*v, p, n);
        for (size_t i = 0; i < n; ++i)
            r.check(s[i] > 0 && s[i] <= 1e6f, json_at(p, i), "must be in (0, 1e6] metres (got " + shortest_decimal(s[i]) + ")");
        l.size = n == 1 ? vec2(s[0]) : vec2(s[0], s[1]);
    }
    if (auto* v = r.optional(j, "visible")) l.visible = r.boolean(*v, json_join(path, "visible"));
    return l;
}

void parse_lookat(const JsonReader& r, const json& j, CameraSpec& c) {
    c.eye = r.vector3(r.required(j, "camera", "eye"), "camera.eye");
    c.target = r.vector3(r.required(j, "camera", "target"), "camera.target");
    if (auto* v = r.optional(j, "up")) c.up = r.vector3(*v, "camera.up");
    if (auto* v = r.optional(j, "vfov_deg")) c.vfov_deg = r.real(*v, "camera.vfov_deg");
    r.check(c.vfov_deg > 0 && c.vfov_deg < 180, "camera.vfov_deg",
            "must be in (0, 180) degrees (got " + shortest_decimal(c.vfov_deg) + ")");
    vec3 forward = c.target - c.eye;
    r.check(glm::length(forward) > 0, "camera.target", "must differ from camera.eye");
    r.check(glm::length(c.up) > 0, "camera.up", "must not be the zero vector");
    float s = glm::length(glm::cross(glm::normalize(forward), glm::normalize(c.up)));
    r.check(s > 1e-4f, "camera.up", "must not be parallel to the viewing direction");
}

void parse_opencv(const JsonReader& r, const json& j, CameraSpec& c) {
    auto focal = [&](const char* key, float& out) {
        std::string p = json_join("camera", key);
        out = r.real(r.required(j, "camera", key), p);
        r.check(out > 0, p, "must be > 0 pixels (got " + shortest_decimal(out) + ")");
    };
    focal("fx", c.fx);
    focal("fy", c.fy);
    c.cx = r.real(r.required(j, "camera", "cx"), "camera.cx");
    c.cy = r.real(r.required(j, "camera", "cy"), "camera.cy");
    if (auto* v = r.optional(j, "distortion")) {
        // OpenCV writes 4 or 5 coefficients for this model; rational/thin-prism models are
        // not supported.
        const std::string p = "camera.distortion";
        if (!v->is_array()) r.wrong_type(*v, p, "an array [k1, k2, p1, p2, k3]");
        r.check(
            v->size() == 4 || v->size() == 5, p,
            "expected 4 or 5 coefficients [k1, k2, p1, p2, k3], got " + std::to_string(v->size()));
        auto k = r.numbers(*v, p, v->size());
        c.distortion = Distortion{k[0], k[1], k[2], k[3], k.size() == 5 ? k[4] : 0.0f};
    }
    const json& rot = r.required(j, "camera", "rotation");
    if (!rot.is_array() || rot.size() != 3)
        r.fail("camera.rotation", "expected 3 rows of 3 numbers (row-major world-to-camera R)");
    for (int row = 0; row < 3; ++row) {
        vec3 v = r.vector3(rot[size_t(row)], json_at("camera.rotation", size_t(row)));
        for (int col = 0; col < 3; ++col) c.rotation[col][row] = v[col];  // glm: [column][row]
    }
    glm::mat3 e = c.rotation * glm::transpose(c.rotation) - glm::mat3(1.0f);
    float err = 0;
    for (int i = 0; i < 3; ++i)
        err = std::max({err, std::abs(e[i].x), std::abs(e[i].y), std::abs(e[i].z)});
    r.check(err < 1e-3f, "camera.rotation",
            "must be a rotation matrix (R R^T differs from I by " + shortest_decimal(err) + ")");
    r.check(glm::determinant(c.rotation) > 0, "camera.rotation",
            "must be a rotation matrix (determinant is -1: a reflection)");
    c.translation = r.vector3(r.required(j, "camera", "translation"), "camera.translation");
}

CameraSpec parse_camera(const JsonReader& r, const json& j) {
    if (!j.is_object()) r.wrong_type(j, "camera", "an object");
    CameraSpec c;
    c.model = r.choice<CameraSpec::Model>(
        r.required(j, "camera", "model"), "camera.model", "camera model",
        {{"lookat", CameraSpec::Model::LookAt}, {"opencv", CameraSpec::Model::Intrinsics}});
    if (c.model == CameraSpec::Model::LookAt) {
        r.object(j, "camera", {"model", "eye", "target", "up", "vfov_deg"},
                 " for camera model 'lookat'");
        parse_lookat(r, j, c);
    } else {
        r.object(j, "camera",
                 {"model", "fx", "fy", "cx", "cy", "distortion", "rotation", "translation"},
                 " for camera model 'opencv'");
        parse_opencv(r, j, c);
    }
    return c;
}

RenderSettings parse_render(const JsonReader& r, const json& j) {
    r.object(j, "render",
             {"photons_per_pass", "passes", "time_budget_s", "initial_radius", "alpha", "max_depth",
              "seed", "threads", "estimator", "adaptive_threshold", "adaptive_min_passes",
              "low_discrepancy", "balance_photons"});
    constexpr int64_t kIntMax = std::numeric_limits<int>::max();
    constexpr int64_t kInt64Max = std::numeric_limits<int64_t>::max();
    RenderSettings s;
    if (auto* v = r.optional(j, "photons_per_pass"))
        s.photons_per_pass = r.integer(*v, "render.photons_per_pass", 1, kInt64Max);
    if (auto* v = r.optional(j, "passes"))
        s.passes = int(r.integer(*v, "render.passes", 1, kIntMax));
    if (auto* v = r.optional(j, "time_budget_s")) {
        s.time_budget_s = r.number(*v, "render.time_budget_s");
        r.check(s.time_budget_s >= 0, "render.time_budget_s",
                "must be >= 0 seconds (got " + shortest_decimal(s.time_budget_s) + ")");
    }
    if (auto* v = r.optional(j, "initial_radius"); v && !v->is_null()) {  // null: automatic
        float radius = r.real(*v, "render.initial_radius");
        r.check(radius > 0, "render.initial_radius",
                "must be > 0 (got " + shortest_decimal(radius) + ")");
        s.initial_radius = radius;
    }
    if (auto* v = r.optional(j, "alpha")) {
        s.alpha = r.real(*v, "render.alpha");
        r.check(s.alpha > 0 && s.alpha < 1, "render.alpha",
                "must be in (0, 1) exclusive (got " + shortest_decimal(s.alpha) + ")");
    }
    if (auto* v = r.optional(j, "max_depth"))
        s.max_depth = int(r.integer(*v, "render.max_depth", 1, kIntMax));
    if (auto* v = r.optional(j, "seed")) s.seed = r.unsigned_integer(*v, "render.seed");
    if (auto* v = r.optional(j, "threads"))
        s.threads = int(r.integer(*v, "render.threads", 0, kIntMax));
    if (auto* v = r.optional(j, "estimator"))
        s.estimator =
            r.choice<Estimator>(*v, "render.estimator", "estimator",
                                {{"split", Estimator::Split}, {"photons", Estimator::Photons}});
    if (auto* v = r.optional(j, "adaptive_threshold")) {
        s.adaptive_threshold = r.real(*v, "render.adaptive_threshold");
        r.check(s.adaptive_threshold >= 0 && s.adaptive_threshold < 1, "render.adaptive_threshold",
                "must be in [0, 1) (got " + shortest_decimal(s.adaptive_threshold) +
                    "; 0 turns adaptive sampling off)");
    }
    if (auto* v = r.optional(j, "adaptive_min_passes"))
        s.adaptive_min_passes = int(r.integer(*v, "render.adaptive_min_passes", 2, kIntMax));
    if (auto* v = r.optional(j, "low_discrepancy"))
        s.low_discrepancy = r.boolean(*v, "render.low_discrepancy");
    if (auto* v = r.optional(j, "balance_photons"))
        s.balance_photons = r.boolean(*v, "render.balance_photons");
    return s;
}

// ---- writing -------------------------------------------------------------------------------

/// Float as the double with the float's shortest decimal text, so files read "0.1", not
/// "0.10000000149011612", and still load back bit-exactly.
double num(float f) {
    if (!std::isfinite(f)) return double(f);
    char buf[32];
    auto res = std::to_chars(buf, buf + sizeof(buf), f);
    double d = 0;
    std::from_chars(buf, res.ptr, d);
    return d;
}

template <class J>
J vec(const vec3& v) {
    return J::array({num(v.x), num(v.y), num(v.z)});
}

template <class J>
J write_transform(const Transform& t) {
    return J{{"translation", vec<J>(t.translation)},
             {"rotation_deg", vec<J>(t.rotation_deg)},
             {"scale", vec<J>(t.scale)}};
}

template <class J>
J write_shape(const Shape& s) {
    switch (s.kind) {
        case Shape::Kind::Plane:  // size [x, z]: a plane has no extent along its normal
            return J{{"type", shape_kind_name(s.kind)}, {"size", J::array({num(s.size.x), num(s.size.z)})}};
        case Shape::Kind::Box:
            return J{{"type", shape_kind_name(s.kind)}, {"size", vec<J>(s.size)}};
        case Shape::Kind::Sphere:
            return J{{"type", shape_kind_name(s.kind)}, {"radius", num(s.radius)}};
        case Shape::Kind::Mesh: {
            J j{{"type", shape_kind_name(s.kind)}, {"path", s.mesh_path}};
            // Absent stays absent: the file's own axis then applies, whatever file it becomes.
            if (s.up_axis) j["up_axis"] = up_axis_name(*s.up_axis);
            j["unit_scale"] = num(s.unit_scale);
            return j;
        }
    }
    return J();
}

template <class J>
J write_albedo(const Albedo& a) {
    switch (a.kind) {
        case Albedo::Kind::Constant:
            return vec<J>(a.rgb);
        case Albedo::Kind::Texture:
            return J{{"texture", a.texture_path}};
        case Albedo::Kind::Estimate:
            return J("estimate");
    }
    return J();
}

template <class J>
J write_material(const Material& m) {
    switch (m.kind) {
        case Material::Kind::Diffuse:
            return J{{"type", "diffuse"}, {"albedo", write_albedo<J>(m.albedo)}};
        case Material::Kind::Mirror:
            return J{{"type", "mirror"}, {"reflectance", vec<J>(m.reflectance)}};
        case Material::Kind::Glass:
            return J{{"type", "glass"}, {"ior", num(m.ior)}, {"tint", vec<J>(m.tint)}};
        case Material::Kind::Principled: {
            const PrincipledMaterial& p = m.principled;
            J out{{"type", "principled"},           {"base_colour", write_albedo<J>(m.albedo)},
                  {"metallic", num(p.metallic)},    {"roughness", num(p.roughness)},
                  {"ior", num(p.ior)},              {"specular", num(p.specular)},
                  {"transmission", num(p.transmission)}, {"emission", vec<J>(p.emission)}};
            // Written only where used, so that projects without them read as before.
            if (!p.metallic_roughness_texture.empty()) out["metallic_roughness_texture"] = p.metallic_roughness_texture;
            if (!p.normal_texture.empty()) out["normal_texture"] = p.normal_texture;
            if (p.normal_scale != 1.0f) out["normal_scale"] = num(p.normal_scale);
            return out;
        }
    }
    return J();
}

template <class J>
J write_camera(const CameraSpec& c) {
    if (c.model == CameraSpec::Model::LookAt) {
        return J{{"model", "lookat"},
                 {"eye", vec<J>(c.eye)},
                 {"target", vec<J>(c.target)},
                 {"up", vec<J>(c.up)},
                 {"vfov_deg", num(c.vfov_deg)}};
    }
    const Distortion& d = c.distortion;
    J rows = J::array();
    for (int row = 0; row < 3; ++row) {  // row-major in the file, column-major in glm
        const glm::mat3& R = c.rotation;
        rows.push_back(J::array({num(R[0][row]), num(R[1][row]), num(R[2][row])}));
    }
    return J{{"model", "opencv"},
             {"fx", num(c.fx)},
             {"fy", num(c.fy)},
             {"cx", num(c.cx)},
             {"cy", num(c.cy)},
             {"distortion", J::array({num(d.k1), num(d.k2), num(d.p1), num(d.p2), num(d.k3)})},
             {"rotation", rows},
             {"translation", vec<J>(c.translation)}};
}

template <class J>
J write_project(const Project& p) {
    J doc;
    doc["schema_version"] = p.schema_version;
    doc["photo"] = J{{"path", p.photo.path}, {"exposure", num(p.photo.exposure)}};
    if (!p.photo.colorspace.empty()) doc["photo"]["colorspace"] = p.photo.colorspace;
    if (!p.photo.layer.empty()) doc["photo"]["layer"] = p.photo.layer;
    doc["probe"] =
        J{{"path", p.probe.path},
          {"format", p.probe.format == ProbeSpec::Format::LatLong ? "latlong" : "mirrorball"},
          {"rotation_deg", vec<J>(p.probe.rotation_deg)},
          {"intensity", num(p.probe.intensity)}};
    // Neutral is left out: such a file stays readable by builds that know no white balance.
    if (p.probe.white_balance != vec3(1.0f))
        doc["probe"]["white_balance"] = vec<J>(p.probe.white_balance);
    doc["probe"]["mirror_ball_fov_deg"] = num(p.probe.mirror_ball_fov_deg);
    // Automatic is left out, as a neutral white balance is.
    if (p.probe.max_width > 0) doc["probe"]["max_width"] = p.probe.max_width;
    if (p.probe.sun_scale != 1.0f) doc["probe"]["sun_scale"] = p.probe.sun_scale;
    doc["camera"] = write_camera<J>(p.camera);
    doc["real"] = J::array();
    for (const RealProxy& r : p.real) {
        J proxy{{"name", r.name},
                {"shape", write_shape<J>(r.shape)},
                {"transform", write_transform<J>(r.transform)},
                {"albedo", write_albedo<J>(r.albedo)}};
        // Matte is left out: such a file stays readable by builds without gloss.
        if (r.gloss.specular > 0)
            proxy["gloss"] = J{{"specular", num(r.gloss.specular)}, {"roughness", num(r.gloss.roughness)}};
        doc["real"].push_back(proxy);
    }
    doc["objects"] = J::array();
    for (const VirtualObject& o : p.objects) {
        J object{{"name", o.name},
                 {"shape", write_shape<J>(o.shape)},
                 {"transform", write_transform<J>(o.transform)},
                 {"material", write_material<J>(o.material)}};
        // Only a mesh has a file to take materials from.
        if (o.shape.kind == Shape::Kind::Mesh)
            object["material_source"] = material_source_name(o.material_source);
        object["visible"] = o.visible;
        doc["objects"].push_back(object);
    }
    // Written only when there are lights: such a file stays readable by builds without them.
    if (!p.lights.empty()) {
        doc["lights"] = J::array();
        for (const VirtualLight& l : p.lights) {
            J light{{"name", l.name},
                    {"type", light_kind_name(l.kind)},
                    {"transform", write_transform<J>(l.transform)},
                    {"colour", vec<J>(l.colour)},
                    {"power_w", num(l.power_w)}};
            if (l.kind == VirtualLight::Kind::Spot) {
                light["spot_angle_deg"] = num(l.spot_angle_deg);
                light["spot_blend"] = num(l.spot_blend);
            }
            if (l.kind == VirtualLight::Kind::Rect) light["size"] = J::array({num(l.size.x), num(l.size.y)});
            if (l.kind == VirtualLight::Kind::Disk) light["size"] = J::array({num(l.size.x)});
            if (l.kind == VirtualLight::Kind::Rect || l.kind == VirtualLight::Kind::Disk) light["visible"] = l.visible;
            doc["lights"].push_back(light);
        }
    }
    // Written only when there are holdouts, as lights are.
    if (!p.holdouts.empty()) {
        doc["holdouts"] = J::array();
        for (const Holdout& h : p.holdouts)
            doc["holdouts"].push_back(J{{"name", h.name}, {"mask", h.mask}, {"depth", num(h.depth)}});
    }
    const RenderSettings& s = p.render;
    J render;
    render["photons_per_pass"] = s.photons_per_pass;
    render["passes"] = s.passes;
    render["time_budget_s"] = s.time_budget_s;
    if (s.initial_radius) render["initial_radius"] = num(*s.initial_radius);
    render["alpha"] = num(s.alpha);
    render["max_depth"] = s.max_depth;
    render["seed"] = s.seed;
    render["threads"] = s.threads;
    render["estimator"] = s.estimator == Estimator::Split ? "split" : "photons";
    render["adaptive_threshold"] = num(s.adaptive_threshold);
    render["adaptive_min_passes"] = s.adaptive_min_passes;
    render["low_discrepancy"] = s.low_discrepancy;
    render["balance_photons"] = s.balance_photons;
    doc["render"] = render;
    doc["display"] = J{{"exposure", num(p.display.exposure)}};
    if (p.display.view != DisplaySettings{}.view) doc["display"]["view"] = p.display.view;
    if (!p.display.look.empty()) doc["display"]["look"] = p.display.look;
    if (p.display.match_plate) doc["display"]["match_plate"] = true;  // off is left out, as an empty look is
    return doc;
}

}  // namespace

Project parse_project(const json& doc, const std::string& file_for_errors,
                      std::filesystem::path base_dir) {
    JsonReader r(file_for_errors);
    if (!doc.is_object()) r.wrong_type(doc, "", "a JSON object at the top level");
    // The version is checked before anything else: a newer file may use keys this build lacks.
    const json& version = r.required(doc, "", "schema_version");
    int64_t v = r.integer(version, "schema_version", std::numeric_limits<int64_t>::min(),
                          std::numeric_limits<int64_t>::max());
    r.check(v == kProjectSchemaVersion, "schema_version",
            "unsupported schema version " + std::to_string(v) + "; this build reads version " +
                std::to_string(kProjectSchemaVersion));
    r.object(
        doc, "",
        {"schema_version", "photo", "probe", "camera", "real", "objects", "lights", "holdouts", "render", "display"});

    Project p;
    p.base_dir = std::move(base_dir);
    const json& photo = r.required(doc, "", "photo");
    r.object(photo, "photo", {"path", "exposure", "colorspace", "layer"});
    p.photo.path = r.string(r.required(photo, "photo", "path"), "photo.path");
    if (auto* e = r.optional(photo, "exposure")) p.photo.exposure = r.real(*e, "photo.exposure");
    if (auto* c = r.optional(photo, "colorspace")) p.photo.colorspace = r.string(*c, "photo.colorspace");
    if (auto* l = r.optional(photo, "layer")) p.photo.layer = r.string(*l, "photo.layer");

    const json& probe = r.required(doc, "", "probe");
    r.object(probe, "probe",
             {"path", "format", "rotation_deg", "intensity", "white_balance",
              "mirror_ball_fov_deg", "max_width", "sun_scale"});
    p.probe.path = r.string(r.required(probe, "probe", "path"), "probe.path");
    if (auto* f = r.optional(probe, "format")) {
        p.probe.format =
            r.choice<ProbeSpec::Format>(*f, "probe.format", "probe format",
                                        {{"latlong", ProbeSpec::Format::LatLong},
                                         {"mirrorball", ProbeSpec::Format::MirrorBall}});
    }
    if (auto* e = r.optional(probe, "rotation_deg"))
        p.probe.rotation_deg = r.vector3(*e, "probe.rotation_deg");
    if (auto* e = r.optional(probe, "intensity")) {
        p.probe.intensity = r.real(*e, "probe.intensity");
        r.check(p.probe.intensity >= 0, "probe.intensity",
                "must be >= 0 (got " + shortest_decimal(p.probe.intensity) + ")");
    }
    if (auto* e = r.optional(probe, "white_balance"))
        p.probe.white_balance = r.positive3(*e, "probe.white_balance");
    if (auto* e = r.optional(probe, "mirror_ball_fov_deg")) {
        p.probe.mirror_ball_fov_deg = r.real(*e, "probe.mirror_ball_fov_deg");
        r.check(p.probe.mirror_ball_fov_deg >= 0 && p.probe.mirror_ball_fov_deg < 180,
                "probe.mirror_ball_fov_deg",
                "must be in [0, 180) degrees, 0 for an orthographic view (got " +
                    shortest_decimal(p.probe.mirror_ball_fov_deg) + ")");
    }
    if (auto* e = r.optional(probe, "max_width"))
        p.probe.max_width = int(r.integer(*e, "probe.max_width", kMinProbeMaxWidth, kMaxProbeMaxWidth));
    if (auto* e = r.optional(probe, "sun_scale")) {
        p.probe.sun_scale = r.real(*e, "probe.sun_scale");
        r.check(p.probe.sun_scale > 0 && p.probe.sun_scale <= kMaxSunScale, "probe.sun_scale",
                "must be in (0, " + shortest_decimal(kMaxSunScale) + "] (got " + shortest_decimal(p.probe.sun_scale) + ")");
    }

    p.camera = parse_camera(r, r.required(doc, "", "camera"));

    auto each = [&](const char* key, auto parse) {
        const json* arr = r.optional(doc, key);
        if (!arr) return;
        if (!arr->is_array()) r.wrong_type(*arr, key, "an array");
        for (size_t i = 0; i < arr->size(); ++i) parse((*arr)[i], json_at(key, i));
    };
    each("real",
         [&](const json& j, const std::string& path) { p.real.push_back(parse_real(r, j, path)); });
    each("objects", [&](const json& j, const std::string& path) {
        p.objects.push_back(parse_object(r, j, path));
    });
    each("lights", [&](const json& j, const std::string& path) { p.lights.push_back(parse_light(r, j, path)); });
    each("holdouts",
         [&](const json& j, const std::string& path) { p.holdouts.push_back(parse_holdout(r, j, path)); });
    if (auto* s = r.optional(doc, "render")) p.render = parse_render(r, *s);
    if (auto* d = r.optional(doc, "display")) {
        r.object(*d, "display", {"exposure", "view", "look", "match_plate"});
        if (auto* e = r.optional(*d, "exposure"))
            p.display.exposure = r.real(*e, "display.exposure");
        if (auto* v = r.optional(*d, "view")) p.display.view = r.string(*v, "display.view");
        if (auto* l = r.optional(*d, "look")) p.display.look = r.string(*l, "display.look");
        if (auto* m = r.optional(*d, "match_plate")) p.display.match_plate = r.boolean(*m, "display.match_plate");
    }
    return p;
}

json to_json(const Project& project) {
    return write_project<json>(project);
}

Project load_project(const std::string& path) {
    JsonReader r(path);
    const json doc = r.parse(r.read_file("project file"));
    std::error_code ec;
    std::filesystem::path base = std::filesystem::absolute(path, ec).parent_path();
    if (ec) base = std::filesystem::path(path).parent_path();
    return parse_project(doc, path, base.lexically_normal());
}

namespace {

/// Runs the loader's checks (load_project's: the JSON reader, then parse_project) on the text
/// about to be saved, so that a value the loader refuses (a size beyond its range, a camera it
/// cannot build) is refused here, naming the field, and the old file is kept.
void check_loads(const std::string& text, const std::string& path, const std::filesystem::path& base_dir) {
    try {
        JsonReader r(path);
        parse_project(r.parse(text), path, base_dir);
    } catch (const InputError& e) {
        std::string what = e.what();
        const std::string prefix = InputError(e.file(), e.field(), "").what();
        if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
        throw InputError(path, e.field(), what + "; the project would not load again, so it was not saved");
    }
}

}  // namespace

void save_project(const Project& project, const std::string& path) {
    // ordered_json keeps the natural reading order (schema_version, photo, probe, ...).
    const nlohmann::ordered_json doc = write_project<nlohmann::ordered_json>(project);
    // JSON has no NaN or infinity (they would be written as null and the file would no longer
    // load): refuse, naming the field, and keep the old file.
    std::function<void(const nlohmann::ordered_json&, const std::string&)> check_finite =
        [&](const nlohmann::ordered_json& j, const std::string& at) {
            if (j.is_number_float() && !std::isfinite(j.get<double>()))
                throw InputError(path, at, "is not a finite number; the project was not saved");
            if (j.is_object())
                for (const auto& [key, value] : j.items()) check_finite(value, json_join(at, key));
            if (j.is_array())
                for (size_t i = 0; i < j.size(); ++i) check_finite(j[i], at + "[" + std::to_string(i) + "]");
        };
    check_finite(doc, "");
    std::string text = doc.dump(2) + "\n";
    check_loads(text, path, project.base_dir);
    try {
        write_file_atomically(path, text);  // the old file stays whole if this fails
    } catch (const std::runtime_error& e) {
        throw InputError(path, "", e.what());
    }
}

}  // namespace dp
