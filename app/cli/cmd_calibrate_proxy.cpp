// `diffphoton calibrate proxy`: a real proxy (the ground, a wall or a box) from image points.
// Reads a project, adds or replaces the proxy, writes the project back (or to --output) and
// prints the fit with its reprojection error.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "base/error.h"
#include "calibrate_scene_common.h"
#include "commands.h"
#include "common.h"
#include "reconstruction/proxies.h"
#include "scene/project_io.h"

namespace dp::cli {

namespace {

struct ProxyOptions {
    std::string project, output, kind, name;
    std::vector<float> points;
    float height = 0, thickness = 0.2f, max_distance = 0;
    bool force = false;
};

/// Image points from a flat list of numbers "x1 y1 x2 y2 ...".
std::vector<vec2> pairs(const std::vector<float>& xy) {
    std::vector<vec2> out;
    for (size_t i = 0; i + 1 < xy.size(); i += 2) out.emplace_back(xy[i], xy[i + 1]);
    return out;
}

/// The fit for `o.kind`, after checking that the points given suit it.
ProxyFit fit_proxy(const ProxyOptions& o, const Camera& camera, const std::string& name) {
    const std::vector<vec2> pts = pairs(o.points);
    if (o.kind == "ground") {
        if (!o.points.empty()) throw InputError("", "--points", "the ground takes no points");
        return ground_proxy(camera, o.max_distance, name);
    }
    if (o.kind == "wall") {
        if (o.points.size() != 4)
            throw InputError("", "--points",
                             "a wall takes two image points (x1 y1 x2 y2), got " +
                                 std::to_string(o.points.size()) + " numbers");
        return wall_proxy(camera, pts[0], pts[1], o.height, o.thickness, name);
    }
    if (o.points.size() != 6 && o.points.size() != 8)
        throw InputError("", "--points",
                         "a box takes 3 or 4 image points (x y each), got " +
                             std::to_string(o.points.size()) + " numbers");
    return box_proxy(camera, pts, o.height, name);
}

void print_fit(const ProxyFit& fit, bool replaced) {
    const Shape& s = fit.proxy.shape;
    const Transform& t = fit.proxy.transform;
    const char* verb = replaced ? "replaced" : "added";
    const char* name = fit.proxy.name.c_str();
    if (s.kind == Shape::Kind::Plane)
        std::printf("%s real proxy '%s': plane %.4g x %.4g", verb, name, s.size.x, s.size.z);
    else
        std::printf("%s real proxy '%s': box %.4g x %.4g x %.4g", verb, name, s.size.x, s.size.y,
                    s.size.z);
    std::printf(" at %s, turned %.3g deg about +Y\n", vec(t.translation).c_str(), t.rotation_deg.y);
    std::printf("footprint:");
    for (const vec3& c : fit.footprint) std::printf(" (%.4g, %.4g)", c.x, c.z);
    std::printf("\nrms_error_px %.3g\n", fit.rms_error_px);
}

void run_proxy(const ProxyOptions& o) {
    Project p = load_project(o.project);
    check_scene_outputs(p, o.project, o.output, {}, o.force);
    const Camera camera = project_camera(p);
    const std::string name = o.name.empty() ? o.kind : o.name;
    ProxyFit fit;
    try {
        fit = fit_proxy(o, camera, name);
    } catch (const InputError& e) {
        rethrow_for(e, o.project);
    }
    const bool replaced = add_or_replace_real_proxy(p, fit.proxy);
    print_fit(fit, replaced);
    write_back(p, o.project, o.output);
}

}  // namespace

Command add_calibrate_proxy_command(CLI::App& calibrate) {
    auto o = std::make_shared<ProxyOptions>();
    CLI::App* sub = calibrate.add_subcommand(
        "proxy", "Add a real proxy from image points: the ground plane, a wall or a box");
    sub->add_option("project", o->project, "Project file (JSON)")->required();
    sub->add_option("kind", o->kind, "ground, wall or box")
        ->required()
        ->check(CLI::IsMember({"ground", "wall", "box"}));
    sub->add_option("--points", o->points,
                    "Image points x y ... (pixels): a wall's two base ends, or a box's 3-4 "
                    "footprint corners in order around it")
        ->check(kFinite);
    sub->add_option("--height", o->height, "Wall or box height (world units)")->check(kFinite);
    sub->add_option("--thickness", o->thickness,
                    "Wall thickness behind the clicked line (default 0.2)")
        ->check(kFinite);
    sub->add_option("--max-distance", o->max_distance,
                    "Ground: how far from the camera it reaches (0: 20 camera heights)")
        ->check(kFinite);
    sub->add_option("--name", o->name,
                    "Proxy name (default: the kind); an existing one is replaced");
    sub->add_option("-o,--output", o->output, "Write the project here instead of updating it");
    add_force_flag(sub, o->force);
    return {sub, [o] {
                run_proxy(*o);
                return 0;
            }};
}

}  // namespace dp::cli
