#include "common.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "assets/asset_library.h"
#include "assets/scene_checks.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/text.h"
#include "image/image_io.h"
#include "scene/project_io.h"

namespace dp::cli {

namespace fs = std::filesystem;

const CLI::Validator kFinite(
    [](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v))
            return "value " + text + " is not a finite number";
        return {};
    },
    "FINITE");

namespace {

/// A number check whose message a person can read (CLI11's own prints the double's range in
/// full, 309 digits).
CLI::Validator number_check(const char* name, bool (*ok)(double), const char* must) {
    return CLI::Validator(
        [ok, must](std::string& text) -> std::string {
            double v = 0;
            if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v))
                return "value " + text.substr(0, 40) + " is not a finite number";
            if (!ok(v)) return "value " + text.substr(0, 40) + " must be " + must;
            return {};
        },
        name);
}

}  // namespace

const CLI::Validator kSeed(
    [](std::string& text) -> std::string {
        // CLI11 would wrap "-1" into 2^64 - 1 without a word.
        if (text.empty() || text.size() > 20 || text.find_first_not_of("0123456789") != std::string::npos)
            return "seed " + text.substr(0, 40) + " must be a whole number from 0 to 18446744073709551615";
        if (text.size() == 20 && text > "18446744073709551615")
            return "seed " + text + " is more than 18446744073709551615";
        return {};
    },
    "SEED");

const CLI::Validator kPositive = number_check("POSITIVE", [](double v) { return v > 0; }, "greater than 0");
const CLI::Validator kNonNegative = number_check("NONNEGATIVE", [](double v) { return v >= 0; }, "0 or more");
const CLI::Validator kTimeBudget = number_check(
    "SECONDS", [](double v) { return v > 0 && v <= kMaxTimeBudget; }, "greater than 0 and at most 31536000 (a year)");

void warn(const std::string& text) { std::cerr << "warning: " << text << "\n"; }

LoadedScene load_scene(const std::string& project_path, const std::function<void(Project&)>& edit,
                       const std::function<void(const Project&, AssetLibrary&)>& before_build) {
    Project project = load_project(project_path);
    if (edit) edit(project);
    AssetLibrary library;
    if (before_build) before_build(project, library);
    auto scene = build_scene(library, project, 0, 0, project_path);
    for (const std::string& w : scene->assets().warnings) warn(w);
    return {scene, project, project.render};
}

ImageKind check_output_path(const std::string& path, const std::string& option) {
    if (path.empty()) throw InputError(path, option, "no output file given");
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) {
        return char(std::tolower(c));
    });
    if (ext == ".exr") return ImageKind::Exr;
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tif" || ext == ".tiff") return ImageKind::Ldr;
    throw InputError(path, option, "unknown output format '" + ext + "' (use .exr, .png, .jpg, .jpeg, .tif or .tiff)");
}

size_t sanitize(Image& image, const std::string& path, const std::string& layer) {
    const size_t replaced = replace_non_finite(image);
    if (replaced > 0)
        warn(shorten_path(path) + ": " + std::to_string(replaced) + " NaN/Inf values in layer '" + layer +
             "' replaced by 0 before writing");
    return replaced;
}

void add_output_format_options(CLI::App* sub, OutputFormat& f) {
    sub->add_option("--view", f.view,
                    "View transform of PNG/JPEG/TIFF outputs: Standard (exact sRGB, the default), Raw, or a "
                    "view of the OpenColorIO config (Filmic, Filmic Log, False Color with Blender's)");
    sub->add_option("--look", f.look, "OpenColorIO look applied before the view (e.g. \"High Contrast\")");
    sub->add_option("--bits", f.bits, "Bits per channel: PNG 8 or 16, TIFF 8, 16 or 32 (32: linear float)")
        ->check(CLI::IsMember({8, 16, 32}));
    sub->add_flag("--half", f.half, "EXR outputs in half floats (16 bits) instead of 32-bit floats");
    sub->add_option("--quality", f.quality, "JPEG quality, 1 to 100")->check(CLI::Range(1, 100));
}

ImageWriteOptions write_options(const OutputFormat& f, std::vector<std::pair<std::string, std::string>> metadata) {
    ImageWriteOptions options;
    options.format = f.bits == 8    ? SampleFormat::U8
                     : f.bits == 16 ? SampleFormat::U16
                     : f.bits == 32 ? SampleFormat::Float
                     : f.half       ? SampleFormat::Half
                                    : SampleFormat::Default;
    options.jpeg_quality = f.quality;
    options.metadata = std::move(metadata);
    return options;
}

