// `diffphoton calibrate proxy|albedo|probe`: real proxies, albedo textures and the light probe's
// field of view, rotation and exposure, from the photograph. Each reads a project, updates it,
// writes it back (or to --output) and prints what it did with an error figure where one exists.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "assets/asset_library.h"
#include "base/error.h"
#include "commands.h"
#include "common.h"
#include "image/image_io.h"
#include "probe/probe.h"
#include "reconstruction/albedo.h"
#include "reconstruction/probe_align.h"
#include "reconstruction/proxies.h"
#include "scene/project_io.h"

namespace dp::cli {

namespace fs = std::filesystem;

namespace {

constexpr float kDegPerRad = 180.0f / kPi;

/// Rethrows an error of the reconstruction calls, which name no file, labelled with the project
/// whose camera, photo and probe the given points and figures refer to.
[[noreturn]] void rethrow_for(const InputError& e, const std::string& project) {
    std::string what = e.what();
    const std::string prefix = e.field().empty() ? "" : "field '" + e.field() + "': ";
    if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
    throw InputError(project, e.field(), what);
}

/// Image points from a flat list of numbers "x1 y1 x2 y2 ...".
std::vector<vec2> pairs(const std::vector<float>& xy) {
    std::vector<vec2> out;
    for (size_t i = 0; i + 1 < xy.size(); i += 2) out.emplace_back(xy[i], xy[i + 1]);
    return out;
}

/// The photo's size and the camera that took it (the photo file is read for its size).
Camera project_camera(const Project& p) {
    AssetLibrary assets;
    int w = 0, h = 0;
    assets.photo_size(p, w, h);
    return p.camera.build(w, h);
}

/// Where a photo value clips, in the photo's units after the project's exposure: `given` (file
/// units) when set, 0.99 for an 8-bit photo (sRGB 254 and 255), none for EXR/HDR.
float clip_level(const Project& p, const std::optional<float>& given) {
    if (given) return *given * std::exp2(p.photo.exposure);
    AssetLibrary assets;
    return assets.photo_clip_level(p);
}

void write_back(const Project& p, const std::string& input, const std::string& output) {
    const std::string path = output.empty() ? input : output;
    save_project(p, path);
    std::printf("wrote %s\n", path.c_str());
}

// ---- proxy ---------------------------------------------------------------------------------

struct ProxyOptions {
    std::string project, output, kind, name;
    std::vector<float> points;
    float height = 0, thickness = 0.2f, max_distance = 0;
};

void run_proxy(const ProxyOptions& o) {
    Project p = load_project(o.project);
    Camera camera = project_camera(p);
    const std::string name = o.name.empty() ? o.kind : o.name;
    const std::vector<vec2> pts = pairs(o.points);
    ProxyFit fit;
    try {
        if (o.kind == "ground") {
            if (!o.points.empty()) throw InputError("", "--points", "the ground takes no points");
            fit = ground_proxy(camera, o.max_distance, name);
        } else if (o.kind == "wall") {
            if (o.points.size() != 4)
                throw InputError("", "--points", "a wall takes two image points (x1 y1 x2 y2), got " +
                                                     std::to_string(o.points.size()) + " numbers");
            fit = wall_proxy(camera, pts[0], pts[1], o.height, o.thickness, name);
        } else {
            if (o.points.size() != 6 && o.points.size() != 8)
                throw InputError("", "--points", "a box takes 3 or 4 image points (x y each), got " +
                                                     std::to_string(o.points.size()) + " numbers");
            fit = box_proxy(camera, pts, o.height, name);
        }
    } catch (const InputError& e) {
        rethrow_for(e, o.project);
    }
    auto same = std::find_if(p.real.begin(), p.real.end(), [&](const RealProxy& r) { return r.name == name; });
    const bool replaced = same != p.real.end();
    if (replaced) {
        fit.proxy.albedo = same->albedo;  // keep what was estimated or set for it
        *same = fit.proxy;
    } else {
        p.real.push_back(fit.proxy);
    }
    const Shape& s = fit.proxy.shape;
    const Transform& t = fit.proxy.transform;
    if (s.kind == Shape::Kind::Plane)
        std::printf("%s real proxy '%s': plane %.4g x %.4g", replaced ? "replaced" : "added", name.c_str(), s.size.x,
                    s.size.z);
    else
        std::printf("%s real proxy '%s': box %.4g x %.4g x %.4g", replaced ? "replaced" : "added", name.c_str(),
                    s.size.x, s.size.y, s.size.z);
    std::printf(" at %s, turned %.3g deg about +Y\n", vec(t.translation).c_str(), t.rotation_deg.y);
    std::printf("footprint:");
    for (const vec3& c : fit.footprint) std::printf(" (%.4g, %.4g)", c.x, c.z);
    std::printf("\nrms_error_px %.3g\n", fit.rms_error_px);
    write_back(p, o.project, o.output);
}

// ---- albedo --------------------------------------------------------------------------------

struct AlbedoOptions {
    std::string project, output;
    std::vector<std::string> proxies;
    int resolution = 256, subsamples = 3, samples = 512, bounce = 64, threads = 0;
    std::optional<float> clip;
    uint64_t seed = 1;
};

void run_albedo(const AlbedoOptions& o) {
    with_threads(o.threads, [&] {
        LoadedScene loaded = load_scene(o.project);
        auto scene = loaded.scene;
        Project p = loaded.project;
        // Which proxies: the named ones, else every one that has a texture layout.
        std::vector<size_t> chosen;
        for (const std::string& want : o.proxies) {
            auto it = std::find_if(p.real.begin(), p.real.end(), [&](const RealProxy& r) { return r.name == want; });
            if (it == p.real.end()) throw InputError(o.project, "--proxy", "no real proxy named '" + want + "'");
            chosen.push_back(size_t(it - p.real.begin()));
        }
        if (o.proxies.empty())
            for (size_t i = 0; i < p.real.size(); ++i)
                if (p.real[i].shape.kind != Shape::Kind::Sphere) chosen.push_back(i);
        if (chosen.empty()) throw InputError(o.project, "real", "the project has no plane, box or mesh proxy");

        AlbedoTextureOptions ao;
        ao.max_resolution = o.resolution;
        ao.subsamples = o.subsamples;
        ao.probe_samples = o.samples;
        ao.bounce_samples = o.bounce;
        ao.clip_level = clip_level(p, o.clip);
        ao.seed = o.seed;
        for (size_t i : chosen) {
            AlbedoTexture t;
            try {
                t = estimate_albedo_texture(*scene, int(i), ao);
            } catch (const InputError& e) {
                rethrow_for(e, o.project);
            }
            const std::string texture = attach_albedo_texture(p, int(i), t, o.output.empty() ? o.project : o.output, true);
            const std::string mask = fs::path(texture).stem().string() + "_mask.exr";
            const double n = double(t.albedo.size()) / 100.0;
            std::printf("real[%zu] '%s': %dx%d texels, estimated %.1f%% (clipped %.1f%%, unseen %.1f%%, unlit %.1f%%)\n",
                        i, p.real[i].name.c_str(), t.albedo.width(), t.albedo.height(), t.valid / n, t.clipped / n,
                        t.unseen / n, t.unlit / n);
            std::printf("  mean_albedo %s  irradiance_rel_error %.3g  bounce_fraction %.3g\n",
                        vec(t.mean_albedo).c_str(), t.irradiance_rel_error, t.bounce_fraction);
            std::printf("  texture %s  mask %s\n", texture.c_str(), mask.c_str());
        }
        write_back(p, o.project, o.output);
        return 0;
    });
}

// ---- probe ---------------------------------------------------------------------------------

struct ProbeOptions {
    std::string project, output;
    std::optional<float> fov, intensity, clip;
    std::vector<float> shadow, card;
    float object_height = 0, reflectance = 0.18f;
    bool object_base = false;
    int samples = 256;
};

void run_probe(const ProbeOptions& o) {
    if (!o.fov && !o.intensity && o.shadow.empty() && o.card.empty())
        throw InputError(o.project, "",
                         "nothing to do: give --fov, --shadow (with --object-height), --grey-card (with "
                         "--reflectance) or --intensity");
    Project p = load_project(o.project);
    if (o.fov) {
        if (!(*o.fov >= 0 && *o.fov < 180))
            throw InputError(o.project, "--fov", "the ball camera's field of view must be in [0, 180) degrees");
        if (p.probe.format != ProbeSpec::Format::MirrorBall)
            throw InputError(o.project, "--fov", "the probe is not a mirror ball (probe.format is \"latlong\")");
        std::printf("probe mirror_ball_fov_deg %g -> %g\n", p.probe.mirror_ball_fov_deg, *o.fov);
        p.probe.mirror_ball_fov_deg = *o.fov;
    }
    if (!o.shadow.empty()) {
        if (!(o.object_height > 0))
            throw InputError(o.project, "--object-height", "the shadow cue needs the object point's height (> 0)");
        SceneAssets assets = load_assets(p);
        for (const std::string& w : assets.warnings) warn(w);
        Camera camera = p.camera.build(assets.photo.width(), assets.photo.height());
        ShadowCue cue;
        cue.object_px = vec2(o.shadow[0], o.shadow[1]);
        cue.shadow_px = vec2(o.shadow[2], o.shadow[3]);
        cue.height = o.object_height;
        cue.object_is_base = o.object_base;
        vec3 sun, bright;
        try {
            sun = sun_direction_from_shadow(camera, cue);
            bright = brightest_direction(assets.probe_latlong);
        } catch (const InputError& e) {
            rethrow_for(e, o.project);
        }
        ProbeYaw yaw = align_probe_yaw(bright, p.probe.rotation_deg, sun);
        std::printf("sun from the shadow: azimuth %.2f deg, elevation %.2f deg\n",
                    std::atan2(sun.x, -sun.z) * kDegPerRad, std::asin(sun.y) * kDegPerRad);
        std::printf("probe rotation_deg %s -> %s (turned %.2f deg about +Y)\n", vec(p.probe.rotation_deg).c_str(),
                    vec(yaw.rotation_deg).c_str(), yaw.yaw_deg);
        std::printf("elevation_mismatch_deg %.3g\n", yaw.elevation_mismatch_deg);
        p.probe.rotation_deg = yaw.rotation_deg;
    }
    if (o.intensity) {
        std::printf("probe intensity %g -> %g (set by hand)\n", p.probe.intensity, *o.intensity);
        p.probe.intensity = *o.intensity;
    } else if (!o.card.empty()) {
        if (!(o.reflectance > 0 && o.reflectance <= 1))
            throw InputError(o.project, "--reflectance", "the card's reflectance must be in (0, 1]");
        SceneAssets assets = load_assets(p);
        for (const std::string& w : assets.warnings) warn(w);
        RenderScene scene(p, std::move(assets));
        GreyCard card;
        card.x0 = int(std::lround(o.card[0]));
        card.y0 = int(std::lround(o.card[1]));
        card.x1 = int(std::lround(o.card[2]));
        card.y1 = int(std::lround(o.card[3]));
        card.reflectance = o.reflectance;
        ExposureMatch m;
        try {
            m = match_exposure_grey_card(scene, card, clip_level(p, o.clip), o.samples);
        } catch (const InputError& e) {
            rethrow_for(e, o.project);
        }
        std::printf("probe intensity %g -> %g (x%.4g from %d card pixels)\n", p.probe.intensity, m.intensity,
                    m.scale, m.pixels);
        std::printf("card_spread %.3g\n", m.spread);
        p.probe.intensity = m.intensity;
    }
    write_back(p, o.project, o.output);
}

}  // namespace

void add_calibrate_scene_commands(CLI::App& calibrate) {
    {
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
        sub->add_option("--thickness", o->thickness, "Wall thickness behind the clicked line (default 0.2)")
            ->check(kFinite);
        sub->add_option("--max-distance", o->max_distance,
                        "Ground: how far from the camera it reaches (0: 20 camera heights)")
            ->check(kFinite);
        sub->add_option("--name", o->name, "Proxy name (default: the kind); an existing one is replaced");
        sub->add_option("-o,--output", o->output, "Write the project here instead of updating it");
        sub->callback([o] { run_proxy(*o); });
    }
    {
        auto o = std::make_shared<AlbedoOptions>();
        CLI::App* sub = calibrate.add_subcommand(
            "albedo", "Estimate albedo textures of real proxies from the photo and the probe");
        sub->add_option("project", o->project, "Project file (JSON)")->required();
        sub->add_option("--proxy", o->proxies, "Proxy name (repeatable; default: every plane, box and mesh)");
        sub->add_option("--resolution", o->resolution, "Texture size along the longer side (default 256)")
            ->check(CLI::Range(1, 8192));
        sub->add_option("--subsamples", o->subsamples, "Points per texel side (default 3)")->check(CLI::Range(1, 16));
        sub->add_option("--samples", o->samples, "Probe samples per texel (default 512)")
            ->check(CLI::PositiveNumber);
        sub->add_option("--bounce-samples", o->bounce, "Rays per texel for light from other real surfaces (0: off)")
            ->check(CLI::NonNegativeNumber);
        sub->add_option("--clip", o->clip,
                        "Photo value (file units) at which a pixel is clipped (default: 0.99 for 8-bit "
                        "photos, none for EXR/HDR)")
            ->check(kFinite);
        sub->add_option("--seed", o->seed, "Random seed");
        sub->add_option("--threads", o->threads, "Worker threads (0: all cores)")->check(CLI::NonNegativeNumber);
        sub->add_option("-o,--output", o->output,
                        "Write the project here instead of updating it (the textures go beside it)");
        sub->callback([o] { run_albedo(*o); });
    }
    {
        auto o = std::make_shared<ProbeOptions>();
        CLI::App* sub = calibrate.add_subcommand(
            "probe", "Set the mirror ball's field of view, align the probe's rotation to a shadow, match its exposure");
        sub->add_option("project", o->project, "Project file (JSON)")->required();
        sub->add_option("--fov", o->fov, "Vertical field of view (deg) of the camera that shot the mirror ball")
            ->check(kFinite);
        sub->add_option("--shadow", o->shadow,
                        "Shadow cue: object point x y and its shadow's tip x y (pixels); turns the probe "
                        "about +Y to put its brightest region on the sun")
            ->expected(4)
            ->check(kFinite);
        sub->add_option("--object-height", o->object_height, "Height of the clicked object point above the ground")
            ->check(kFinite);
        sub->add_flag("--object-base", o->object_base,
                      "The clicked object point is its base on the ground; the point casting the shadow is "
                      "--object-height above it");
        sub->add_option("--grey-card", o->card, "Grey card rectangle x0 y0 x1 y1 (pixels, inclusive) on a real proxy")
            ->expected(4)
            ->check(kFinite);
        sub->add_option("--reflectance", o->reflectance, "The card's reflectance (default 0.18)")->check(kFinite);
        auto* intensity = sub->add_option("--intensity", o->intensity, "Set the probe intensity by hand")
                              ->check(CLI::NonNegativeNumber);
        intensity->excludes(sub->get_option("--grey-card"));
        sub->add_option("--clip", o->clip, "Photo value (file units) at which a card pixel is clipped")
            ->check(kFinite);
        sub->add_option("--samples", o->samples, "Probe samples per card pixel (default 256)")
            ->check(CLI::PositiveNumber);
        sub->add_option("-o,--output", o->output, "Write the project here instead of updating it");
        sub->callback([o] { run_probe(*o); });
    }
}

}  // namespace dp::cli
