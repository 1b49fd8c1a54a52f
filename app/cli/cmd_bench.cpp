// `diffphoton bench`: run time against error for differential photon mapping and standard
// differential rendering on benchmark scenes with converged ground truths.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>

#include "base/atomic_file.h"
#include "base/error.h"
#include "bench_cycles.h"
#include "commands.h"
#include "common.h"
#include "outputs.h"
#include "image/denoise.h"
#include "image/image_io.h"
#include "image/image_metrics.h"
#include "reference/standard_differential.h"
#include "render/denoise_aovs.h"
#include "scene/project_io.h"
#include "image/noise_blend.h"
#include "render/progressive.h"

namespace dp::cli {

namespace fs = std::filesystem;

namespace {


struct BenchOptions {
    std::vector<std::string> scenes;
    std::vector<std::string> methods{"differential", "standard", "standard-correlated"};
    std::string output, images, blender;
    std::string bpy5_python;  ///< Blender 5's Python, for cycles5 and cycles5-artist
    double max_seconds_differential = 30, max_seconds_standard = 120;
    int threads = 0;
    bool denoise = false;  ///< also measure the denoised image of our methods at each snapshot
    bool force = false;    ///< replace a read-only output
};

/// A scene folder: scene.json (what both methods render) and two independent halves of the
/// converged truth, truth-a.exr and truth-b.exr (main layer and alpha).
struct BenchScene {
    std::string name, dir;
    std::shared_ptr<RenderScene> scene;
    RenderSettings settings;
    Image truth, alpha;
    std::vector<bool> changed, on_objects, on_real;  ///< changed pixels; split by what they see
    float ceiling = 0;  ///< errors are measured on values clamped here
    nlohmann::json info;
    std::optional<DenoiseAovs> aovs;  ///< the denoiser's guides, made on first use
};

BenchScene load_bench_scene(const std::string& dir) {
    BenchScene b;
    b.name = fs::path(dir).filename().string();
    if (b.name.empty()) b.name = fs::path(dir).parent_path().filename().string();
    b.dir = dir;
    LoadedScene loaded = load_scene((fs::path(dir) / "scene.json").string());
    b.scene = loaded.scene;
    b.settings = loaded.settings;
    const std::string ta = (fs::path(dir) / "truth-a.exr").string(), tb = (fs::path(dir) / "truth-b.exr").string();
    for (const std::string& t : {ta, tb})
        if (!fs::exists(t))
            throw InputError(t, "", "missing ground truth (make it with bench/scenes/make_scenes.py)");
    const Image a = load_exr_layer(ta, ""), bb = load_exr_layer(tb, "");
    b.truth = mean_image(a, bb);
    b.alpha = mean_image(load_exr_layer(ta, "alpha"), load_exr_layer(tb, "alpha"));
    const Image& photo = b.scene->photo();
    if (photo.width() != b.truth.width() || photo.height() != b.truth.height())
        throw InputError(ta, "", "the truth's size differs from the photograph's");
    b.changed = changed_pixels(photo, b.truth, b.alpha);
    b.on_objects.resize(b.changed.size());
    b.on_real.resize(b.changed.size());
    for (size_t i = 0; i < b.changed.size(); ++i) {
        b.on_objects[i] = b.changed[i] && b.alpha[i].x > 0;
        b.on_real[i] = b.changed[i] && b.alpha[i].x == 0;
    }
    // Errors are measured on pixel values clamped at the renderer's own ceiling (a few pixels
    // that see the sun in a mirror, 10^4 times brighter, would otherwise decide every figure).
    b.ceiling = kErrorCeilingFactor * luminance_quantile(photo, 0.999);
    // The mean of two independent halves has half the error of their difference.
    const ImageError whole = image_error(a, bb, {}, b.ceiling), changed = image_error(a, bb, b.changed, b.ceiling);
    b.info = {{"scene", b.name},
              {"width", photo.width()},
              {"height", photo.height()},
              {"changed_pixels", changed.pixels},
              {"error_ceiling", b.ceiling},
              {"truth_rmse", whole.rmse / 2},
              {"truth_rel_rmse", whole.rel_rmse / 2},
              {"truth_rmse_changed", changed.rmse / 2},
              {"truth_rel_rmse_changed", changed.rel_rmse / 2}};
    return b;
}

/// Variants of our method that turn one of its parts off, to show what each buys.
std::function<void(RenderSettings&)> variant_edit(const std::string& method) {
    if (method == "differential-photons") return [](RenderSettings& s) { s.estimator = Estimator::Photons; };
    if (method == "differential-random") return [](RenderSettings& s) { s.low_discrepancy = false; };
    if (method == "differential-uniform") return [](RenderSettings& s) { s.adaptive_threshold = 0; };
    if (method == "differential-fixed-photons") return [](RenderSettings& s) { s.balance_photons = false; };
    return {};
}

/// Our photon-mapping methods: the default and its variants.
bool is_differential(const std::string& method) { return method == "differential" || bool(variant_edit(method)); }

std::unique_ptr<PassRenderer> make_renderer(const std::string& method, BenchScene& b) {
    using Sampling = StandardDifferentialRenderer::Sampling;
    RenderSettings settings = b.settings;
    if (const auto edit = variant_edit(method)) edit(settings);
    if (method == "standard")
        return std::make_unique<StandardDifferentialRenderer>(b.scene, settings, Sampling::Independent);
    if (method == "standard-correlated")
        return std::make_unique<StandardDifferentialRenderer>(b.scene, settings, Sampling::Correlated);
    return std::make_unique<ProgressiveRenderer>(b.scene, settings);
}


/// Error of the denoised image (render --denoise's, its quality chosen by the render's time) against the truth, and
/// the filter's time (not counted in the render's time).
struct DenoisedError {
    ImageError changed, objects, real;
    double seconds = 0;
};

DenoisedError denoised_error(BenchScene& b, const PassRenderer& r, const Image& img) {
    if (!b.aovs) b.aovs = denoise_aovs(*b.scene);
    const auto t0 = std::chrono::steady_clock::now();
    const Image& photo = b.scene->photo();
    const Image variance = r.variance_layer();
    Image d = denoise_augmented(photo, img, r.alpha_layer(), r.dL_layer(), b.aovs->albedo, b.aovs->normal,
                                denoise_quality_for(r.stats().seconds, photo.size()));
    if (variance.width() == img.width() && variance.height() == img.height()) d = blend_by_noise(img, d, variance);
    DenoisedError e;
    e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    e.changed = image_error(d, b.truth, b.changed, b.ceiling);
    e.objects = image_error(d, b.truth, b.on_objects, b.ceiling);
    e.real = image_error(d, b.truth, b.on_real, b.ceiling);
    return e;
}

/// Runs one method on one scene until its time budget is spent, measuring the error at pass
/// counts spaced by sqrt(2). Only render_pass() is timed; measuring the error is not.
nlohmann::json run_method(const BenchOptions& o, BenchScene& b, const std::string& method,
                          nlohmann::json& rows) {
    const double budget = is_differential(method) ? o.max_seconds_differential : o.max_seconds_standard;
    std::unique_ptr<PassRenderer> r =
        is_cycles_method(method)
            ? make_cycles_renderer(b.scene, {method, method == "cycles" ? o.blender : o.bpy5_python, budget, o.threads})
            : make_renderer(method, b);
    std::vector<double> pass_seconds;
    double next_snapshot = 1;
    for (;;) {
        const double before = r->stats().seconds;
        if (!r->render_pass(interrupt_flag())) break;
        pass_seconds.push_back(r->stats().seconds - before);
        const bool last = r->stats().seconds >= budget;
        if (r->passes() + 1e-9 < next_snapshot && !last) continue;
        while (next_snapshot <= r->passes()) next_snapshot = std::max(next_snapshot + 1, std::round(next_snapshot * std::sqrt(2.0)));
        const Image img = r->image();
        const ImageError whole = image_error(img, b.truth, {}, b.ceiling);
        const ImageError changed = image_error(img, b.truth, b.changed, b.ceiling);
        const ImageError objects = image_error(img, b.truth, b.on_objects, b.ceiling);
        const ImageError real = image_error(img, b.truth, b.on_real, b.ceiling);
        const RenderStats& st = r->stats();
        rows.push_back({{"scene", b.name},
                        {"method", method},
                        {"seconds", st.seconds},
                        {"passes", st.passes},
                        {"photons", st.photons_emitted},
                        {"samples_per_pixel", st.samples_per_pixel},
                        {"rmse", whole.rmse},
                        {"rel_rmse", whole.rel_rmse},
                        {"rmse_changed", changed.rmse},
                        {"rel_rmse_changed", changed.rel_rmse},
                        {"rel_rmse_objects", objects.rel_rmse},
                        {"rel_rmse_real_changed", real.rel_rmse},
                        {"estimated_rel_error", st.estimated_rel_error},
                        {"tiles_stopped", st.tiles_stopped},
                        {"photons_last_pass", st.photons_per_pass},
                        {"photon_variance_share", st.photon_variance_share}});
        std::printf("%-14s %-12s %8.2fs  passes %5d  rel. RMSE %.4f  changed %.4f (objects %.4f, real %.4f, "
                    "estimated %.4f)",
                    b.name.c_str(), method.c_str(), st.seconds, st.passes, whole.rel_rmse,
                    changed.rel_rmse, objects.rel_rmse, real.rel_rmse, st.estimated_rel_error);
        if (o.denoise && is_differential(method)) {
            const DenoisedError d = denoised_error(b, *r, img);
            rows.back().update({{"denoise_seconds", d.seconds},
                                {"rel_rmse_changed_denoised", d.changed.rel_rmse},
                                {"rel_rmse_objects_denoised", d.objects.rel_rmse},
                                {"rel_rmse_real_changed_denoised", d.real.rel_rmse}});
            std::printf("  denoised %.4f (%.2f s)", d.changed.rel_rmse, d.seconds);
        }
        std::printf("\n");
        std::fflush(stdout);
        if (last || interrupted()) {
            if (!o.images.empty()) {
                Image out = img;
                save_ldr((fs::path(o.images) / (b.name + "-" + method + ".png")).string(), out);
            }
            break;
        }
    }
    std::vector<double> sorted = pass_seconds;
    std::sort(sorted.begin(), sorted.end());
    return {{"scene", b.name},
            {"method", method},
            {"passes", r->passes()},
            {"median_pass_seconds", sorted.empty() ? 0.0 : sorted[sorted.size() / 2]}};
}

/// The command line's own checks, before any scene is read (Command::check).
void check_bench_options(const BenchOptions& o) {
    for (const std::string& m : o.methods)
        if (!is_differential(m) && m != "standard" && m != "standard-correlated" && !is_cycles_method(m))
            throw InputError("", "--methods",
                             "unknown method '" + m +
                                 "' (differential, differential-photons, differential-random, "
                                 "differential-uniform, differential-fixed-photons, standard, standard-correlated, cycles, cycles5 or "
                                 "cycles5-artist)");
    if (o.denoise) {
        std::string why;
        if (!denoiser_available(&why)) throw InputError("", "--denoise", why);
    }
}

int run_bench(BenchOptions o) {
    check_bench_options(o);
    ReadSet inputs;
    for (const std::string& dir : o.scenes) {
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(dir, ec))
            inputs.add(entry.path().string(), "a file of scene folder " + dir);
        const std::string project = (fs::path(dir) / "scene.json").string();
        if (fs::is_regular_file(project, ec)) inputs.add_project(load_project(project), project);
    }
    check_outputs({{o.output, "--output"}}, inputs, o.force);
    o.blender = prepare_cycles_method(o.methods, o.blender);
    o.bpy5_python = prepare_cycles5_methods(o.methods);
    if (!o.images.empty()) fs::create_directories(o.images);
    return with_threads(o.threads, [&]() -> int {
        install_interrupt_handler();
        nlohmann::json doc = {{"scenes", nlohmann::json::array()},
                              {"runs", nlohmann::json::array()},
                              {"rows", nlohmann::json::array()}};
        for (const std::string& dir : o.scenes) {
            BenchScene b = load_bench_scene(dir);
            doc["scenes"].push_back(b.info);
            for (const std::string& m : o.methods) {
                doc["runs"].push_back(run_method(o, b, m, doc["rows"]));
                if (interrupted()) break;
            }
            if (interrupted()) break;
        }
        write_file_atomically(o.output, doc.dump(1) + "\n");
        std::printf("wrote %s\n", o.output.c_str());
        return interrupted() ? kInterruptedExit : 0;
    });
}

}  // namespace

