#pragma once
// Helpers shared by the benchmarks: the bundled sample scene, thread arenas, peak memory.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>

#include "assets/render_scene.h"
#include "scene/project_io.h"

namespace dp::bench {

/// The bundled sample project; DP_SAMPLE_PROJECT overrides it (e.g. to try another scene).
inline std::string sample_project_path() {
    if (const char* env = std::getenv("DP_SAMPLE_PROJECT"); env && *env) return env;
    return std::string(DP_SOURCE_DIR) + "/resources/sample/sample.json";
}

/// The sample project's render settings (the scene does not keep them).
inline const RenderSettings& sample_settings() {
    static const RenderSettings settings = load_project(sample_project_path()).render;
    return settings;
}

/// The sample's render settings with another photon count (and seed).
inline RenderSettings sample_settings(int64_t photons_per_pass) {
    RenderSettings s = sample_settings();
    s.photons_per_pass = photons_per_pass;
    return s;
}

/// The sample scene exactly as the CLI loads it, built once per process.
inline std::shared_ptr<const RenderScene> sample_scene() {
    static std::shared_ptr<const RenderScene> scene = [] {
        Project project = load_project(sample_project_path());
        SceneAssets assets = load_assets(project);
        return std::make_shared<const RenderScene>(project, std::move(assets));
    }();
    return scene;
}

/// Resamples `src` to width x height with bilinear filtering (pixel centres aligned); a look-at
/// camera's intrinsics follow the new image size.
inline Image resize_bilinear(const Image& src, int width, int height) {
    Image out(width, height);
    const float sx = float(src.width()) / width, sy = float(src.height()) / height;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            out.at(x, y) = src.bilinear((x + 0.5f) * sx - 0.5f, (y + 0.5f) * sy - 0.5f);
    return out;
}

/// A counter reported per second of wall time (the benchmarks use UseRealTime()).
inline benchmark::Counter rate(double count) {
    return benchmark::Counter(count, benchmark::Counter::kIsRate);
}

/// Threads for a benchmark argument: 0 means the project's setting (0 there: all cores), as
/// RenderSession does; anything else is an explicit count.
inline int arena_threads(int64_t arg) {
    int t = arg > 0 ? int(arg) : sample_settings().threads;
    return t > 0 ? t : tbb::task_arena::automatic;
}

/// Reads a "Name:   123 kB" line of /proc/self/status, in bytes (0 if unavailable).
inline double proc_status_bytes(const char* name) {
    std::ifstream in("/proc/self/status");
    std::string line, key = std::string(name) + ":";
    while (std::getline(in, line)) {
        if (line.compare(0, key.size(), key) == 0)
            return std::strtod(line.c_str() + key.size(), nullptr) * 1024.0;
    }
    return 0;
}

/// Peak resident set size of the process so far.
inline double peak_rss_bytes() { return proc_status_bytes("VmHWM"); }

/// Resets VmHWM to the current RSS (Linux >= 4.0) so a benchmark reports its own peak rather
/// than an earlier benchmark's; returns false where the kernel refuses.
inline bool reset_peak_rss() {
    std::ofstream out("/proc/self/clear_refs");
    out << "5";
    out.flush();
    return bool(out);
}

}  // namespace dp::bench
