// A pass depends only on (seed, pass index): thread count must not change a single bit.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "render/progressive.h"
#include "common/test_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {
Image render_with_threads(const std::shared_ptr<RenderScene>& scene, int threads, uint64_t seed) {
    Image out;
    tbb::task_arena arena(threads);
    arena.execute([&] {
        ProgressiveRenderer r(scene, settings(60000, seed));
        for (int i = 0; i < 2; ++i) r.render_pass();
        out = r.image();
    });
    return out;
}
}  // namespace

TEST(Determinism, TheSameSeedGivesTheSameImageWithOneAndTwoThreads) {
    Project p = look_at_project(vec3(0, 2.5f, 4), vec3(0, 0.5f, 0), 45);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.objects.push_back(sphere(vec3(-0.6f, 0.5f, 0), 0.5f, glass(1.5f)));
    p.objects.push_back(sphere(vec3(0.6f, 0.5f, 0), 0.5f, diffuse(vec3(0.8f, 0.3f, 0.2f))));
    Image probe = make_sun_sky_probe(128, 64, glm::normalize(vec3(1, 1.2f, 0.5f)), vec3(3000.0f), 2.0f,
                                     vec3(0.3f, 0.5f, 1.0f), vec3(0.8f, 0.9f, 1.0f));
    auto scene = build(p, Image(80, 60, vec3(0.3f)), probe);
    Image one = render_with_threads(scene, 1, 42);
    Image two = render_with_threads(scene, 2, 42);
    EXPECT_TRUE(one == two);
    Image other_seed = render_with_threads(scene, 2, 43);
    EXPECT_FALSE(one == other_seed);
}