Command add_bench_command(CLI::App& app) {
    auto o = std::make_shared<BenchOptions>();
    CLI::App* sub = app.add_subcommand(
        "bench", "Run time against error of both methods on benchmark scenes (JSON rows)");
    sub->add_option("scenes", o->scenes, "Scene folders (scene.json, truth-a.exr, truth-b.exr)")
        ->required()
        ->check(CLI::ExistingDirectory);
    sub->add_option("-o,--output", o->output, "Rows as JSON")->required();
    sub->add_option("--methods", o->methods,
                    "Comma-separated: differential (split estimator), differential-photons (all-photon "
                    "estimator), differential-random (no low-discrepancy points), differential-uniform "
                    "(no adaptive sampling), differential-fixed-photons (the project's photons in every "
                    "pass), standard, standard-correlated, cycles (Blender 3.4), cycles5 "
                    "(Blender 5: $DP_BPY5_PYTHON, else .deps/bpy5/bin/python), cycles5-artist (Blender 5 "
                    "as artists run it: denoised, adaptive sampling, path guiding, light tree, MNEE)")
        ->delimiter(',');
    sub->add_option("--max-seconds-differential", o->max_seconds_differential,
                    "Render-time budget of differential photon mapping per scene")
        ->check(kPositive);
    sub->add_option("--max-seconds-standard", o->max_seconds_standard,
                    "Render-time budget of standard differential rendering (and of the Cycles methods) per scene")
        ->check(kPositive);
    sub->add_option("--blender", o->blender,
                    "Blender 3.4 for the cycles method (default: $DP_BLENDER, else blender on PATH)");
    sub->add_option("--images", o->images, "Folder for each run's last image (PNG)");
    sub->add_option("--threads", o->threads, "Worker threads (0: all cores)")->check(kNonNegative);
    sub->add_flag("--denoise", o->denoise,
                  "Also measure our methods' images denoised (Open Image Denoise, final quality) at "
                  "each measurement; the filter's time is reported apart from the render's");
    add_force_flag(sub, o->force);
    return {sub, [o] { return run_bench(*o); }, [o] { check_bench_options(*o); }};
}

}  // namespace dp::cli
