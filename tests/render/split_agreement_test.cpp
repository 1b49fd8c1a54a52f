// The split estimator (direct light the objects block by rays, photons for the rest, photons
// splatted where a pixel outgrows the gather disk) and the all-photon one estimate the same
// change: on small versions of the benchmark scenes, the mean over many passes of each agrees
// with the other within noise, region by region. Regions are large against the gather radius,
// so the all-photon estimator's blur moves little light across their borders; a tolerance of
// 0.2% of the photo over the region stands for what it does move.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "common/test_scenes.h"
#include "probe/synthetic_probe.h"
#include "render/progressive.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr int kW = 64, kH = 40;

/// Per pass, the summed luminance change over each of four regions: real pixels left and right
/// of the image centre, object pixels, and all pixels.
struct RegionSums {
    std::vector<std::array<double, 4>> passes;
    double photo[4] = {0, 0, 0, 0};
};

RegionSums region_sums(std::shared_ptr<RenderScene> scene, const RenderSettings& base, int passes, uint64_t seed) {
    RegionSums out;
    ProgressiveRenderer r(scene, settings(60000, seed, base));
    const Image& photo = scene->photo();
    for (int pass = 1; pass <= passes; ++pass) {
        Image change, dL, alpha;
        r.render_single_pass(pass, change, dL, alpha);
        std::array<double, 4> s{0, 0, 0, 0};
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const size_t i = size_t(y) * kW + x;
                const double d = luminance(change[i]);
                const int region = alpha[i].x > 0 ? 2 : (x < kW / 2 ? 0 : 1);
                s[region] += d;
                s[3] += d;
                if (pass == 1) {
                    out.photo[region] += luminance(photo[i]);
                    out.photo[3] += luminance(photo[i]);
                }
            }
        out.passes.push_back(s);
    }
    return out;
}

void mean_and_error(const RegionSums& r, int region, double& mean, double& error) {
    double sum = 0, sum2 = 0;
    const double n = double(r.passes.size());
    for (const auto& p : r.passes) {
        sum += p[region];
        sum2 += p[region] * p[region];
    }
    mean = sum / n;
    error = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1));
}

/// Renders both estimators and compares every region: |difference| within 4.5 standard errors
/// plus 0.2% of the region's photo (the all-photon estimator's blur across region borders).
void expect_agreement(const std::string& name, const Project& base, const Image& photo, const Image& probe,
                      int passes) {
    Project split = base, photons = base;
    split.render.estimator = Estimator::Split;
    photons.render.estimator = Estimator::Photons;
    const RegionSums a = region_sums(build(split, photo, probe), split.render, passes, 11);
    const RegionSums b = region_sums(build(photons, photo, probe), photons.render, passes, 23);
    const char* names[4] = {"real left", "real right", "objects", "all"};
    for (int g = 0; g < 4; ++g) {
        double ma, ea, mb, eb;
        mean_and_error(a, g, ma, ea);
        mean_and_error(b, g, mb, eb);
        const double sigma = std::hypot(ea, eb), blur = 0.002 * a.photo[g];
        std::printf("%-12s %-10s split %10.4f +- %.4f  photons %10.4f +- %.4f  (z %.2f)\n", name.c_str(), names[g],
                    ma, ea, mb, eb, sigma > 0 ? (ma - mb) / sigma : 0.0);
        EXPECT_LE(std::abs(ma - mb), 4.5 * sigma + blur) << name << ", " << names[g];
    }
}

Project bench_like(vec3 eye, vec3 target) {
    Project p = look_at_project(eye, target, 40);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.render.initial_radius = 0.03f;
    p.render.adaptive_threshold = 0;
    return p;
}

Image sun_sky(float sun_radius_deg) {
    return make_sun_sky_probe(512, 256, glm::normalize(vec3(0.45f, 0.8f, 0.4f)), vec3(3000.0f), sun_radius_deg,
                              vec3(0.12f, 0.2f, 0.45f), vec3(0.35f, 0.4f, 0.5f));
}

/// The photo's value does not enter the change on real surfaces (rho is the proxy's), only
/// the objects' pixels: a flat grey photo is enough.
Image grey_photo() {
    Image photo(kW, kH);
    for (size_t i = 0; i < photo.size(); ++i) photo[i] = vec3(0.4f);
    return photo;
}

}  // namespace

TEST(SplitAgreement, AHardAndASoftSunShadowAgreeWithTheAllPhotonEstimate) {
    Project p = bench_like(vec3(0, 1.4f, 4.2f), vec3(0, 0.35f, 0));
    p.objects.push_back(sphere(vec3(0, 0.5f, 0), 0.5f, diffuse(vec3(0.7f, 0.6f, 0.5f))));
    expect_agreement("hard shadow", p, grey_photo(), sun_sky(0.5f), 48);
    expect_agreement("soft shadow", p, grey_photo(), sun_sky(6.0f), 48);
}

TEST(SplitAgreement, GlassAndMirrorsAgreeWithTheAllPhotonEstimate) {
    Project p = bench_like(vec3(0, 1.4f, 4.2f), vec3(0, 0.35f, 0));
    p.objects.push_back(sphere(vec3(-0.7f, 0.35f, 0.1f), 0.35f, mirror(vec3(0.92f))));
    p.objects.push_back(sphere(vec3(0.8f, 0.45f, -0.2f), 0.45f, glass(1.5f)));
    p.objects.push_back(sphere(vec3(0.05f, 0.3f, 0.45f), 0.3f, diffuse(vec3(0.75f, 0.2f, 0.12f))));
    expect_agreement("glass+mirror", p, grey_photo(), sun_sky(1.5f), 48);
}

TEST(SplitAgreement, LightBlockedFromARealWallAgreesWithTheAllPhotonEstimate) {
    // A box near a wall: the wall's light that the box hides from the floor, and the floor's
    // light it hides from the wall, are the surroundings' part of the direct change.
    Project p = bench_like(vec3(0.3f, 1.2f, 3.4f), vec3(0, 0.5f, -0.5f));
    p.real.push_back(wall_proxy(-0.9f, vec3(0.8f)));
    VirtualObject box = sphere(vec3(0, 0.35f, -0.5f), 0.3f, diffuse(vec3(0.6f)));
    box.shape.kind = Shape::Kind::Box;
    box.shape.size = vec3(0.8f, 0.7f, 0.5f);
    p.objects.push_back(box);
    expect_agreement("box by wall", p, grey_photo(), make_constant_probe(256, 128, vec3(0.6f, 0.65f, 0.7f)), 48);
}
