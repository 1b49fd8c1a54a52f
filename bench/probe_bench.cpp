// Cost of one call of the probe's importance sampling and lookups, single thread, on a real
// HDR map (Blender's city studio light) or, where Blender is not installed, on a synthetic sky.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "base/euler.h"
#include "base/rng.h"
#include "image/image_io.h"
#include "probe/probe.h"
#include "probe/synthetic_probe.h"

namespace dp {
namespace {

/// Directions kept for pdf() and radiance(): 12 MiB, streamed in order.
constexpr size_t kDirections = size_t(1) << 20;

const Probe& bench_probe() {
    static const Probe probe = [] {
        const std::string path = "/usr/share/blender/datafiles/studiolights/world/city.exr";
        Image img = std::filesystem::exists(path)
                        ? load_image(path, "probe")
                        : make_sun_sky_probe(2048, 1024, vec3(0.3f, 0.8f, -0.5f),
                                             vec3(1e5f), 0.5f, vec3(0.3f, 0.5f, 1.0f),
                                             vec3(0.9f, 0.9f, 1.0f));
        return Probe(std::move(img), euler_xyz_deg(vec3(10, 40, 0)), 1.5f);
    }();
    return probe;
}

/// World directions the probe would return, for pdf() and radiance().
const std::vector<vec3>& directions() {
    static const std::vector<vec3> dirs = [] {
        const Probe& probe = bench_probe();
        std::vector<vec3> d(kDirections);
        Rng rng(5, 17);
        for (vec3& x : d) x = probe.sample(rng.uniform(), rng.uniform(), rng.uniform()).dir;
        return d;
    }();
    return dirs;
}

void set_map_counters(benchmark::State& state, const Probe& probe) {
    state.counters["width"] = probe.width();
    state.counters["height"] = probe.height();
    state.SetItemsProcessed(state.iterations());
}

/// Independent calls: the time per iteration is the ns per sample, drawing its three numbers
/// included. They are drawn in the loop, as the tracer does, rather than read from a table that
/// would compete with the probe for the cache.
void BM_ProbeSample(benchmark::State& state) {
    const Probe& probe = bench_probe();
    Rng rng(9, 9);
    for (auto _ : state) {
        const float u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        ProbeSample s = probe.sample(u0, u1, u2);
        benchmark::DoNotOptimize(s);
    }
    set_map_counters(state, probe);
}
BENCHMARK(BM_ProbeSample);

/// Each call waits for the one before (its first number depends on the previous pixel), as in
/// a tracer that needs a photon's direction before it moves on: latency rather than throughput.
void BM_ProbeSampleChained(benchmark::State& state) {
    const Probe& probe = bench_probe();
    Rng rng(9, 9);
    size_t previous = 0;
    for (auto _ : state) {
        const uint32_t bits = (rng.next_u32() >> 8) ^ uint32_t(previous & 1);
        const float u0 = float(bits) * 0x1p-24f, u1 = rng.uniform(), u2 = rng.uniform();
        ProbeSample s = probe.sample(u0, u1, u2);
        benchmark::DoNotOptimize(s);
        previous = s.pixel;
    }
    set_map_counters(state, probe);
}
BENCHMARK(BM_ProbeSampleChained);

void BM_ProbePdf(benchmark::State& state) {
    const Probe& probe = bench_probe();
    const std::vector<vec3>& d = directions();
    size_t k = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(probe.pdf(d[k]));
        k = (k + 1) & (kDirections - 1);
    }
    set_map_counters(state, probe);
}
BENCHMARK(BM_ProbePdf);

void BM_ProbeRadiance(benchmark::State& state) {
    const Probe& probe = bench_probe();
    const std::vector<vec3>& d = directions();
    size_t k = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(probe.radiance(d[k]));
        k = (k + 1) & (kDirections - 1);
    }
    set_map_counters(state, probe);
}
BENCHMARK(BM_ProbeRadiance);

}  // namespace
}  // namespace dp
