// `diffphoton render`: progressive differential photon mapping through a RenderSession, the
// same path the studio uses.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "base/error.h"
#include "base/error_reason.h"
#include "commands.h"
#include "common.h"
#include "image/denoise.h"
#include "image/image_io.h"
#include "image/plate_match.h"
#include "reference/standard_differential.h"
#include "render/denoise_aovs.h"
#include "image/noise_blend.h"
#include "outputs.h"
#include "render/progressive.h"
#include "render/render_limits.h"
#include "render/render_output.h"
#include "render/session.h"
#include "render_pixel.h"
#include "render_shard.h"
#include "render_sink.h"

namespace dp::cli {

namespace {

struct RenderOptions {
    std::string project, output, pixel, method = "differential", pass_range, adaptive, match_plate;
    int passes = 0, pass = 1, threads = 0, focus_after = 0, samples_per_pass = 1, probe_max_width = 0;
    double time_s = 0;
    int64_t photons = 0;
    uint64_t seed = 0;
    float exposure = 0;
    bool layers = false, denoise = false, force = false;
    OutputFormat format;
    CLI::Option *passes_opt = nullptr, *time_opt = nullptr, *photons_opt = nullptr,
                *seed_opt = nullptr, *threads_opt = nullptr, *pixel_opt = nullptr, *range_opt = nullptr,
                *probe_max_width_opt = nullptr;
};

void apply_overrides(const RenderOptions& o, Project& p) {
    if (o.passes_opt->count()) {
        p.render.passes = o.passes;
        p.render.time_budget_s = 0;  // a pass count on the command line beats the file's budget
    }
    if (o.time_opt->count()) p.render.time_budget_s = o.time_s;
    if (o.photons_opt->count()) p.render.photons_per_pass = o.photons;
    if (o.seed_opt->count()) p.render.seed = o.seed;
    if (o.threads_opt->count()) p.render.threads = o.threads;
    if (o.probe_max_width_opt->count()) p.probe.max_width = o.probe_max_width;
    if (o.adaptive == "off") p.render.adaptive_threshold = 0;
    if (o.adaptive == "on" && p.render.adaptive_threshold == 0)  // on, where the project had it off
        p.render.adaptive_threshold = RenderSettings{}.adaptive_threshold;
}

/// The project fields the command line set, each with the flag that set it.
std::vector<std::pair<std::string, std::string>> overridden_fields(const RenderOptions& o) {
    std::vector<std::pair<std::string, std::string>> fields;
    if (o.passes_opt->count()) fields.emplace_back("render.passes", "--passes");
    if (o.time_opt->count()) fields.emplace_back("render.time_budget_s", "--time");
    if (o.photons_opt->count()) fields.emplace_back("render.photons_per_pass", "--photons");
    if (o.seed_opt->count()) fields.emplace_back("render.seed", "--seed");
    if (o.threads_opt->count()) fields.emplace_back("render.threads", "--threads");
    if (o.probe_max_width_opt->count()) fields.emplace_back("probe.max_width", "--probe-max-width");
    if (!o.adaptive.empty()) fields.emplace_back("render.adaptive_threshold", "--adaptive");
    return fields;
}

/// Runs `work`; a value the command line gave that is refused (by the scene's or the render's
/// checks, which know only project fields) is reported under the flag the user typed, with no
/// project file: "--photons", not "render.photons_per_pass".
template <class F>
int reported_under_flags(const RenderOptions& o, F&& work) {
    try {
        return work();
    } catch (const InputError& e) {
        for (const auto& [field, flag] : overridden_fields(o))
            if (e.field() == field) throw InputError("", flag, error_reason(e));
        throw;
    }
}

/// `--pass-range`'s options: refuses what would make a shard's passes depend on passes it does
/// not render, or what a shard does not hold.
void check_shard_options(const RenderOptions& o) {
    if (o.adaptive == "on")
        throw InputError("", "--adaptive", "a shard's passes must not depend on passes it does not render: "
                                           "--pass-range renders without adaptive sampling");
    if (o.method != "differential")
        throw InputError("", "--pass-range", "only --method differential renders shards");
    if (o.focus_after > 0) throw InputError("", "--focus-after", "cannot be used with --pass-range");
    if (o.denoise) throw InputError("", "--denoise", "shards hold sums, not images; denoise the merged image");
    if (o.layers) throw InputError("", "--layers", "shards hold every layer's sums; pass --layers to merge");
    if (o.pixel_opt->count()) throw InputError("", "--pixel", "cannot be used with --pass-range");
    int begin = 0, end = 0;
    parse_pass_range(o.pass_range, begin, end);
    check_shard_output(o.output);
}

/// `--pass-range`: a shard of the passes, written as exact sums for `merge` (render_shard.h).
int run_shard(const RenderOptions& o) {
    ShardRequest r;
    r.project = o.project;
    r.output = o.output;
    parse_pass_range(o.pass_range, r.pass_begin, r.pass_end);
    r.threads = o.threads;
    r.force = o.force;
    r.edit = [&o](Project& p) { apply_overrides(o, p); };
    return reported_under_flags(o, [&] { return render_shard(r); });
}

/// The denoised augmented photo and change (docs/method-notes.md, "Denoising"): only the
/// render's change is denoised, guided by albedo and normal from the pixel centres.
struct Denoised {
    Image image, dL;
};

Denoised denoise_result(const RenderScene& scene, const RenderUpdate& u, bool with_dL) {
    const int w = u.image.width(), h = u.image.height();
    DenoiseAovs aovs = denoise_aovs(scene);
    const Image& photo = scene.photo();
    const bool same = photo.width() == w && photo.height() == h;
    if (!same) aovs = {resample(aovs.albedo, w, h), resample(aovs.normal, w, h)};
    Denoised d;
    // The filter's quality follows the render's time: a quick render is not held up by it.
    const DenoiseQuality quality = denoise_quality_for(u.stats.seconds, size_t(w) * size_t(h));
    d.image = denoise_augmented(same ? photo : resample(photo, w, h), u.image, u.alpha, u.dL, aovs.albedo,
                                aovs.normal, quality);
    // Where the raw render has converged past what the filter keeps, the raw pixels stand.
    if (u.variance.width() == w && u.variance.height() == h) d.image = blend_by_noise(u.image, d.image, u.variance);
    if (with_dL) d.dL = denoise_change(u.dL, aovs.albedo, aovs.normal, denoise_ceiling(photo), quality);
    return d;
}

/// The render given the photo's grain and softness (image/plate_match.h), from `image` (the raw
/// or denoised composite); says on stderr what was measured.
PlateMatch plate_matched(const RenderScene& scene, const Image& image, const RenderUpdate& u, uint64_t seed) {
    const PlateFigures figures = measure_plate(scene.photo());
    if (figures.grain.empty()) warn("--match-plate: the photo has too few flat patches to measure its grain; none is added");
    if (figures.softness_px < 0) warn("--match-plate: the photo has too few edges to measure its softness; nothing is blurred");
    std::fprintf(stderr, "plate: %s\n", figures.summary().c_str());
    return match_plate(image, scene.photo(), u.alpha, u.dL, figures, seed);
}

void write_result(const RenderOptions& o, ImageKind kind, const LoadedScene& loaded, RenderUpdate& u) {
    const RenderScene& scene = *loaded.scene;
    const ImageWriteOptions options =
        write_options(o.format, render_metadata(loaded.project, o.project, u.stats.passes, loaded.settings.seed));
    std::optional<Denoised> denoised;
    if (o.denoise) denoised = denoise_result(scene, u, kind == ImageKind::Exr);
    std::optional<PlateMatch> matched;
    if (o.match_plate == "on" || (o.match_plate.empty() && loaded.project.display.match_plate))
        matched = plate_matched(scene, denoised ? denoised->image : u.image, u, loaded.settings.seed);
    if (kind == ImageKind::Ldr) {
        write_image(o.output, matched ? std::move(matched->beauty) : denoised ? std::move(denoised->image) : std::move(u.image),
                    output_view(o.format, o.exposure, project_view(loaded.project)), options);
        return;
    }
    std::vector<ExrLayer> extra;
    if (denoised) extra = {{"denoised", &denoised->image}, {"dL_denoised", &denoised->dL}};
    // The main layer stays the render as rendered; the matched one and its grain beside it.
    if (matched) extra.insert(extra.end(), {{"matched", &matched->beauty}, {"grain", &matched->grain}});
    if (o.format.bits != 0) throw InputError(o.output, "--bits", "an EXR holds half (--half) or 32-bit floats");
    for (const std::string& w : save_render_exr(o.output, u, scene.photo(), o.layers, extra, options))
        warn(o.output + ": " + w);
}

/// check_outputs for a render's image: its size from the photo's, its channels from the options.
void check_render_output(const RenderOptions& o, ImageKind kind, const Project& p, AssetLibrary& library) {
    ReadSet inputs;
    inputs.add_project(p, o.project);
    int width = 0, height = 0;
    library.photo_size(p, width, height);
    const int channels =
        kind == ImageKind::Exr
            ? render_exr_channels(o.layers) + (o.denoise ? 6 : 0) +
                  (o.match_plate == "on" || (o.match_plate.empty() && p.display.match_plate) ? 6 : 0)  // matched, grain
            : 3;
    check_outputs({{o.output, "--output", image_output_bytes(o.output, o.format, width, height, channels)}}, inputs,
                  o.force);
}

/// The options that only some methods take, refused (exit 2) before any pass.
void check_method_options(const RenderOptions& o, bool standard, bool debug) {
    if (standard && debug)
        throw InputError("", "--pixel", "the per-pixel debugger is for --method differential");
    if (!standard && o.focus_after > 0)
        throw InputError("", "--focus-after", "only the path-traced methods (standard, standard-correlated) focus");
    if (!standard && o.samples_per_pass != 1)
        throw InputError("", "--samples-per-pass", "only the path-traced methods take camera samples per pass");
    if (o.denoise && debug) throw InputError("", "--denoise", "the per-pixel debugger does not denoise");
    if (o.denoise) {
        std::string why;
        if (!denoiser_available(&why)) throw InputError("", "--denoise", why);
    }
}

/// The command line's own checks, before any file is read (Command::check).
void check_render_options(const RenderOptions& o) {
    if (o.range_opt->count()) return check_shard_options(o);
    const bool debug = o.pixel_opt->count() > 0;
    if (!debug && o.output.empty()) throw CLI::RequiredError("--output");
    const ImageKind kind = o.output.empty() ? ImageKind::Exr : check_output_path(o.output, "--output");
    if (o.layers && kind != ImageKind::Exr)
        throw InputError(o.output, "--layers", "layers can only be written to an EXR file");
    if (o.format.bits != 0 && kind == ImageKind::Exr)
        throw InputError(o.output, "--bits", "an EXR holds half (--half) or 32-bit floats");
    if (o.format.half && kind != ImageKind::Exr) throw InputError(o.output, "--half", "only EXR outputs are half floats");
    int px = 0, py = 0;
    if (debug) parse_pixel(o.pixel, px, py);
    check_method_options(o, o.method != "differential", debug);
}

int render_loaded(const RenderOptions& o, ImageKind kind, bool debug, int px, int py);

int run_render(const RenderOptions& o) {
    check_render_options(o);
    if (o.range_opt->count()) return run_shard(o);
    const bool debug = o.pixel_opt->count() > 0;
    const ImageKind kind = o.output.empty() ? ImageKind::Exr : check_output_path(o.output, "--output");
    int px = 0, py = 0;
    if (debug) parse_pixel(o.pixel, px, py);
    if (debug && !o.output.empty()) warn("--output is ignored with --pixel; nothing is written");
    const bool standard = o.method != "differential";
    if (standard && o.photons_opt->count())
        warn("--photons is ignored by --method standard (a pass is one path-traced sample per pixel)");

    return reported_under_flags(o, [&] { return render_loaded(o, kind, debug, px, py); });
}

/// The render itself, once the command line is checked: loads the project with the command
/// line's overrides, renders and writes the output.
int render_loaded(const RenderOptions& o, ImageKind kind, bool debug, int px, int py) {
    const bool standard = o.method != "differential";
    return with_threads(o.threads, [&]() -> int {
        LoadedScene loaded = load_scene(
            o.project, [&](Project& p) { apply_overrides(o, p); },
            [&](const Project& p, AssetLibrary& library) {
                if (!debug) check_render_output(o, kind, p, library);  // --pixel writes nothing
            });
        auto scene = loaded.scene;
        if (!standard) check_render_limits(*scene, loaded.settings);  // bad input, exit 2, before any pass
        if (debug) return debug_pixel(scene, loaded.settings, o.project, px, py, o.pass);

        install_interrupt_handler();
        Progress progress;
        CliSink sink(progress);
        RenderSession session(&sink);
        if (standard) {
            const auto sampling = o.method == "standard" ? StandardDifferentialRenderer::Sampling::Independent
                                                         : StandardDifferentialRenderer::Sampling::Correlated;
            const int focus = o.focus_after, spp = o.samples_per_pass;
            session.set_renderer_factory([sampling, focus, spp](std::shared_ptr<const RenderScene> s,
                                                                const RenderSettings& settings) {
                auto r = std::make_unique<StandardDifferentialRenderer>(std::move(s), settings, sampling, spp);
                r->focus_after(focus);
                return r;
            });
        }
        session.start(scene, loaded.settings);
        while (!sink.wait_stopped(std::chrono::milliseconds(100)))
            if (interrupted()) session.cancel();
        session.wait();
        progress.finish();
        if (std::exception_ptr failure = session.failure()) std::rethrow_exception(failure);  // by kind
        if (!sink.error().empty()) throw std::runtime_error("render failed: " + sink.error());

        std::optional<RenderUpdate> last = sink.take_last();
        if (!last) {
            std::cerr << "error: interrupted before the first pass finished; nothing written\n";
            return kInterruptedExit;
        }
        if (sink.cancelled())
            warn("interrupted: writing the " + std::to_string(last->stats.passes) +
                 " passes done so far");
        const double render_s = progress.elapsed();
        write_result(o, kind, loaded, *last);
        const RenderStats& st = last->stats;
        const double skipped =
            st.pixels_total ? 1.0 - double(st.pixels_gathered) / double(st.pixels_total) : 0.0;
        std::printf("wrote %s  passes %d  seconds %.2f  skipped pixels %.3f", o.output.c_str(),
                    st.passes, o.denoise ? render_s : progress.elapsed(), skipped);
        if (o.denoise) std::printf("  denoise seconds %.2f", progress.elapsed() - render_s);
        std::printf("\n");
        if (st.non_finite_samples > 0)
            warn(std::to_string(st.non_finite_samples) + " NaN/Inf samples were discarded");
        return sink.cancelled() ? kInterruptedExit : 0;
    });
}

}  // namespace

Command add_render_command(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* sub = app.add_subcommand("render", "Render the virtual objects into the photo");
    sub->add_option("project", o->project, "Project file (JSON)")->required();
    sub->add_option("-o,--output", o->output,
                    "Output image: .exr (linear, layered) or .png/.jpg/.tif (through the project's display view)");
    o->passes_opt =
        sub->add_option("--passes", o->passes, "Number of passes (overrides the project)")
            ->check(kPositive);
    o->time_opt = sub->add_option("--time", o->time_s, "Render for this many seconds instead")
                      ->check(kTimeBudget)
                      ->excludes(o->passes_opt);
    o->range_opt = sub->add_option("--pass-range", o->pass_range,
                                   "A:B: render only passes A to B-1 (counted from 0) and write their exact "
                                   "sums to a .dpp shard for `diffphoton merge` (docs/farm.md); implies "
                                   "--adaptive off")
                       ->excludes(o->passes_opt)
                       ->excludes(o->time_opt);
    sub->add_option("--adaptive", o->adaptive,
                    "on/off: adaptive sampling (stop converged tiles; default: the project's). Off "
                    "renders every tile in every pass, as merged shards do")
        ->check(CLI::IsMember({"on", "off"}));
    o->photons_opt = sub->add_option("--photons", o->photons, "Photons per pass")
                         ->check(kPositive);
    o->seed_opt = sub->add_option("--seed", o->seed, "Random seed")->check(kSeed);
    o->threads_opt = sub->add_option("--threads", o->threads, "Worker threads (0: all cores)")
                         ->check(kNonNegative);
    o->probe_max_width_opt =
        sub->add_option("--probe-max-width", o->probe_max_width,
                        "Shrink a wider probe to this width on load, its light kept (overrides "
                        "the project's probe.max_width)")
            ->check(CLI::Range(kMinProbeMaxWidth, kMaxProbeMaxWidth));
    sub->add_flag("--layers", o->layers, "EXR only: also write layers dL, alpha and shadow");
    sub->add_flag("--denoise", o->denoise,
                  "Denoise the change with Open Image Denoise: EXR gets layers denoised and "
                  "dL_denoised beside the raw image; PNG/JPEG is the denoised image");
    sub->add_option("--match-plate", o->match_plate,
                    "on/off: give what the render adds the photo's grain and softness (default: the "
                    "project's display.match_plate); EXR gets layers matched and grain, PNG/JPEG/TIFF "
                    "is the matched image")
        ->check(CLI::IsMember({"on", "off"}));
    sub->add_option("--exposure", o->exposure, "PNG/JPEG/TIFF only: exposure in stops")
        ->check(kFinite);
    add_output_format_options(sub, o->format);
    add_force_flag(sub, o->force);
    sub->add_option("--method", o->method,
                    "differential (photon mapping of the change), standard (two independent "
                    "path-traced simulations, without and with the objects; one sample per pixel "
                    "a pass) or standard-correlated (both simulations share each sample's rays)")
        ->check(CLI::IsMember({"differential", "standard", "standard-correlated"}));
    sub->add_option("--samples-per-pass", o->samples_per_pass,
                    "standard methods: camera samples per pixel in each pass (default 1)")
        ->check(CLI::Range(1, 1 << 20));
    sub->add_option("--focus-after", o->focus_after,
                    "standard methods: after this many passes, sample only the pixels the objects "
                    "change (and two pixels around them); for truths with many samples")
        ->check(kNonNegative);
    o->pixel_opt = sub->add_option("--pixel", o->pixel,
                                   "Debug: print one pixel of one pass (X,Y) instead of rendering");
    sub->add_option("--pass", o->pass, "Debug: the pass for --pixel (1-based)")
        ->check(kPositive)
        ->needs(o->pixel_opt);
    return {sub, [o] { return run_render(*o); }, [o] { check_render_options(*o); }};
}

}  // namespace dp::cli
