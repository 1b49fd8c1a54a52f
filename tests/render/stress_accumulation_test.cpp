// A billion signed photons whose fluxes nearly cancel (a caustic inside a shadow), through the
// real accumulation chain: PhotonMap::gather, CameraGather::real_dL, TileAccumulator. Each stage's
// result is compared with an exact sum computed in 128-bit fixed point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/tile_accumulator.h"
#include "render/stress_common.h"

using namespace dp;
using namespace dp::test;

namespace {

// Every flux used below is a multiple of 2^-kFixedBits: exact as a 128-bit integer.
constexpr int kFixedBits = 90;

__int128 to_fixed(float v) { return static_cast<__int128>(std::ldexp(double(v), kFixedBits)); }
double from_fixed(__int128 v) {
    // Split so the conversion of each half is exact.
    const __int128 hi = v >> 64;
    const __int128 lo = v - (hi << 64);
    return std::ldexp(double(hi), 64 - kFixedBits) + std::ldexp(double(lo), -kFixedBits);
}

/// One pass's photons: a caustic (positive) and a shadow (negative) on the same spot, stored in
/// the worst order for a running sum (every positive photon first), fluxes spanning 2^12 per
/// channel as bounced photons do, net flux about 1e-6 of the total.
std::vector<Photon> cancelling_photons(size_t n, float radius, uint64_t seed) {
    Rng rng(seed, 77);
    std::vector<Photon> ps(n);
    const size_t half = n / 2;
    const float base = 0x1p-20f;  // plausible per-photon flux for a million-photon pass
    for (size_t i = 0; i < half; ++i) {
        vec3 f;
        for (int c = 0; c < 3; ++c) f[c] = base * std::exp2(-12.0f * rng.uniform()) * (1 + rng.uniform());
        ps[i].flux = f;
    }
    // The shadow photons: the caustic photons in a shuffled order, each a hair weaker, so the
    // sums cancel to ~1e-6.
    std::vector<size_t> order(half);
    for (size_t i = 0; i < half; ++i) order[i] = i;
    for (size_t i = half; i > 1; --i) std::swap(order[i - 1], order[size_t(rng.uniform_double() * double(i))]);
    for (size_t i = 0; i < half; ++i) ps[half + i].flux = -(ps[order[i]].flux * (1.0f - 0x1p-20f));
    for (Photon& p : ps) {
        // Inside 0.7 r of the centre: every gather point below (within 0.1 r) sees every photon.
        vec2 d = vec2(rng.uniform(), rng.uniform()) * 2.0f - 1.0f;
        while (glm::dot(d, d) > 1) d = vec2(rng.uniform(), rng.uniform()) * 2.0f - 1.0f;
        d *= 0.7f * radius;
        p.position = vec3(d.x, 0, d.y);
        p.normal = vec3(0, 1, 0);
    }
    return ps;
}

}  // namespace

