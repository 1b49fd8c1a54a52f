// One progressive pass of the sample project at 1920x1080 with a million photons: the product's
// interactive-rate promise (under 1 s per pass on a 2-core machine, under 1 GiB resident).
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <memory>
#include <vector>

#include "base/rng.h"
#include "bench_common.h"
#include "render/photon_tracer.h"
#include "render/progressive.h"
#include "render/camera_gather.h"

namespace dp {
namespace {

constexpr int kWidth = 1920, kHeight = 1080;
constexpr int64_t kPhotonsPerPass = 1'000'000;
constexpr int kPass = 1;  // the first pass: largest radius, fewest skipped pixels

/// The sample project with its photograph resampled to 1080p. The camera is look-at, so its
/// intrinsics follow the new image size.
std::shared_ptr<const RenderScene> scene_1080p() {
    static std::shared_ptr<const RenderScene> scene = [] {
        Project project = load_project(bench::sample_project_path());
        SceneAssets assets = load_assets(project);
        assets.photo = bench::resize_bilinear(assets.photo, kWidth, kHeight);
        return std::make_shared<const RenderScene>(project, std::move(assets));
    }();
    return scene;
}

// ProgressiveRenderer::render_pass for pass 1 (the largest gather radius, so the fewest skipped
// pixels): photon tracing, both map builds, the gather over the image, accumulation. Each
// repetition uses a fresh renderer; its per-camera pixel cache is built outside the timing.
void BM_OnePass1080p(benchmark::State& state) {
    // Report this benchmark's own peak, not that of whatever ran earlier in the process.
    const bool reset = bench::reset_peak_rss();
    auto scene = scene_1080p();
    tbb::task_arena arena(bench::arena_threads(0));
    std::unique_ptr<ProgressiveRenderer> renderer;
    arena.execute([&] {
        renderer = std::make_unique<ProgressiveRenderer>(scene, bench::sample_settings(kPhotonsPerPass));
    });
    for (auto _ : state) arena.execute([&] { renderer->render_pass(); });
    const RenderStats& st = renderer->stats();
    state.counters["skipped_fraction"] = renderer->skipped_fraction();
    state.counters["peak_rss_bytes"] = bench::peak_rss_bytes();
    state.counters["peak_rss_reset"] = reset ? 1 : 0;
    state.counters["photons_per_s"] = st.photons_per_second;
    state.counters["photons_stored"] = double(st.photons_stored) / st.passes;
    state.counters["width"] = scene->photo().width();
    state.counters["height"] = scene->photo().height();
    state.counters["threads"] = double(arena.max_concurrency());
}
BENCHMARK(BM_OnePass1080p)
    ->Iterations(1)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// The same pass with the renderer's own phase timers (RenderStats): photon tracing, map
// builds, marking the pixels the photons reach and picking the tiles, shading the tiles, and
// adding them up (with the convergence check).
void BM_OnePass1080pPhases(benchmark::State& state) {
    auto scene = scene_1080p();
    tbb::task_arena arena(bench::arena_threads(0));
    RenderStats sum;
    double tiles = 0, pixels = 0;
    for (auto _ : state) {
        arena.execute([&] {
            state.PauseTiming();
            ProgressiveRenderer r(scene, bench::sample_settings(kPhotonsPerPass));
            state.ResumeTiming();
            r.render_pass();
            const RenderStats& st = r.stats();
            sum.trace_s += st.trace_s;
            sum.maps_s += st.maps_s;
            sum.mark_s += st.mark_s;
            sum.shade_s += st.shade_s;
            sum.accumulate_s += st.accumulate_s;
            tiles += double(st.tiles_shaded);
            pixels += double(st.pixels_gathered);
        });
    }
    const double it = double(state.iterations());
    state.counters["trace_s"] = sum.trace_s / it;
    state.counters["maps_s"] = sum.maps_s / it;
    state.counters["mark_s"] = sum.mark_s / it;
    state.counters["shade_s"] = sum.shade_s / it;
    state.counters["accumulate_s"] = sum.accumulate_s / it;
    state.counters["tiles_shaded"] = tiles / it;
    state.counters["pixels_shaded"] = pixels / it;
    state.counters["threads"] = double(arena.max_concurrency());
}
BENCHMARK(BM_OnePass1080pPhases)
    ->Iterations(1)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dp
