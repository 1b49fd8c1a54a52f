// Photons per pass set from what they add to the error per unit of work (PhotonBalance): the
// closed form, the variances it measures, and what a render does with it.
#include "render/photon_balance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/test_scenes.h"
#include "render/progressive.h"

using namespace dp;
using namespace dp::test;

TEST(PhotonBalance, TheCountMovesBySquareRootOfTheVarianceAndCostRatios) {
    constexpr int64_t lo = 1000, hi = 1000000;
    // Equal shares of the variance at equal cost: the balance holds.
    EXPECT_EQ(PhotonBalance::next_count(100000, 1.0, 1.0, 5.0, 5.0, lo, hi), 100000);
    // Photons 4x the variance of the rest at equal cost: twice the photons.
    EXPECT_EQ(PhotonBalance::next_count(100000, 4.0, 1.0, 5.0, 5.0, lo, hi), 200000);
    // The same variances with photons 4x as dear: the balance holds again.
    EXPECT_EQ(PhotonBalance::next_count(100000, 4.0, 1.0, 20.0, 5.0, lo, hi), 100000);
    // The rest dominating: fewer photons, by at most kMaxStep a decision.
    EXPECT_EQ(PhotonBalance::next_count(100000, 1.0, 4.0, 5.0, 5.0, lo, hi), 50000);
    EXPECT_EQ(PhotonBalance::next_count(100000, 1.0, 1e6, 5.0, 5.0, lo, hi), 25000);
    EXPECT_EQ(PhotonBalance::next_count(100000, 0.0, 1.0, 5.0, 5.0, lo, hi), 25000);
    // Damped: half the step in log, at most 2.
    EXPECT_EQ(PhotonBalance::next_count(100000, 16.0, 1.0, 5.0, 5.0, lo, hi, true), 200000);
    EXPECT_EQ(PhotonBalance::next_count(100000, 1.0, 4.0, 5.0, 5.0, lo, hi, true), 70711);
    // Within the bounds.
    EXPECT_EQ(PhotonBalance::next_count(2000, 1.0, 1e6, 5.0, 5.0, lo, hi), lo);
    EXPECT_EQ(PhotonBalance::next_count(900000, 1e6, 1.0, 5.0, 5.0, lo, hi), hi);
}

TEST(PhotonBalance, MeasuresEachPartsVarianceOverThePassesOfAWindow) {
    constexpr size_t kPixels = 4000;
    PhotonBalance b(100000, 1000, 1000000, kPixels);
    std::mt19937 rng(3);
    // Photons' part: mean 0.5, sd 0.2; the rest: mean -0.3, sd 0.1 (a variance 4x smaller).
    std::normal_distribution<float> photon(0.5f, 0.2f), rest(-0.3f, 0.1f);
    bool due = false;
    for (int pass = 0; pass < PhotonBalance::kWindow; ++pass) {
        ASSERT_FALSE(due);
        for (size_t i = 0; i < kPixels; ++i) b.add(i, photon(rng), rest(rng));
        // Equal cost: as many photon rays as camera samples are worth.
        due = b.end_pass(uint64_t(PhotonBalance::kRaysPerCameraSample * 1000), 1000);
    }
    ASSERT_TRUE(due);
    const int64_t next = b.decide([](size_t i) { return i % 2 == 0; });
    EXPECT_NEAR(b.photon_share(), 0.8, 0.02);
    EXPECT_NEAR(double(next), 200000.0, 10000.0);
    // A new window starts from nothing: pixels the picker leaves out never count.
    for (int pass = 0; pass < PhotonBalance::kWindow; ++pass) {
        for (size_t i = 0; i < kPixels; ++i) b.add(i, i % 2 ? photon(rng) : 0.5f, rest(rng));
        b.end_pass(uint64_t(PhotonBalance::kRaysPerCameraSample * 1000), 1000);
    }
    b.decide([](size_t i) { return i % 2 == 0; });
    EXPECT_DOUBLE_EQ(b.photon_share(), 0.0);
    // Photons without variance ask for a quarter; a later decision goes half the way (in log).
    EXPECT_EQ(b.photons(), std::llround(double(next) * 0.5));
}

namespace {

/// A ball on a floor under the sun: clay (a change that is almost all direct shadow) or glass
/// (a caustic, which only photons carry).
std::shared_ptr<RenderScene> sun_scene(const Material& ball) {
    SunProbe sun;
    Project p = look_at_project(vec3(0, 3, 4), vec3(0, 0.5f, 0), 45);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.objects.push_back(sphere(vec3(0, 0.5f, 0), 0.5f, ball));
    return build(p, Image(96, 72, vec3(0.2f)), sun.image());
}
std::shared_ptr<RenderScene> sun_shadow_scene() { return sun_scene(diffuse(vec3(0.5f))); }

RenderStats stats_after(std::shared_ptr<RenderScene> scene, RenderSettings s, int passes) {
    ProgressiveRenderer r(std::move(scene), s);
    for (int i = 0; i < passes; ++i) EXPECT_TRUE(r.render_pass());
    return r.stats();
}

int64_t photons_after(std::shared_ptr<RenderScene> scene, RenderSettings s, int passes) {
    return stats_after(std::move(scene), s, passes).photons_per_pass;
}

}  // namespace

// A change that is almost all direct shadow (which rays estimate) spends few photons; in a glass
// ball's caustic they hold a larger share of the noise (here the ball's own pixels, which rays
// shade, still hold more); without adaptive sampling (render shards) or with the balance off,
// every pass traces the project's count.
TEST(PhotonBalance, ARenderSpendsPhotonsWhereTheyPay) {
    const RenderSettings s = settings(100000, 1);
    const RenderStats shadow = stats_after(sun_shadow_scene(), s, 12);
    EXPECT_LE(shadow.photons_per_pass, 100000 / 3);
    EXPECT_GE(shadow.photons_per_pass, 100000 / 4);  // the floor: a few windows miss rare paths
    const RenderStats caustic = stats_after(sun_scene(glass(1.5f)), s, 12);
    EXPECT_GT(caustic.photon_variance_share, shadow.photon_variance_share)
        << "caustic " << caustic.photon_variance_share << " shadow " << shadow.photon_variance_share;
    EXPECT_GT(shadow.photon_variance_share, 0.0);

    RenderSettings off = s;
    off.balance_photons = false;
    EXPECT_EQ(photons_after(sun_shadow_scene(), off, 12), 100000);
    RenderSettings uniform = s;
    uniform.adaptive_threshold = 0;
    EXPECT_EQ(photons_after(sun_shadow_scene(), uniform, 12), 100000);
}
