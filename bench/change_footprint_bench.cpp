// Work that follows the change: one clay ball on the sample's floor, at 1920x1080 and
// 3840x2160, with radii 0.4, 0.1 and 0.025 m, 300,000 photons a pass. A pass should cost its
// photon tracing plus work in proportion to the pixels the ball can change, not to the frame.
#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <map>
#include <memory>
#include <vector>

#include "bench_common.h"
#include "render/progressive.h"

namespace dp {
namespace {

constexpr int64_t kPhotons = 300000;
constexpr int kPasses = 7;  ///< the first is left out of the medians (largest radius)

/// The sample project with one clay ball of radius r on its floor, its photo resampled.
std::shared_ptr<const RenderScene> ball_scene(float radius, int width, int height) {
    static std::map<std::tuple<float, int, int>, std::shared_ptr<const RenderScene>> cache;
    auto& slot = cache[{radius, width, height}];
    if (slot) return slot;
    Project project = load_project(bench::sample_project_path());
    project.objects.resize(1);
    VirtualObject& ball = project.objects[0];
    ball.shape.kind = Shape::Kind::Sphere;
    ball.shape.radius = radius;
    ball.transform.translation = vec3(-1.05f, radius, 0.15f);
    ball.material.kind = Material::Kind::Diffuse;
    ball.material.albedo.rgb = vec3(0.75f, 0.18f, 0.12f);
    SceneAssets assets = load_assets(project);
    assets.photo = bench::resize_bilinear(assets.photo, width, height);
    slot = std::make_shared<const RenderScene>(project, std::move(assets));
    return slot;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

/// Args: radius in mm, image height (1080 or 2160).
void BM_WorkFollowsTheChange(benchmark::State& state) {
    const float radius = float(state.range(0)) * 1e-3f;
    const int height = int(state.range(1)), width = height * 16 / 9;
    auto scene = ball_scene(radius, width, height);
    tbb::task_arena arena(bench::arena_threads(0));
    std::vector<double> pass_s, trace_s, shaded, tiles, direct, shade_s, mark_s;
    double skipped = 0;
    for (auto _ : state) {
        arena.execute([&] {
            ProgressiveRenderer r(scene, bench::sample_settings(kPhotons));
            for (int p = 0; p < kPasses; ++p) {
                const double before = r.stats().seconds;
                r.render_pass();
                if (p == 0) continue;
                const RenderStats& st = r.stats();
                pass_s.push_back(st.seconds - before);
                trace_s.push_back(st.trace_s);
                shaded.push_back(double(st.pixels_gathered));
                tiles.push_back(double(st.tiles_shaded));
                direct.push_back(double(st.direct_estimates));
                shade_s.push_back(st.shade_s);
                mark_s.push_back(st.mark_s);
            }
            skipped = r.skipped_fraction();
        });
        state.SetIterationTime(median(pass_s));
    }
    state.counters["pass_s"] = median(pass_s);
    state.counters["trace_s"] = median(trace_s);
    state.counters["pass_over_trace"] = median(pass_s) / std::max(1e-9, median(trace_s));
    state.counters["pixels_shaded"] = median(shaded);
    state.counters["tiles_shaded"] = median(tiles);
    state.counters["direct_estimates"] = median(direct);
    state.counters["shade_s"] = median(shade_s);
    state.counters["mark_s"] = median(mark_s);
    state.counters["skipped_fraction"] = skipped;
    state.counters["width"] = width;
}
BENCHMARK(BM_WorkFollowsTheChange)
    ->ArgsProduct({{400, 100, 25}, {1080, 2160}})
    ->Iterations(1)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dp
