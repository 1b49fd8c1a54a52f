// Render shards: passes summed in separate renderers and merged give the bits of one renderer
// that summed them all, because the accumulator's sums are exact (FixedSum).
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>

#include <unistd.h>

#include "base/error.h"
#include "base/fixed_sum.h"
#include "common/test_scenes.h"
#include "render/pass_shard.h"
#include "render/progressive.h"

using namespace dp;
using namespace dp::test;

namespace {

RenderSettings without_adaptive() {
    RenderSettings s = settings(30000, 42);
    s.adaptive_threshold = 0;
    return s;
}

/// Renders passes [first, first + count) (from 1) with `threads` threads.
std::unique_ptr<ProgressiveRenderer> render_passes(const std::shared_ptr<RenderScene>& scene, int first, int count,
                                                   int threads) {
    auto r = std::make_unique<ProgressiveRenderer>(scene, without_adaptive());
    tbb::task_arena arena(threads);
    arena.execute([&] {
        r->start_at_pass(first);
        for (int i = 0; i < count; ++i) r->render_pass();
    });
    return r;
}

bool same_bits(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() &&
           std::memcmp(a.data(), b.data(), a.size() * sizeof(vec3)) == 0;
}

}  // namespace

TEST(FixedSum, TermsOfEveryMagnitudeSumToTheSameBitsInAnyOrderAndGrouping) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> mantissa(-1, 1);
    std::uniform_int_distribution<int> exponent(-50, 30);
    std::vector<double> terms(5000);
    for (double& t : terms) t = std::ldexp(mantissa(rng), exponent(rng));
    FixedSum forward, backward, left, right;
    for (double t : terms) forward.add(t);
    for (auto it = terms.rbegin(); it != terms.rend(); ++it) backward.add(*it);
    for (size_t i = 0; i < terms.size(); ++i) (i % 3 == 0 ? left : right).add(terms[i]);
    left.add(right);
    EXPECT_EQ(forward, backward);
    EXPECT_EQ(forward, left);
}

TEST(FixedSum, HoldsAFloatSampleExactlyAndCancelsItExactly) {
    for (float v : {1.2345e-3f, -7.5e4f, 3.0e-12f, 0.1f}) {
        FixedSum s;
        s.add(v);
        EXPECT_EQ(s.value(), double(v)) << v;
        s.add(-double(v));
        EXPECT_TRUE(s.zero()) << v;
    }
    FixedSum huge;
    huge.add(1e300);  // clamped, not wrapped
    EXPECT_EQ(huge.value(), FixedSum::kMax);
}

TEST(RenderShards, PassesSplitAcrossRenderersMergeToTheSingleRenderBitForBit) {
    auto scene = glass_and_clay_scene();
    const auto whole = render_passes(scene, 1, 7, 2);
    // Uneven shards, each at another thread count: passes 1-2, 3 and 4-7.
    const auto a = render_passes(scene, 1, 2, 1);
    const auto b = render_passes(scene, 3, 1, 2);
    const auto c = render_passes(scene, 4, 4, 1);
    TileAccumulator merged(whole->accumulator().width(), whole->accumulator().height(),
                           whole->accumulator().tile_size());
    for (const auto* r : {c.get(), a.get(), b.get()}) merged.merge(r->accumulator());
    EXPECT_EQ(merged.passes(), 7);
    EXPECT_TRUE(same_bits(whole->image(), accumulated_image(scene->photo(), merged)));
    EXPECT_TRUE(same_bits(whole->dL_layer(), accumulated_dL(merged)));
    EXPECT_TRUE(same_bits(whole->alpha_layer(), accumulated_alpha(merged)));
    EXPECT_FALSE(same_bits(whole->image(), a->image()));  // the shards do differ
}

TEST(RenderShards, ARendererWithAdaptiveSamplingRefusesToStartAtALaterPass) {
    ProgressiveRenderer r(glass_and_clay_scene(), settings(1000, 1));
    EXPECT_THROW(r.start_at_pass(5), std::logic_error);
}

TEST(RenderShards, AShardFileReadsBackToTheSameSumsAndATruncatedOneIsRefused) {
    auto scene = glass_and_clay_scene();
    const auto r = render_passes(scene, 3, 2, 2);
    ShardHeader h;
    h.project_hash = "p";
    h.inputs_hash = "i";
    h.seed = 42;
    h.pass_begin = 2;
    h.pass_end = 4;
    h.width = r->accumulator().width();
    h.height = r->accumulator().height();
    h.tile = r->accumulator().tile_size();
    const auto dir = std::filesystem::temp_directory_path() / ("dp_shard_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "part.dpp").string();
    write_shard(path, h, r->accumulator());
    const Shard back = read_shard(path);
    EXPECT_EQ(back.header.pass_begin, 2);
    EXPECT_EQ(back.header.seed, 42u);
    EXPECT_TRUE(same_bits(r->image(), accumulated_image(scene->photo(), back.sums)));
    EXPECT_TRUE(same_bits(r->dL_layer(), accumulated_dL(back.sums)));

    const auto size = std::filesystem::file_size(path);
    std::filesystem::resize_file(path, size - 100);
    EXPECT_THROW(read_shard(path), InputError);
    std::filesystem::remove_all(dir);
}

// The sums are allocated by the frame the header declares: a few hundred bytes declaring a frame
// no photo can be, or tiles that are not the renderer's, are refused before that.
TEST(RenderShards, AHeaderDeclaringAFrameNoPhotoCanBeIsRefusedBeforeTheSumsAreAllocated) {
    const auto dir = std::filesystem::temp_directory_path() / ("dp_shard_frame_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "part.dpp").string();
    struct Frame {
        int width, height, tile;
        const char* why;
    };
    for (const Frame& f : {Frame{65536, 65536, 8, "more than the"}, Frame{640, 480, 1, "impossible frame size"},
                           Frame{640, 480, 16, "impossible frame size"}}) {
        ShardHeader h;
        h.pass_begin = 0;
        h.pass_end = 1;
        h.width = f.width;
        h.height = f.height;
        h.tile = f.tile;
        TileAccumulator none(8, 8, 8);  // no tile touched: the file is its header and little else
        none.set_passes(1);
        write_shard(path, h, none);
        EXPECT_LT(std::filesystem::file_size(path), 1000u);
        try {
            read_shard(path);
            ADD_FAILURE() << f.width << " x " << f.height << " in tiles of " << f.tile << " was read";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(f.why), std::string::npos) << e.what();
        }
    }
    std::filesystem::remove_all(dir);
}

TEST(RenderShards, GapsAndOverlapsAreFoundWhateverTheOrder) {
    auto header = [](int b, int e) {
        ShardHeader h;
        h.pass_begin = b;
        h.pass_end = e;
        return h;
    };
    const auto gaps = shard_gaps({header(5, 8), header(0, 2), header(10, 12)});
    ASSERT_EQ(gaps.size(), 2u);
    EXPECT_EQ(gaps[0], std::make_pair(2, 5));
    EXPECT_EQ(gaps[1], std::make_pair(8, 10));
    EXPECT_NO_THROW(check_mergeable({header(4, 8), header(0, 4)}, {"b", "a"}));
    EXPECT_THROW(check_mergeable({header(3, 8), header(0, 4)}, {"b", "a"}), InputError);
}
