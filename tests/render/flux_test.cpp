// Flux bookkeeping of photon emission: meshes, several clusters on one line, albedo estimate.
#include <gtest/gtest.h>

#include <cmath>

#include "render/photon_tracer.h"
#include "common/test_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {

/// Sum of negative flux on first landing and the flux one photon carries.
struct NegativeFlux {
    double total = 0, per_photon = 0;
    int64_t count = 0;
};

NegativeFlux negative_flux(const RenderScene& scene, int64_t n, uint64_t seed) {
    PhotonPass pass = trace_photons(scene, seed, 1, n);
    NegativeFlux f;
    for (const Photon& p : pass.real)
        if (p.flux.x < 0) {
            f.total += -p.flux.x;
            f.per_photon = std::max(f.per_photon, double(-p.flux.x));
            ++f.count;
        }
    return f;
}

/// 4-sigma binomial bound on a sum of equal-flux photons.
double bound(const NegativeFlux& f, int64_t n) {
    double p = double(f.count) / n;
    return 4 * f.per_photon * std::sqrt(n * p * (1 - p));
}

}  // namespace

TEST(EmissionFlux, AMeshCubeBlocksTheFluxThroughItsProjectedArea) {
    SunProbe sun;
    Project p = look_at_project(vec3(0, 3, 4), vec3(0, 0, 0), 45);
    p.real.push_back(ground_plane(vec3(0.0f)));  // black: only first landings
    VirtualObject cube;
    cube.name = "cube";
    cube.shape.kind = Shape::Kind::Box;
    cube.shape.size = vec3(0.6f);
    cube.transform.translation = vec3(0, 1, 0);
    cube.material = diffuse(vec3(0.0f));
    p.objects.push_back(cube);
    auto scene = build(p, Image(32, 24), sun.image());
    const int64_t n = 1000000;
    NegativeFlux f = negative_flux(*scene, n, 21);
    vec3 l = sun.direction();
    double projected = 0.36 * (std::abs(l.x) + std::abs(l.y) + std::abs(l.z));
    double expected = sun.normal_irradiance() * projected;
    EXPECT_NEAR(f.total, expected, bound(f, n) + 1e-3 * expected) << "ratio " << f.total / expected;
}

TEST(EmissionFlux, TwoClustersOnOneLightLineAreNotCountedTwice) {
    SunProbe sun;
    vec3 l = sun.direction();
    Project p = look_at_project(vec3(0, 3, 4), vec3(0, 0, 0), 45);
    p.real.push_back(ground_plane(vec3(0.0f)));
    // Stacked along the sun direction, three radii apart: separate clusters, one shadow.
    vec3 low(0, 0.8f, 0);
    p.objects.push_back(sphere(low, 0.3f, diffuse(vec3(0.0f))));
    p.objects.push_back(sphere(low + l * 0.9f, 0.3f, diffuse(vec3(0.0f))));
    auto scene = build(p, Image(32, 24), sun.image());
    ASSERT_EQ(scene->clusters().size(), 2u);
    const int64_t n = 1000000;
    NegativeFlux f = negative_flux(*scene, n, 5);
    double expected = sun.normal_irradiance() * kPi * 0.09;
    EXPECT_NEAR(f.total, expected, bound(f, n) + 1e-3 * expected) << "ratio " << f.total / expected;
}

TEST(EmissionFlux, FarApartObjectsEachCastTheirFullShadow) {
    SunProbe sun;
    Project p = look_at_project(vec3(0, 3, 4), vec3(0, 0, 0), 45);
    p.real.push_back(ground_plane(vec3(0.0f)));
    p.objects.push_back(sphere(vec3(-3, 1, 0), 0.3f, diffuse(vec3(0.0f))));
    p.objects.push_back(sphere(vec3(3, 1, 0), 0.5f, diffuse(vec3(0.0f))));
    auto scene = build(p, Image(32, 24), sun.image());
    ASSERT_EQ(scene->clusters().size(), 2u);
    const int64_t n = 1000000;
    NegativeFlux f = negative_flux(*scene, n, 8);
    double expected = sun.normal_irradiance() * kPi * (0.09 + 0.25);
    // Cluster choice adds variance: photons differ in flux only by cluster, both bounded.
    EXPECT_NEAR(f.total / expected, 1.0, 0.01);
}

TEST(AlbedoEstimate, RecoversTheAlbedoOfASunlitPlaneFromThePhoto) {
    SunProbe sun;
    Project p = look_at_project(vec3(0, 3, 4), vec3(0, 0, 0), 45);
    const vec3 truth(0.6f, 0.4f, 0.2f);
    RealProxy g = ground_plane(vec3(0.5f));
    g.albedo.kind = Albedo::Kind::Estimate;
    p.real.push_back(g);
    p.objects.push_back(sphere(vec3(0, 0.5f, 0), 0.5f, diffuse(vec3(0.5f))));
    auto scene = build(p, analytic_ground_photo(p, 96, 72, sun, truth), sun.image());
    vec3 est = scene->real_surfaces()[0].albedo;
    EXPECT_NEAR(est.x, truth.x, 0.01f);
    EXPECT_NEAR(est.y, truth.y, 0.01f);
    EXPECT_NEAR(est.z, truth.z, 0.01f);
}
