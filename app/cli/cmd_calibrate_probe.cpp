// `diffphoton calibrate probe`: the light probe's mirror-ball field of view, its rotation from a
// shadow cue and its exposure (and white balance) from a grey card. Reads a project, updates the
// probe, writes the project back (or to --output) and prints each change with an error figure
// where one exists.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "assets/render_scene.h"
#include "base/error.h"
#include "calibrate_scene_common.h"
#include "commands.h"
#include "common.h"
#include "reconstruction/probe_align.h"
#include "reconstruction/sun_from_shadow.h"
#include "scene/project_io.h"

namespace dp::cli {

namespace {

struct ProbeOptions {
    std::string project, output;
    std::optional<float> fov, intensity, clip;
    std::vector<float> shadow, card, sun_from_shadow;
    int patch_radius = 2;
    float object_height = 0, reflectance = 0.18f;
    bool object_base = false;
    bool white_balance = false, force = false;
    int samples = 256;
};

void set_mirror_ball_fov(Project& p, const ProbeOptions& o) {
    if (!(*o.fov >= 0 && *o.fov < 180))
        throw InputError(o.project, "--fov",
                         "the ball camera's field of view must be in [0, 180) degrees");
    if (p.probe.format != ProbeSpec::Format::MirrorBall)
        throw InputError(o.project, "--fov",
                         "the probe is not a mirror ball (probe.format is \"latlong\")");
    std::printf("probe mirror_ball_fov_deg %g -> %g\n", p.probe.mirror_ball_fov_deg, *o.fov);
    p.probe.mirror_ball_fov_deg = *o.fov;
}

/// Turns the probe about +Y so that its brightest region lies where the shadow puts the sun.
void align_to_shadow(Project& p, const ProbeOptions& o) {
    if (!(o.object_height > 0))
        throw InputError(o.project, "--object-height",
                         "the shadow cue needs the object point's height (> 0)");
    SceneAssets assets = load_assets(p);
    for (const std::string& w : assets.warnings) warn(w);
    const Camera camera = p.camera.build(assets.photo.width(), assets.photo.height());
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
    const ProbeYaw yaw = align_probe_yaw(bright, p.probe.rotation_deg, sun);
    const Bearing b = bearing_of(sun);
    std::printf("sun from the shadow: azimuth %.2f deg, elevation %.2f deg\n", b.azimuth_deg,
                b.elevation_deg);
    std::printf("probe rotation_deg %s -> %s (turned %.2f deg about +Y)\n",
                vec(p.probe.rotation_deg).c_str(), vec(yaw.rotation_deg).c_str(), yaw.yaw_deg);
    std::printf("elevation_mismatch_deg %.3g\n", yaw.elevation_mismatch_deg);
    p.probe.rotation_deg = yaw.rotation_deg;
}

/// Scales the probe's intensity (and with --white-balance each channel) so that the grey card's
/// photographed radiance matches.
void match_grey_card(Project& p, const ProbeOptions& o) {
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
    WhiteBalanceMatch wb;
    try {
        if (o.white_balance)
            m = wb = match_white_balance_grey_card(scene, card, clip_level(p, o.clip), o.samples);
        else
            m = match_exposure_grey_card(scene, card, clip_level(p, o.clip), o.samples);
    } catch (const InputError& e) {
        rethrow_for(e, o.project);
    }
    std::printf("probe intensity %g -> %g (x%.4g from %d card pixels)\n", p.probe.intensity,
                m.intensity, m.scale, m.pixels);
    if (o.white_balance) {
        std::printf("probe white_balance %s -> %s\n", vec(p.probe.white_balance).c_str(),
                    vec(wb.white_balance).c_str());
        // The card's colour as r, g, b summing to 1: how far the probe's light was off.
        std::printf("card chromaticity: photo %s, probe before %s, after %s\n",
                    vec(wb.photo_chromaticity).c_str(), vec(wb.before_chromaticity).c_str(),
                    vec(wb.after_chromaticity).c_str());
        p.probe.white_balance = wb.white_balance;
    }
    std::printf("card_spread %.3g\n", m.spread);
    p.probe.intensity = m.intensity;
}

/// Scales the probe's sun so that it gives a lit and a shadowed patch of one surface the
/// photo's contrast between them.
void restore_sun(Project& p, const ProbeOptions& o) {
    if (o.patch_radius < 0 || o.patch_radius > 50)
        throw InputError(o.project, "--patch-radius", "must be in [0, 50] pixels");
    SceneAssets assets = load_assets(p);
    for (const std::string& w : assets.warnings)
        if (w.rfind("probe.path: the probe's", 0) != 0) warn(w);  // the clipped sun is what this fixes
    RenderScene scene(p, std::move(assets));
    SunShadowPatches patches;
    patches.lit = vec2(o.sun_from_shadow[0], o.sun_from_shadow[1]);
    patches.shadow = vec2(o.sun_from_shadow[2], o.sun_from_shadow[3]);
    patches.radius = o.patch_radius;
    SunFromShadow m;
    try {
        m = match_sun_to_shadow(scene, patches);
    } catch (const InputError& e) {
        // Named by the option that carried the patches.
        std::string what = e.what();
        const std::string prefix = "field '" + e.field() + "': ";
        if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
        throw InputError(o.project, "--sun-from-shadow", what);
    }
    std::printf("lit / shadowed patch: photo %.4g, probe before %.4g (sun %.4g, sky %.4g and %.4g)\n",
                m.photo_contrast, m.probe_contrast, m.sun_lit, m.sky_lit, m.sky_shadow);
    std::printf("probe sun_scale %g -> %g (x%.4g)\n", p.probe.sun_scale, m.sun_scale, m.scale);
    if (!(m.sun_scale <= kMaxSunScale))
        throw InputError(o.project, "--sun-from-shadow",
                         "the sun would need " + std::to_string(m.sun_scale) + " times its light, more than "
                         "probe.sun_scale allows: is the shadowed patch lit by the sky at all?");
    p.probe.sun_scale = m.sun_scale;
}

void run_probe(const ProbeOptions& o) {
    if (!o.fov && !o.intensity && o.shadow.empty() && o.card.empty() && o.sun_from_shadow.empty())
        throw InputError(o.project, "",
                         "nothing to do: give --fov, --shadow (with --object-height), --sun-from-shadow, "
                         "--grey-card (with --reflectance) or --intensity");
    Project p = load_project(o.project);
    check_scene_outputs(p, o.project, o.output, {}, o.force);
    if (o.fov) set_mirror_ball_fov(p, o);
    if (!o.shadow.empty()) align_to_shadow(p, o);
    // Before the grey card: a card in sunlight is lit by the restored sun.
    if (!o.sun_from_shadow.empty()) restore_sun(p, o);
    if (o.intensity) {
        std::printf("probe intensity %g -> %g (set by hand)\n", p.probe.intensity, *o.intensity);
        p.probe.intensity = *o.intensity;
    } else if (!o.card.empty()) {
        match_grey_card(p, o);
    }
    write_back(p, o.project, o.output);
}

}  // namespace

Command add_calibrate_probe_command(CLI::App& calibrate) {
    auto o = std::make_shared<ProbeOptions>();
    CLI::App* sub = calibrate.add_subcommand(
        "probe",
        "Set the mirror ball's field of view, align the probe's rotation to a shadow, match its "
        "exposure and white balance");
    sub->add_option("project", o->project, "Project file (JSON)")->required();
    sub->add_option("--fov", o->fov,
                    "Vertical field of view (deg) of the camera that shot the mirror ball")
        ->check(kFinite);
    sub->add_option("--shadow", o->shadow,
                    "Shadow cue: object point x y and its shadow's tip x y (pixels); turns the "
                    "probe about +Y to put its brightest region on the sun")
        ->expected(4)
        ->check(kFinite);
    sub->add_option("--object-height", o->object_height,
                    "Height of the clicked object point above the ground")
        ->check(kFinite);
    sub->add_flag("--object-base", o->object_base,
                  "The clicked object point is its base on the ground; the point casting the "
                  "shadow is --object-height above it");
    sub->add_option("--sun-from-shadow", o->sun_from_shadow,
                    "A sunlit and a shadowed patch of one real surface, x y x y (pixels): scales the "
                    "probe's sun (probe.sun_scale) so that it gives them the photo's contrast; for a "
                    "clipped sun")
        ->expected(4)
        ->check(kFinite);
    sub->add_option("--patch-radius", o->patch_radius,
                    "With --sun-from-shadow: each patch is (2r+1)^2 pixels (default 2)")
        ->needs(sub->get_option("--sun-from-shadow"));
    sub->add_option("--grey-card", o->card,
                    "Grey card rectangle x0 y0 x1 y1 (pixels, inclusive) on a real proxy")
        ->expected(4)
        ->check(kFinite);
    sub->add_option("--reflectance", o->reflectance, "The card's reflectance (default 0.18)")
        ->check(kFinite);
    sub->add_flag("--white-balance", o->white_balance,
                  "With --grey-card: match the probe's colour too (probe.white_balance, of "
                  "luminance 1), the card being neutral grey")
        ->needs(sub->get_option("--grey-card"));
    auto* intensity =
        sub->add_option("--intensity", o->intensity, "Set the probe intensity by hand")
            ->check(kNonNegative);
    intensity->excludes(sub->get_option("--grey-card"));
    sub->add_option("--clip", o->clip, "Photo value (file units) at which a card pixel is clipped")
        ->check(kFinite);
    sub->add_option("--samples", o->samples, "Probe samples per card pixel (default 256)")
        ->check(kPositive);
    sub->add_option("-o,--output", o->output, "Write the project here instead of updating it");
    add_force_flag(sub, o->force);
    return {sub, [o] {
                run_probe(*o);
                return 0;
            }};
}

}  // namespace dp::cli
