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
    auto scene = glass_and_clay_scene();
    Image one = render_with_threads(scene, 1, 42);
    Image two = render_with_threads(scene, 2, 42);
    EXPECT_TRUE(one == two);
    Image other_seed = render_with_threads(scene, 2, 43);
    EXPECT_FALSE(one == other_seed);
}
