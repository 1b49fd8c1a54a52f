// The denoiser's cost on the sample project's change at a viewer's and a final picture's size
// (targets: 0.15 s at 480x360 and 0.5 s at 1280x720 on two cores for the interactive quality).
// The render (4 passes at the benchmark size) and the guides are made outside the timing.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "bench_common.h"
#include "image/denoise.h"
#include "image/noise_blend.h"
#include "render/denoise_aovs.h"
#include "render/progressive.h"

namespace dp {
namespace {

/// What one denoise needs: the render's layers and the guides, at width x height.
struct DenoiseInput {
    std::shared_ptr<const RenderScene> scene;
    Image image, alpha, dL, variance;
    DenoiseAovs aovs;
};

const DenoiseInput& input(int width, int height) {
    static std::map<std::pair<int, int>, std::unique_ptr<DenoiseInput>> cache;
    auto& slot = cache[{width, height}];
    if (!slot) {
        Project project = load_project(bench::sample_project_path());
        SceneAssets assets = load_assets(project);
        assets.photo = bench::resize_bilinear(assets.photo, width, height);
        auto in = std::make_unique<DenoiseInput>();
        in->scene = std::make_shared<const RenderScene>(project, std::move(assets));
        ProgressiveRenderer r(in->scene, bench::sample_settings());
        for (int i = 0; i < 4; ++i) r.render_pass();
        in->image = r.image();
        in->alpha = r.alpha_layer();
        in->dL = r.dL_layer();
        in->variance = r.variance_layer();
        in->aovs = denoise_aovs(*in->scene);
        slot = std::move(in);
    }
    return *slot;
}

// denoise_augmented and the blend with the raw picture, as the studio and render --denoise run them.
void BM_DenoiseSample(benchmark::State& state) {
    std::string why;
    if (!denoiser_available(&why)) {
        state.SkipWithError(why.c_str());
        return;
    }
    const int w = int(state.range(0)), h = int(state.range(1));
    const DenoiseQuality quality = state.range(2) ? DenoiseQuality::Final : DenoiseQuality::Interactive;
    const DenoiseInput& in = input(w, h);
    for (auto _ : state) {
        Image d = denoise_augmented(in.scene->photo(), in.image, in.alpha, in.dL, in.aovs.albedo, in.aovs.normal, quality);
        benchmark::DoNotOptimize(blend_by_noise(in.image, d, in.variance));
    }
    state.SetLabel(quality == DenoiseQuality::Final ? "final" : "interactive");
}
BENCHMARK(BM_DenoiseSample)
    ->ArgNames({"w", "h", "final"})
    ->Args({480, 360, 0})
    ->Args({1280, 720, 0})
    ->Args({480, 360, 1})
    ->Args({1280, 720, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->UseRealTime();

}  // namespace
}  // namespace dp
