// Photon throughput on the bundled sample scene: raw Embree rays of the kind the photon tracer
// casts, the tracer itself, and the photon map's build and gather.
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <cmath>
#include <vector>

#include "base/rng.h"
#include "base/sampling.h"
#include "bench_common.h"
#include "render/photon_map.h"
#include "render/photon_tracer.h"
#include "render/progressive.h"
#include "assets/scattering.h"

namespace dp {
namespace {

constexpr int64_t kRayCount = int64_t(1) << 20;
constexpr int64_t kRayBlock = 1024;  // as the tracer's blocks
constexpr uint64_t kSeed = 1;

/// Primary photon rays as trace_photons emits them: a cluster picked by cross-section, a probe
/// direction by importance, a point on the cluster's disk, the origin moved outside every
/// cluster, the ray pointing back at the objects. Precomputed so the benchmark times Embree
/// (and the Hit set-up RenderScene does) alone.
std::vector<Ray> photon_rays(const RenderScene& scene, int64_t count) {
    PhotonEmitter emitter(scene, count);
    std::vector<Ray> rays;
    rays.reserve(size_t(count));
    for (uint64_t i = 0; int64_t(rays.size()) < count; ++i) {
        Rng rng = Rng::keyed(kSeed, 1000, i);
        EmittedPhoton e = emitter.emit(rng);
        if (e.valid) rays.push_back(e.ray);  // the tracer casts nothing for invalid starts
    }
    return rays;
}

const std::vector<Ray>& sample_rays() {
    static const std::vector<Ray> rays = photon_rays(*bench::sample_scene(), kRayCount);
    return rays;
}

/// Five repetitions reported as mean/median/stddev: the machines these run on are shared.
void repeated(benchmark::internal::Benchmark* b) {
    b->Repetitions(5)->ReportAggregatesOnly(true)->UseRealTime()->Unit(benchmark::kMillisecond);
}

void set_thread_counter(benchmark::State& state, tbb::task_arena& arena) {
    state.counters["threads"] = double(arena.max_concurrency());
}

// (a) Embree alone: every precomputed ray is intersected with the virtual and the real BVH
// (rtcIntersect1 through RenderScene), split into blocks over TBB like the tracer.
void BM_EmbreeRaysSampleScene(benchmark::State& state) {
    auto scene = bench::sample_scene();
    const std::vector<Ray>& rays = sample_rays();
    tbb::task_arena arena(bench::arena_threads(state.range(0)));
    const int64_t n = int64_t(rays.size()), blocks = (n + kRayBlock - 1) / kRayBlock;
    std::atomic<uint64_t> hits_virtual{0}, hits_real{0};
    auto body = [&](const tbb::blocked_range<int64_t>& r) {
        uint64_t hv = 0, hr = 0;
        for (int64_t b = r.begin(); b < r.end(); ++b) {
            const int64_t end = std::min(n, (b + 1) * kRayBlock);
            for (int64_t i = b * kRayBlock; i < end; ++i) {
                hv += bool(scene->intersect_virtual(rays[size_t(i)]));
                hr += bool(scene->intersect_real(rays[size_t(i)]));
            }
        }
        hits_virtual += hv;
        hits_real += hr;
    };
    for (auto _ : state) {
        arena.execute([&] { tbb::parallel_for(tbb::blocked_range<int64_t>(0, blocks, 1), body); });
    }
    const double cast = double(n) * double(state.iterations());
    state.counters["rays_per_s"] = bench::rate(2.0 * cast);
    state.counters["virtual_hit_frac"] = double(hits_virtual.load()) / cast;
    state.counters["real_hit_frac"] = double(hits_real.load()) / cast;
    set_thread_counter(state, arena);
}
BENCHMARK(BM_EmbreeRaysSampleScene)->ArgName("threads")->Arg(0)->Arg(1)->Apply(repeated);

// (b) The photon tracer with the sample's photons per pass. rays_per_s counts every Embree query
// the tracer issues (PhotonStats::rays: intersections and occlusion tests, bounces included);
// its ratio to (a)'s rays_per_s is the tracer's overhead over raw Embree.
void BM_PhotonTracingSampleScene(benchmark::State& state) {
    auto scene = bench::sample_scene();
    const int64_t count = bench::sample_settings().photons_per_pass;
    tbb::task_arena arena(bench::arena_threads(state.range(0)));
    PhotonStats total;
    uint64_t pass = 0;
    for (auto _ : state) {
        PhotonPass p;
        // A new pass each iteration, as the renderer does: fresh photons, same cost profile.
        arena.execute([&] { p = trace_photons(*scene, kSeed, ++pass, count); });
        total.emitted += p.stats.emitted;
        total.hit_virtual += p.stats.hit_virtual;
        total.stored_real += p.stats.stored_real;
        total.stored_caustic += p.stats.stored_caustic;
        total.rays += p.stats.rays;
    }
    state.counters["photons_per_s"] = bench::rate(double(total.emitted));
    state.counters["rays_per_s"] = bench::rate(double(total.rays));
    const double emitted = std::max<double>(1, double(total.emitted));
    const double stored = double(total.stored_real + total.stored_caustic);
    state.counters["rays_per_photon"] = double(total.rays) / emitted;
    state.counters["hit_virtual_frac"] = double(total.hit_virtual) / emitted;
    state.counters["stored_per_photon"] = stored / emitted;
    state.counters["photons_per_pass"] = double(count);
    set_thread_counter(state, arena);
}
BENCHMARK(BM_PhotonTracingSampleScene)->ArgName("threads")->Arg(0)->Arg(1)->Apply(repeated);

/// One pass of the sample scene's photons at the renderer's first-pass radius.
struct SamplePhotons {
    PhotonPass pass;
    float radius = 0;
};

const SamplePhotons& sample_photons() {
    static const SamplePhotons s = [] {
        auto scene = bench::sample_scene();
        SamplePhotons out;
        RenderSettings settings = bench::sample_settings();
        settings.seed = kSeed;
        ProgressiveRenderer renderer(scene, settings);
        out.radius = renderer.radius_for_pass(1);
        out.pass = trace_photons(*scene, kSeed, 1, bench::sample_settings().photons_per_pass);
        return out;
    }();
    return s;
}

// (c) PhotonMap::build of the real (signed) photons of one sample pass, in an arena like the
// others since the build may use TBB. The copy of the input and the freeing of the map are left
// out of the timing.
void BM_PhotonMapBuild(benchmark::State& state) {
    auto scene = bench::sample_scene();
    const SamplePhotons& s = sample_photons();
    tbb::task_arena arena(bench::arena_threads(state.range(0)));
    for (auto _ : state) {
        state.PauseTiming();
        std::vector<Photon> photons = s.pass.real;
        PhotonMap map;
        state.ResumeTiming();
        arena.execute([&] { map.build(std::move(photons), s.radius); });
        benchmark::DoNotOptimize(map.size());
        state.PauseTiming();
        map = PhotonMap();
        state.ResumeTiming();
    }
    state.counters["photons"] = double(s.pass.real.size());
    state.counters["photons_per_s"] = bench::rate(double(s.pass.real.size()) * state.iterations());
    set_thread_counter(state, arena);
}
BENCHMARK(BM_PhotonMapBuild)->ArgName("threads")->Arg(0)->Arg(1)->Apply(repeated);

// (c) PhotonMap::gather at the real points the camera sees wherever the map reaches (the pixels
// the renderer gathers), with the sample's first-pass radius, over TBB.
void BM_Gather(benchmark::State& state) {
    auto scene = bench::sample_scene();
    const SamplePhotons& s = sample_photons();
    PhotonMap map;
    map.build(s.pass.real, s.radius);
    struct Query {
        vec3 p, n;
    };
    std::vector<Query> queries;
    const Camera& cam = scene->camera();
    for (int y = 0; y < cam.height(); ++y)
        for (int x = 0; x < cam.width(); ++x) {
            Ray ray = cam.generate_ray(float(x), float(y));
            Hit hit = scene->intersect(ray);
            if (hit && !hit.surface->is_virtual && map.reaches(hit.p))
                queries.push_back({hit.p, facing_normal(hit.ng, ray.dir)});
        }
    tbb::task_arena arena(bench::arena_threads(state.range(0)));
    const int64_t n = int64_t(queries.size());
    auto body = [&](const tbb::blocked_range<int64_t>& r) {
        dvec3 sum(0);
        for (int64_t i = r.begin(); i < r.end(); ++i) {
            const Query& q = queries[size_t(i)];
            sum += map.gather(q.p, q.n);
        }
        benchmark::DoNotOptimize(sum);
    };
    for (auto _ : state) {
        arena.execute([&] { tbb::parallel_for(tbb::blocked_range<int64_t>(0, n, 256), body); });
    }
    state.counters["queries"] = double(n);
    state.counters["gathers_per_s"] = bench::rate(double(n) * state.iterations());
    state.counters["map_photons"] = double(map.size());
    set_thread_counter(state, arena);
}
BENCHMARK(BM_Gather)->ArgName("threads")->Arg(0)->Arg(1)->Apply(repeated);

}  // namespace
}  // namespace dp