DisplayTransform output_view(const OutputFormat& f, float exposure, const ViewSettings& fallback) {
    ViewSettings settings = fallback;
    if (!f.view.empty()) settings.view = f.view;
    if (!f.look.empty() || !f.view.empty()) settings.look = f.look;
    settings.exposure = exposure;
    try {
        return DisplayTransform(settings);
    } catch (const InputError& e) {
        throw InputError("", "--" + e.field(), e.what());
    }
}

std::vector<std::pair<std::string, std::string>> render_metadata(const Project& project,
                                                                 const std::string& project_path, int passes,
                                                                 uint64_t seed) {
    auto m = read_image_metadata(project.resolve(project.photo.path).string());
    m.emplace_back("diffphoton:project", fs::path(project_path).filename().string());
    m.emplace_back("diffphoton:passes", std::to_string(passes));
    m.emplace_back("diffphoton:seed", std::to_string(seed));
    return m;
}

ViewSettings project_view(const Project& project) {
    ViewSettings v;
    v.view = project.display.view;
    v.look = project.display.look;
    return v;
}

void write_image(const std::string& path, Image image, const DisplayTransform& view, const ImageWriteOptions& options) {
    const ImageKind kind = check_output_path(path, "output");
    sanitize(image, path, "main");
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (kind == ImageKind::Exr) {
        if (options.format != SampleFormat::Default && options.format != SampleFormat::Half &&
            options.format != SampleFormat::Float)
            throw InputError(path, "--bits", "an EXR holds half (--half) or 32-bit floats");
        save_exr(path, {{"", &image}}, options);
        return;
    }
    if (ext == ".jpg" || ext == ".jpeg") {
        if (options.format != SampleFormat::Default && options.format != SampleFormat::U8)
            throw InputError(path, "--bits", "a JPEG holds 8 bits per channel");
    } else if (ext == ".png" && options.format != SampleFormat::Default && options.format != SampleFormat::U8 &&
               options.format != SampleFormat::U16) {
        throw InputError(path, "--bits", "a PNG holds 8 or 16 bits per channel");
    }
    if (options.format == SampleFormat::Half) throw InputError(path, "--half", "only EXR outputs are half floats");
    for (size_t i = 0; i < image.size(); ++i) image[i] = glm::max(image[i], vec3(0.0f));
    save_display_image(path, image, view, options);
}

namespace {

std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "used from a signal handler");

extern "C" void on_interrupt(int) {
    if (!g_interrupted.exchange(true)) return;  // the first asks the command to stop
    // A second Ctrl-C ends the process at once, as usual; an output being written keeps its
    // old content (writes are atomic) and the half-written temporary file goes with us.
    remove_temporaries_in_flight();
    std::signal(SIGINT, SIG_DFL);
    std::raise(SIGINT);
}

}  // namespace

void install_interrupt_handler() { std::signal(SIGINT, on_interrupt); }
bool interrupted() { return g_interrupted.load(); }
const std::atomic<bool>* interrupt_flag() { return &g_interrupted; }

std::string sci(double v) {
    if (!std::isfinite(v)) return "?";
    if (v == 0) return "0";
    int exponent = int(std::floor(std::log10(std::abs(v))));
    double mantissa = v / std::pow(10.0, exponent);
    if (std::abs(mantissa) >= 9.95) {  // 9.97e5 rounds to 10.0e5
        mantissa /= 10;
        ++exponent;
    }
    char buf[32];
    if (exponent >= -2 && exponent <= 3)
        std::snprintf(buf, sizeof(buf), "%.3g", v);
    else
        std::snprintf(buf, sizeof(buf), "%.1fe%d", mantissa, exponent);
    return buf;
}

std::string duration(double seconds) {
    char buf[32];
    if (!std::isfinite(seconds) || seconds < 0) return "?";
    // Beyond this, hours no longer fit the counters below; no render lasts that long.
    if (seconds >= 1e9) return ">30 years";
    if (seconds < 60) {
        std::snprintf(buf, sizeof(buf), "%.1fs", seconds);
    } else if (seconds < 3600) {
        long s = std::lround(seconds);
        std::snprintf(buf, sizeof(buf), "%ldm%02lds", s / 60, s % 60);
    } else {
        long m = std::lround(seconds / 60);
        std::snprintf(buf, sizeof(buf), "%ldh%02ldm", m / 60, m % 60);
    }
    return buf;
}

std::string vec(const vec3& v) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "(%g, %g, %g)", v.x, v.y, v.z);
    return buf;
}

}  // namespace dp::cli
