// `diffphoton calibrate albedo`: albedo textures of real proxies from the photo and the probe.
// Reads a project, writes each texture (and its mask) beside the project, points the proxies at
// them, writes the project back (or to --output) and prints how much of each was estimated.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "calibrate_scene_common.h"
#include "commands.h"
#include "common.h"
#include "reconstruction/albedo.h"

namespace dp::cli {

namespace fs = std::filesystem;

namespace {

struct AlbedoOptions {
    std::string project, output;
    std::vector<std::string> proxies;
    int resolution = 256, subsamples = 3, samples = 512, bounce = 64, threads = 0;
    std::optional<float> clip;
    uint64_t seed = 1;
    bool force = false;
};

/// Which proxies: the named ones, else every one that has a texture layout.
std::vector<size_t> chosen_proxies(const Project& p, const AlbedoOptions& o) {
    std::vector<size_t> chosen;
    for (const std::string& want : o.proxies) {
        auto it = std::find_if(p.real.begin(), p.real.end(),
                               [&](const RealProxy& r) { return r.name == want; });
        if (it == p.real.end())
            throw InputError(o.project, "--proxy", "no real proxy named '" + want + "'");
        chosen.push_back(size_t(it - p.real.begin()));
    }
    if (o.proxies.empty()) chosen = texturable_real_proxies(p);
    if (chosen.empty())
        throw InputError(o.project, "real", "the project has no plane, box or mesh proxy");
    return chosen;
}

void print_texture(const Project& p, size_t i, const AlbedoTexture& t, const std::string& texture) {
    const std::string mask = fs::path(texture).stem().string() + "_mask.exr";
    const double n = double(t.albedo.size()) / 100.0;
    std::printf(
        "real[%zu] '%s': %dx%d texels, estimated %.1f%% (clipped %.1f%%, unseen %.1f%%, "
        "unlit %.1f%%)\n",
        i, p.real[i].name.c_str(), t.albedo.width(), t.albedo.height(), t.valid / n, t.clipped / n,
        t.unseen / n, t.unlit / n);
    std::printf("  mean_albedo %s  irradiance_rel_error %.3g  bounce_fraction %.3g\n",
                vec(t.mean_albedo).c_str(), t.irradiance_rel_error, t.bounce_fraction);
    std::printf("  texture %s  mask %s\n", texture.c_str(), mask.c_str());
}

/// check_scene_outputs with the textures and masks the chosen proxies get; each texture may
/// replace the one its proxy has now (it is estimated anew), no other input.
void check_albedo_outputs(const Project& p, const AlbedoOptions& o) {
    const std::string project_file = o.output.empty() ? o.project : o.output;
    std::vector<Output> textures;
    for (size_t i : chosen_proxies(p, o)) {
        const AlbedoTextureFiles files = albedo_texture_files(p, int(i), project_file);
        const std::string field = "real[" + std::to_string(i) + "].albedo.texture";
        const double bytes = image_output_bytes(".exr", {}, o.resolution, o.resolution);
        Output texture{files.texture.string(), field, bytes};
        const Albedo& now = p.real[i].albedo;
        if (now.kind == Albedo::Kind::Texture) texture.updates = p.resolve(now.texture_path).string();
        textures.push_back(texture);
        textures.push_back({files.mask.string(), field, bytes});
    }
    check_scene_outputs(p, o.project, o.output, textures, o.force);
}

void run_albedo(const AlbedoOptions& o) {
    with_threads(o.threads, [&] {
        LoadedScene loaded =
            load_scene(o.project, {}, [&](const Project& p, AssetLibrary&) { check_albedo_outputs(p, o); });
        auto scene = loaded.scene;
        Project p = loaded.project;
        const std::vector<size_t> chosen = chosen_proxies(p, o);

        AlbedoTextureOptions ao;
        ao.max_resolution = o.resolution;
        ao.subsamples = o.subsamples;
        ao.probe_samples = o.samples;
        ao.bounce_samples = o.bounce;
        ao.clip_level = clip_level(p, o.clip);
        ao.seed = o.seed;
        const std::string project_file = o.output.empty() ? o.project : o.output;
        for (size_t i : chosen) {
            AlbedoTexture t;
            try {
                t = estimate_albedo_texture(*scene, int(i), ao);
            } catch (const InputError& e) {
                rethrow_for(e, o.project);
            }
            print_texture(p, i, t, attach_albedo_texture(p, int(i), t, project_file, true));
        }
        write_back(p, o.project, o.output);
        return 0;
    });
}

}  // namespace

Command add_calibrate_albedo_command(CLI::App& calibrate) {
    auto o = std::make_shared<AlbedoOptions>();
    CLI::App* sub = calibrate.add_subcommand(
        "albedo", "Estimate albedo textures of real proxies from the photo and the probe");
    sub->add_option("project", o->project, "Project file (JSON)")->required();
    sub->add_option("--proxy", o->proxies,
                    "Proxy name (repeatable; default: every plane, box and mesh)");
    sub->add_option("--resolution", o->resolution,
                    "Texture size along the longer side (default 256)")
        ->check(CLI::Range(1, 8192));
    sub->add_option("--subsamples", o->subsamples, "Points per texel side (default 3)")
        ->check(CLI::Range(1, 16));
    sub->add_option("--samples", o->samples, "Probe samples per texel (default 512)")
        ->check(kPositive);
    sub->add_option("--bounce-samples", o->bounce,
                    "Rays per texel for light from other real surfaces (0: off)")
        ->check(kNonNegative);
    sub->add_option("--clip", o->clip,
                    "Photo value (file units) at which a pixel is clipped (default: 0.99 for "
                    "8-bit photos, none for EXR/HDR)")
        ->check(kFinite);
    sub->add_option("--seed", o->seed, "Random seed")->check(kSeed);
    sub->add_option("--threads", o->threads, "Worker threads (0: all cores)")
        ->check(kNonNegative);
    sub->add_option("-o,--output", o->output,
                    "Write the project here instead of updating it (the textures go beside it)");
    add_force_flag(sub, o->force);
    return {sub, [o] {
                run_albedo(*o);
                return 0;
            }};
}

}  // namespace dp::cli
