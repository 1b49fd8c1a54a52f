// One progressive pass of the sample project at 1920x1080 with a million photons: the product's
// interactive-rate promise (under 1 s per pass on a 2-core machine, under 1 GiB resident).
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <vector>

#include "base/rng.h"
#include "bench_common.h"
#include "render/photon_tracer.h"
#include "render/pixel_cache.h"
#include "render/progressive.h"
#include "render/shading.h"

namespace dp {
namespace {

constexpr int kWidth = 1920, kHeight = 1080;
constexpr int64_t kPhotonsPerPass = 1'000'000;
constexpr int kPass = 1;  // the first pass: largest radius, fewest skipped pixels

/// Resamples `src` to width x height with bilinear filtering (pixel centres aligned).
Image resize_bilinear(const Image& src, int width, int height) {
    Image out(width, height);
    const float sx = float(src.width()) / width, sy = float(src.height()) / height;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            out.at(x, y) = src.bilinear((x + 0.5f) * sx - 0.5f, (y + 0.5f) * sy - 0.5f);
    return out;
}

/// The sample project with its photograph resampled to 1080p. The camera is look-at, so its
/// intrinsics follow the new image size.
std::shared_ptr<const RenderScene> scene_1080p() {
    static std::shared_ptr<const RenderScene> scene = [] {
        Project project = load_project(bench::sample_project_path());
        SceneAssets assets = load_assets(project);
        assets.photo = resize_bilinear(assets.photo, kWidth, kHeight);
        return std::make_shared<const RenderScene>(project, std::move(assets));
    }();
    return scene;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// ProgressiveRenderer::render_pass for pass 1 (the largest gather radius, so the fewest skipped
// pixels): photon tracing, both map builds, the gather over the image, accumulation. Each
// repetition uses a fresh renderer; its per-camera pixel cache is built outside the timing.
void BM_OnePass1080p(benchmark::State& state) {
    // Report this benchmark's own peak, not that of whatever ran earlier in the process.
    const bool reset = bench::reset_peak_rss();
    auto scene = scene_1080p();
    tbb::task_arena arena(bench::arena_threads(*scene, 0));
    const uint64_t seed = scene->project().render.seed;
    std::unique_ptr<ProgressiveRenderer> renderer;
    arena.execute([&] {
        renderer = std::make_unique<ProgressiveRenderer>(scene, kPhotonsPerPass, seed);
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

/// What the camera's centre ray sees per pixel, as ProgressiveRenderer caches it.


/// Runs body(pixel index, x, y) over the image in blocks of rows, as shade_pass does; returns
/// the sum of what it returned.
template <class Body>
size_t count_over_rows(int W, int H, const Body& body) {
    std::atomic<size_t> count{0};
    tbb::parallel_for(tbb::blocked_range<int>(0, H, 4), [&](const tbb::blocked_range<int>& r) {
        size_t local = 0;
        for (int y = r.begin(); y < r.end(); ++y)
            for (int x = 0; x < W; ++x) local += body(size_t(y) * W + x, x, y);
        count += local;
    });
    return count.load();
}

// The same pass as BM_OnePass1080p rebuilt from the public API with a timer around each phase,
// to show where the time goes. The shading phase is split by pixel class: pixels near a
// virtual object (camera ray, next-event estimation, bounce, caustic gather) and real pixels
// whose cell the photon map reaches (camera ray, one gather). `skip_test_s` is the cost of the
// skip test alone (reaches() for every pixel), included in the two shading figures.
void BM_OnePass1080pPhases(benchmark::State& state) {
    auto scene = scene_1080p();
    const RenderScene& s = *scene;
    tbb::task_arena arena(bench::arena_threads(s, 0));
    const uint64_t seed = s.project().render.seed;
    float radius = 0;
    int diffuse_samples = 0;
    PixelCache cache;
    arena.execute([&] {
        ProgressiveRenderer r(scene, kPhotonsPerPass, seed);
        radius = r.radius_for_pass(kPass);
        diffuse_samples = r.camera_diffuse_samples();
        cache = build_pixel_cache(s);
    });
    const int W = s.photo().width(), H = s.photo().height();
    const size_t n = size_t(W) * H;
    std::vector<dvec3> sum_delta(n, dvec3(0)), sum_dL(n, dvec3(0));
    std::vector<double> sum_alpha(n, 0.0);
    double t_trace = 0, t_build = 0, t_virtual = 0, t_real = 0, t_acc = 0, t_skip = 0;
    size_t px_virtual = 0, px_real = 0;
    for (auto _ : state) {
        arena.execute([&] {
            auto t0 = std::chrono::steady_clock::now();
            PhotonPass photons = trace_photons(s, seed, kPass, kPhotonsPerPass);
            t_trace += seconds_since(t0);

            t0 = std::chrono::steady_clock::now();
            PassMaps maps;
            maps.radius = radius;
            maps.real.build(std::move(photons.real), radius);
            maps.caustic.build(std::move(photons.caustic), radius);
            t_build += seconds_since(t0);

            std::vector<SampleResult> out(n, SampleResult{});
            Shader shader(s, maps, diffuse_samples);
            // Same sample streams as ProgressiveRenderer::shade_pass for pass 1.
            auto shade = [&](size_t i, int x, int y) {
                Rng rng = Rng::keyed(seed, uint64_t(kPass) * 2 + 1, i);
                float jx = rng.uniform() - 0.5f, jy = rng.uniform() - 0.5f;
                out[i] = shader.shade_camera(x, y, float(x) + jx, float(y) + jy, rng);
            };
            auto rows = [&](auto&& body) { return count_over_rows(W, H, body); };

            t0 = std::chrono::steady_clock::now();
            px_virtual += rows([&](size_t i, int x, int y) -> size_t {
                if (!cache.near_virtual[i]) return 0;
                shade(i, x, y);
                return 1;
            });
            t_virtual += seconds_since(t0);

            t0 = std::chrono::steady_clock::now();
            auto reached = [&](size_t i) {
                return cache.has_real[i] && maps.real.reaches(cache.real_point[i]);
            };
            px_real += rows([&](size_t i, int x, int y) -> size_t {
                if (cache.near_virtual[i] || !reached(i)) return 0;
                shade(i, x, y);
                return 1;
            });
            t_real += seconds_since(t0);

            t0 = std::chrono::steady_clock::now();
            for (size_t i = 0; i < n; ++i) {
                const SampleResult& r = out[i];
                if (!is_finite(r.delta) || !is_finite(r.dL) || !std::isfinite(r.alpha)) continue;
                sum_delta[i] += dvec3(r.delta);
                sum_dL[i] += dvec3(r.dL);
                sum_alpha[i] += r.alpha;
            }
            t_acc += seconds_since(t0);

            t0 = std::chrono::steady_clock::now();
            size_t kept = rows([&](size_t i, int, int) -> size_t {
                return cache.near_virtual[i] || reached(i);
            });
            t_skip += seconds_since(t0);
            benchmark::DoNotOptimize(kept);
        });
    }
    const double it = double(state.iterations());
    state.counters["trace_s"] = t_trace / it;
    state.counters["build_s"] = t_build / it;
    state.counters["shade_virtual_s"] = t_virtual / it;
    state.counters["shade_real_s"] = t_real / it;
    state.counters["accumulate_s"] = t_acc / it;
    state.counters["skip_test_s"] = t_skip / it;
    state.counters["pixels_virtual"] = double(px_virtual) / it;
    state.counters["pixels_real_gathered"] = double(px_real) / it;
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
