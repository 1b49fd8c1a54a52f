#pragma once
#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <tbb/task_arena.h>

#include "base/threads.h"
#include "image/display_transform.h"
#include "image/image.h"
#include "image/image_io.h"
#include "assets/asset_library.h"
#include "assets/render_scene.h"
#include "scene/project.h"

namespace dp::cli {

/// Validator for floating-point flags: rejects nan and inf, which CLI11 parses happily.
extern const CLI::Validator kFinite;
/// Finite and > 0, or finite and >= 0, with readable messages.
extern const CLI::Validator kPositive;
/// A random seed: a whole number in [0, 2^64).
extern const CLI::Validator kSeed;
extern const CLI::Validator kNonNegative;
/// The longest --time a render takes: a year, in seconds.
inline constexpr double kMaxTimeBudget = 365.0 * 24 * 3600;
/// A time budget in seconds: > 0 and at most kMaxTimeBudget.
extern const CLI::Validator kTimeBudget;

/// Prints "warning: <text>" to stderr.
void warn(const std::string& text);

/// Runs `work` inside a TBB arena of `threads` workers; `threads` <= 0 leaves TBB's default.
template <class F>
auto with_threads(int threads, F&& work) {
    if (threads <= 0) return work();
    if (threads > hardware_threads())
        warn("--threads " + std::to_string(threads) + " is more than the " + std::to_string(hardware_threads()) +
             " cores of this machine; using " + std::to_string(hardware_threads()));
    tbb::task_arena arena(worker_threads(threads));
    return arena.execute(std::forward<F>(work));
}

/// A compiled scene, and the project as loaded (its render settings are not in the scene).
struct LoadedScene {
    std::shared_ptr<RenderScene> scene;
    Project project;
    RenderSettings settings;
};

/// Loads a project and every file it names, lets `edit` override settings, builds the scene
/// and checks it (check_scene). `before_build` sees the project (and the library the scene is
/// built from) before any file but the project is decoded: commands check their outputs there
/// (check_outputs), so a refusal costs no loading. Asset and scene warnings go to stderr.
/// Throws InputError.
LoadedScene load_scene(const std::string& project_path, const std::function<void(Project&)>& edit = {},
                       const std::function<void(const Project&, AssetLibrary&)>& before_build = {});

enum class ImageKind { Exr, Ldr };

/// The kind of output image `path` names by its extension: .exr, or .png, .jpg, .jpeg, .tif or
/// .tiff; checked first, so that a typo does not cost a render. Throws InputError naming the
/// path and `option`. Where it may be written is check_outputs' (outputs.h).
ImageKind check_output_path(const std::string& path, const std::string& option);

/// Replaces NaN/Inf channels by 0 and warns (naming `path` and `layer`) if there were any.
size_t sanitize(Image& image, const std::string& path, const std::string& layer);

/// How an output image is encoded (`--view`, `--look`, `--bits`, `--half`, `--quality`).
struct OutputFormat {
    std::string view, look;  ///< "" : the project's display view (or Standard)
    int bits = 0;            ///< PNG 8 or 16, TIFF 8, 16 or 32 (linear float); 0: the format's default
    bool half = false;       ///< EXR in half floats
    int quality = 95;        ///< JPEG
};
/// Adds the OutputFormat options to a command.
void add_output_format_options(CLI::App* sub, OutputFormat& format);
/// The writer's options for `format` with `metadata` (name, value) for the file's header.
ImageWriteOptions write_options(const OutputFormat& format,
                                std::vector<std::pair<std::string, std::string>> metadata = {});
/// The view for a display output: `format`'s, else `fallback`'s (a project's display), with
/// `exposure` stops. Throws InputError for an unknown view or look.
DisplayTransform output_view(const OutputFormat& format, float exposure, const ViewSettings& fallback = {});

/// What a render's output header says of how it was made (project file name, passes, seed),
/// after the plate's camera data (read_image_metadata). `render` and `merge` write the same.
std::vector<std::pair<std::string, std::string>> render_metadata(const Project& project,
                                                                 const std::string& project_path, int passes,
                                                                 uint64_t seed);

/// The project's display view and look (exposure 0: outputs are at 0 EV unless asked).
ViewSettings project_view(const Project& project);

/// Writes `image` (after sanitize) as a single-layer EXR, or as PNG/JPEG/TIFF through `view`
/// (exposure included) with negative values clamped to 0. The command has checked `path`
/// (check_outputs) before its work.
void write_image(const std::string& path, Image image, const DisplayTransform& view, const ImageWriteOptions& options = {});

/// Ctrl-C: the first one asks long commands to stop (they check interrupted()), a second one
/// kills the process as usual, removing the temporary file of an output being written (the
/// output itself keeps its old content).
void install_interrupt_handler();
bool interrupted();
const std::atomic<bool>* interrupt_flag();
/// Exit code after an interrupt (128 + SIGINT, as shells report it).
inline constexpr int kInterruptedExit = 130;

/// "1.2e6": compact scientific notation without the "+0" of printf's %e.
std::string sci(double v);
/// "2.1s", "3m05s" or "1h02m".
std::string duration(double seconds);
/// "(0.5, 0.5, 0.5)".
std::string vec(const vec3& v);

}  // namespace dp::cli