TEST(SignedAccumulation, ABillionNearlyCancellingPhotonsStayExactToOnePartInABillion) {
    // The scene only supplies the real surface that real_dL shades.
    Project p = look_at_project(vec3(0, 2, 3), vec3(0, 0, 0), 40);
    p.real.push_back(ground_plane(vec3(0.5f)));
    SunProbe sun;
    auto scene = build(p, Image(4, 4), sun.image());
    const Surface& ground = scene->real_surfaces()[0];

    const float radius = 0.01f;
    const size_t kPhotons = size_t(1) << 20;
    const int kPasses = 16, kPixels = 60;
    TileAccumulator acc(8, 8, 8);  // one tile of 64 pixels, the first kPixels used
    std::vector<__int128> pass_sum(kPixels * 3, 0);  // exact sums of what the accumulator got
    std::vector<SampleResult> samples(64);
    double worst_gather = 0, worst_delta = 0;
    double cancellation = 0;
    uint64_t accumulated = 0;
    for (int pass = 0; pass < kPasses; ++pass) {
        std::vector<Photon> photons = cancelling_photons(kPhotons, radius, 100 + pass);
        // Exact per-channel sums of the photons' flux and of their magnitudes.
        __int128 exact[3] = {0, 0, 0}, magnitude[3] = {0, 0, 0};
        for (const Photon& ph : photons)
            for (int c = 0; c < 3; ++c) {
                exact[c] += to_fixed(ph.flux[c]);
                magnitude[c] += to_fixed(std::abs(ph.flux[c]));
            }
        PassMaps maps;
        maps.radius = radius;
        maps.real.build(photons, radius);
        ASSERT_EQ(maps.real.size(), kPhotons);
        CameraGather gather(*scene, maps);
        Rng rng(pass, 5);
        for (int k = 0; k < kPixels; ++k) {
            Hit hit;
            hit.surface = &ground;
            hit.p = vec3(rng.uniform() - 0.5f, 0, rng.uniform() - 0.5f) * (0.2f * radius);
            hit.ng = hit.ns = vec3(0, 1, 0);
            const vec3 down(0, -1, 0);
            const dvec3 phi = maps.real.gather(hit.p, vec3(0, 1, 0));
            const vec3 dL = gather.real_dL(hit, down, rng, nullptr);
            accumulated += kPhotons;
            const dvec3 rho = dvec3(ground.reflectance_at(hit.uv));
            for (int c = 0; c < 3; ++c) {
                const double want = from_fixed(exact[c]);
                cancellation = std::max(cancellation, std::abs(want) / from_fixed(magnitude[c]));
                // Check 1: the gather's double sum equals the exact sum to 1e-9 of the (tiny) net.
                worst_gather = std::max(worst_gather, std::abs(phi[c] - want) / std::abs(want));
                // Check 2: dL = rho/pi phi / (pi r^2), rounded once to float.
                const double want_dL = rho[c] / kPi * want / (kPi * double(radius) * radius);
                worst_delta = std::max(worst_delta, std::abs(dL[c] - want_dL) / std::abs(want_dL));
                pass_sum[k * 3 + c] += to_fixed(dL[c]);
            }
            samples[k].pixel_change = samples[k].dL = dL;
            samples[k].alpha = 0;
        }
        ASSERT_EQ(acc.add_tile(0, pass % 2 == 1, samples.data()), 0u);
        acc.finish_pass();
    }
    std::printf("%.3g photons accumulated; net/total flux %.2e; worst gather error %.2e, dL error %.2e\n",
                double(accumulated), cancellation, worst_gather, worst_delta);
    EXPECT_GE(accumulated, uint64_t(1000000000));
    EXPECT_LT(cancellation, 1e-5);  // the signs do nearly cancel
    EXPECT_LT(worst_gather, 1e-9);
    EXPECT_LT(worst_delta, 1e-6);  // one float rounding
    // Check 3: the pass accumulator's mean equals the exact mean of the samples it was given.
    ASSERT_EQ(acc.passes(), kPasses);
    double worst_mean = 0;
    for (int k = 0; k < kPixels; ++k) {
        const dvec3 mean = acc.mean_pixel_change(size_t(k));
        const dvec3 mean_dL = acc.mean_dL(size_t(k));
        for (int c = 0; c < 3; ++c) {
            const double want = from_fixed(pass_sum[k * 3 + c]) / kPasses;
            worst_mean = std::max(worst_mean, std::abs(mean[c] - want) / std::abs(want));
            worst_mean = std::max(worst_mean, std::abs(mean_dL[c] - want) / std::abs(want));
        }
    }
    std::printf("worst pass-mean error %.2e\n", worst_mean);
    EXPECT_LT(worst_mean, 1e-9);
}

TEST(SignedAccumulation, ANonFiniteSampleIsDroppedWholeAndCounted) {
    TileAccumulator acc(3, 1, 8);
    std::vector<SampleResult> s(64);
    s[0].pixel_change = vec3(1, 2, 3);
    s[1].pixel_change = vec3(NAN, 0, 0);
    s[2].dL = vec3(0, INFINITY, 0);
    s[2].pixel_change = vec3(5);
    EXPECT_EQ(acc.add_tile(0, true, s.data()), 2u);
    acc.finish_pass();
    s[1].pixel_change = vec3(4);
    s[2].dL = vec3(0);
    EXPECT_EQ(acc.add_tile(0, false, s.data()), 0u);
    acc.finish_pass();
    // Check: pixel 1's NaN pass added nothing (its mean is 4/2), pixel 2's Inf pass likewise.
    EXPECT_EQ(acc.mean_pixel_change(0), dvec3(1, 2, 3));
    EXPECT_EQ(acc.mean_pixel_change(1), dvec3(2));
    EXPECT_EQ(acc.mean_pixel_change(2), dvec3(2.5));
    EXPECT_TRUE(acc.untouched(0) == false);
}
