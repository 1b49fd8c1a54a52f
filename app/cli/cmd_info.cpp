// `diffphoton info`: loads and validates a project and prints what it holds.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "render/render_limits.h"
#include "scene/project_io.h"
#include "commands.h"
#include "common.h"

namespace dp::cli {

namespace {

std::string size_text(const Image& img) {
    return std::to_string(img.width()) + "x" + std::to_string(img.height());
}

std::string shape_text(const Shape& s, const TriangleMesh* mesh) {
    char buf[128];
    switch (s.kind) {
        case Shape::Kind::Plane:
            std::snprintf(buf, sizeof(buf), "plane %g x %g", s.size.x, s.size.z);
            return buf;
        case Shape::Kind::Box:
            std::snprintf(buf, sizeof(buf), "box %g x %g x %g", s.size.x, s.size.y, s.size.z);
            return buf;
        case Shape::Kind::Sphere:
            std::snprintf(buf, sizeof(buf), "sphere radius %g", s.radius);
            return buf;
        case Shape::Kind::Mesh: {
            std::string t = "mesh '" + s.mesh_path + "'";
            if (mesh) t += " (" + std::to_string(mesh->triangle_count()) + " triangles)";
            if (s.up_axis && *s.up_axis != UpAxis::Y) t += std::string(", up axis ") + up_axis_name(*s.up_axis);
            if (s.unit_scale != 1.0f) {
                std::snprintf(buf, sizeof(buf), ", unit_scale %g", double(s.unit_scale));
                t += buf;
            }
            return t;
        }
    }
    return "?";
}

std::string transform_text(const Transform& t) {
    if (t == Transform{}) return "";
    return "  at " + vec(t.translation) + " rotated " + vec(t.rotation_deg) + " scaled " +
           vec(t.scale);
}

std::string albedo_text(const Albedo& a, const Image& texture, const vec3& estimated) {
    switch (a.kind) {
        case Albedo::Kind::Constant: return vec(a.rgb);
        case Albedo::Kind::Texture:
            return "texture '" + a.texture_path + "' (" + size_text(texture) + ")";
        case Albedo::Kind::Estimate: return "estimated from the photo: " + vec(estimated);
    }
    return "?";
}

std::string material_text(const Material& m, const Image& texture) {
    char buf[160];
    switch (m.kind) {
        case Material::Kind::Diffuse:
            return "diffuse, albedo " + albedo_text(m.albedo, texture, m.albedo.rgb);
        case Material::Kind::Mirror: return "mirror, reflectance " + vec(m.reflectance);
        case Material::Kind::Glass:
            std::snprintf(buf, sizeof(buf), "glass, ior %g, tint ", m.ior);
            return buf + vec(m.tint);
        case Material::Kind::Principled: {
            const PrincipledMaterial& p = m.principled;
            std::snprintf(buf, sizeof(buf), ", metallic %g, roughness %g, ior %g, specular %g, transmission %g",
                          p.metallic, p.roughness, p.ior, p.specular, p.transmission);
            return "principled, base colour " + albedo_text(m.albedo, texture, m.albedo.rgb) + buf;
        }
    }
    return "?";
}

std::string object_label(const std::string& name, const char* list, size_t i) {
    return name.empty() ? std::string(list) + "[" + std::to_string(i) + "]" : "'" + name + "'";
}

/// A light's kind with its shape: "point", "spot 50 deg, blend 0.2", "rect 0.5 x 0.3",
/// "disk diameter 0.4" (the extents before the transform's scale).
std::string light_shape_text(const VirtualLight& l) {
    char buf[96];
    switch (l.kind) {
        case VirtualLight::Kind::Point: return "point";
        case VirtualLight::Kind::Spot:
            std::snprintf(buf, sizeof(buf), "spot %g deg, blend %g", l.spot_angle_deg, l.spot_blend);
            return buf;
        case VirtualLight::Kind::Rect: std::snprintf(buf, sizeof(buf), "rect %g x %g", l.size.x, l.size.y); return buf;
        case VirtualLight::Kind::Disk: std::snprintf(buf, sizeof(buf), "disk diameter %g", l.size.x); return buf;
    }
    return "?";
}

/// A unit direction with float rounding's crumbs (1e-8 after a 90 degree turn) set to 0.
vec3 clean_direction(vec3 d) {
    for (int k = 0; k < 3; ++k)
        if (std::abs(d[k]) < 1e-6f) d[k] = 0;
    return d;
}

/// One line per light: what the project says, then what the renderers make of it (where it
/// shines, its intensity or its face's radiance and area).
void print_lights(const Project& p, const LightSet& lights) {
    std::printf("virtual lights: %zu\n", p.lights.size());
    for (size_t i = 0; i < p.lights.size(); ++i) {
        const VirtualLight& l = p.lights[i];
        const PlacedLight& pl = lights.lights()[i];
        char power[64];
        std::snprintf(power, sizeof(power), "%g W", l.power_w);
        std::string emits;
        if (pl.is_area()) {
            char buf[96];
            std::snprintf(buf, sizeof(buf), ", area %g m^2, radiance ", pl.area);
            emits = buf + vec(pl.radiance) + " W/(m^2 sr)" + (l.visible ? "" : ", hidden from the camera");
        } else {
            emits = ", intensity " + vec(pl.intensity) + " W/sr";
        }
        std::printf("  %s: %s, %s, colour %s, shining along %s%s%s\n",
                    object_label(l.name, "lights", i).c_str(), light_shape_text(l).c_str(), power,
                    vec(l.colour).c_str(), vec(clean_direction(pl.axis)).c_str(), emits.c_str(),
                    transform_text(l.transform).c_str());
    }
}

void print_camera(const Project& p, const Camera& cam) {
    const CameraSpec& c = p.camera;
    if (c.model == CameraSpec::Model::LookAt) {
        std::printf("camera: lookat, eye %s, target %s, up %s, vfov %g deg\n", vec(c.eye).c_str(),
                    vec(c.target).c_str(), vec(c.up).c_str(), c.vfov_deg);
    } else {
        const Distortion& d = c.distortion;
        std::printf("camera: opencv, translation %s, distortion [%g, %g, %g, %g, %g]\n",
                    vec(c.translation).c_str(), d.k1, d.k2, d.p1, d.p2, d.k3);
    }
    std::printf("  fx %g  fy %g  cx %g  cy %g  position %s  forward %s\n", cam.fx(), cam.fy(),
                cam.cx(), cam.cy(), vec(cam.position()).c_str(), vec(cam.forward()).c_str());
}

void print_render_settings(const RenderSettings& r) {
    std::printf("render: photons_per_pass %lld, passes %d, time_budget_s %g, initial_radius %s,\n"
                "  alpha %g, max_depth %d, seed %llu, threads %d\n",
                static_cast<long long>(r.photons_per_pass), r.passes, r.time_budget_s,
                r.initial_radius ? std::to_string(*r.initial_radius).c_str() : "auto", r.alpha,
                r.max_depth, static_cast<unsigned long long>(r.seed), r.threads);
}

nlohmann::json xyz(const vec3& v) { return {v.x, v.y, v.z}; }

/// The lights for `info --json`: the project's numbers and the placed light's.
nlohmann::json lights_json(const Project& p, const LightSet& lights) {
    nlohmann::json out = nlohmann::json::array();
    for (size_t i = 0; i < p.lights.size(); ++i) {
        const VirtualLight& l = p.lights[i];
        const PlacedLight& pl = lights.lights()[i];
        nlohmann::json j = {{"name", l.name},
                            {"type", light_kind_name(l.kind)},
                            {"power_w", l.power_w},
                            {"position", xyz(pl.position)},
                            {"direction", xyz(pl.axis)}};
        if (pl.is_area()) {
            j["area"] = pl.area;
            j["radiance"] = xyz(pl.radiance);
            j["visible"] = l.visible;
        } else {
            j["intensity"] = xyz(pl.intensity);
        }
        out.push_back(j);
    }
    return out;
}

/// What `info` prints, for scripts: the project as written (`project`, paths as stored) and what
/// loading it found (sizes, resolved paths, the camera's intrinsics, triangles, warnings).
nlohmann::json info_json(const std::string& project_path, const Project& p, const RenderScene& scene) {
    const SceneAssets& a = scene.assets();
    const Camera& cam = scene.camera();
    nlohmann::json real = nlohmann::json::array(), objects = nlohmann::json::array();
    for (size_t i = 0; i < p.real.size(); ++i)
        real.push_back({{"name", p.real[i].name},
                        {"triangles", i < a.real_meshes.size() ? a.real_meshes[i].triangle_count() : 0},
                        {"albedo", xyz(scene.real_surfaces()[i].albedo)}});
    for (size_t i = 0; i < p.objects.size(); ++i)
        objects.push_back({{"name", p.objects[i].name},
                           {"visible", p.objects[i].visible},
                           {"triangles", i < a.object_meshes.size() ? a.object_meshes[i].triangle_count() : 0}});
    nlohmann::json clusters = nlohmann::json::array();
    const nlohmann::json lights = lights_json(p, scene.lights());
    for (const EmissionCluster& c : scene.clusters())
        clusters.push_back({{"center", xyz(c.center)}, {"radius", c.radius}, {"objects", c.objects}});
    return {{"file", project_path},
            {"project", to_json(p)},
            {"photo", {{"resolved", p.resolve(p.photo.path).string()},
                       {"width", scene.photo().width()},
                       {"height", scene.photo().height()}}},
            {"probe", {{"resolved", p.resolve(p.probe.path).string()},
                       {"width", scene.probe().image().width()},
                       {"height", scene.probe().image().height()}}},
            {"camera", {{"fx", cam.fx()}, {"fy", cam.fy()}, {"cx", cam.cx()}, {"cy", cam.cy()},
                        {"position", xyz(cam.position())}, {"forward", xyz(cam.forward())}}},
            {"real", real},
            {"objects", objects},
            {"lights", lights},
            {"scene_scale", scene.scale()},
            {"emission_clusters", clusters},
            {"warnings", a.warnings},
            {"non_finite_replaced", a.non_finite_replaced}};
}

int run_info(const std::string& project_path, bool json) {
    LoadedScene loaded = load_scene(project_path);
    check_render_limits(*loaded.scene, loaded.settings);  // what render would refuse, info refuses too
    auto scene = loaded.scene;
    const Project& p = loaded.project;
    const SceneAssets& a = scene->assets();
    if (json) {
        std::printf("%s\n", info_json(project_path, p, *scene).dump(1).c_str());
        return 0;
    }
    std::printf("project: %s\n", project_path.c_str());
    std::printf("photo: '%s' -> %s, %s, exposure %g stops\n", p.photo.path.c_str(),
                p.resolve(p.photo.path).c_str(), size_text(scene->photo()).c_str(),
                p.photo.exposure);
    const bool ball = p.probe.format == ProbeSpec::Format::MirrorBall;
    const std::string balance = p.probe.white_balance == vec3(1.0f)
                                    ? ""
                                    : ", white balance " + vec(p.probe.white_balance);
    std::printf("probe: '%s' -> %s, %s%s, rotation %s deg, intensity %g%s\n",
                p.probe.path.c_str(), p.resolve(p.probe.path).c_str(),
                ball ? "mirrorball unwrapped to lat-long " : "latlong ",
                size_text(scene->probe().image()).c_str(), vec(p.probe.rotation_deg).c_str(),
                p.probe.intensity, balance.c_str());
    print_camera(p, scene->camera());

    std::printf("real proxies: %zu\n", p.real.size());
    for (size_t i = 0; i < p.real.size(); ++i) {
        const RealProxy& r = p.real[i];
        const Surface& s = scene->real_surfaces()[i];
        std::printf("  %s: %s, albedo %s%s\n", object_label(r.name, "real", i).c_str(),
                    shape_text(r.shape, i < a.real_meshes.size() ? &a.real_meshes[i] : nullptr)
                        .c_str(),
                    albedo_text(r.albedo, a.real_textures[i], s.albedo).c_str(),
                    transform_text(r.transform).c_str());
    }
    std::printf("virtual objects: %zu\n", p.objects.size());
    for (size_t i = 0; i < p.objects.size(); ++i) {
        const VirtualObject& o = p.objects[i];
        const std::vector<FileMaterialAsset>* file =
            i < a.object_file_materials.size() && !a.object_file_materials[i].empty()
                ? &a.object_file_materials[i]
                : nullptr;
        std::printf(
            "  %s: %s, %s%s%s%s\n", object_label(o.name, "objects", i).c_str(),
            shape_text(o.shape, i < a.object_meshes.size() ? &a.object_meshes[i] : nullptr).c_str(),
            file ? "materials from the file, elsewhere " : "",
            material_text(o.material, a.object_textures[i]).c_str(), o.visible ? "" : " (hidden)",
            transform_text(o.transform).c_str());
        if (file)
            for (const FileMaterialAsset& f : *file)
                std::printf("    file material '%s': %s\n", f.name.c_str(),
                            material_text(f.material, f.texture).c_str());
    }
    print_lights(p, scene->lights());
    print_render_settings(p.render);
    std::printf("scene scale %g\n", scene->scale());
    std::printf("emission clusters: %zu\n", scene->clusters().size());
    for (const EmissionCluster& c : scene->clusters()) {
        std::string names;
        for (int i : c.objects)
            names += (names.empty() ? "" : ", ") +
                     object_label(p.objects[size_t(i)].name, "objects", size_t(i));
        std::printf("  centre %s radius %g: %s\n", vec(c.center).c_str(), c.radius, names.c_str());
    }
    std::printf("warnings: %zu\n", a.warnings.size());
    for (const std::string& w : a.warnings) std::printf("  %s\n", w.c_str());
    if (a.non_finite_replaced > 0)
        std::printf("  (%zu NaN/Inf pixel values replaced by 0 in total)\n", a.non_finite_replaced);
    return 0;
}

}  // namespace

Command add_info_command(CLI::App& app) {
    auto project = std::make_shared<std::string>();
    auto json = std::make_shared<bool>(false);
    CLI::App* sub = app.add_subcommand("info", "Validate a project and print what it holds");
    sub->add_option("project", *project, "Project file (JSON)")->required();
    sub->add_flag("--json", *json, "Print it as one JSON object (for scripts)");
    return {sub, [project, json] { return run_info(*project, *json); }};
}

}  // namespace dp::cli
