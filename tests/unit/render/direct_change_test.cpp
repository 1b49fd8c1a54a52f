// Next-event estimation of the direct light a virtual object blocks at a real point, against
// closed forms: a sphere straight above a floor point hides a cone whose cosine-weighted solid
// angle is pi (R/h)^2.
#include <gtest/gtest.h>

#include <cmath>

#include "common/test_scenes.h"
#include "probe/synthetic_probe.h"
#include "render/direct_change.h"

using namespace dp;
using namespace dp::test;

namespace {

Hit floor_hit(const RenderScene& s, vec3 p) {
    Hit h = s.intersect_real(Ray{p + vec3(0, 0.5f, 0), vec3(0, -1, 0)});
    EXPECT_TRUE(h);
    return h;
}

/// Mean and standard error of `n` estimates of dE's luminance at `hit`.
std::pair<double, double> mean_estimate(const DirectChange& dc, const Hit& hit, int n, uint64_t seed) {
    Rng rng(seed, 1);
    double sum = 0, sum2 = 0;
    for (int k = 0; k < n; ++k) {
        DirectChange::Samples u;
        u.sun = vec2(rng.uniform(), rng.uniform());
        u.sky = vec2(rng.uniform(), rng.uniform());
        u.cone = vec2(rng.uniform(), rng.uniform());
        u.pick = rng.uniform();
        const double v = luminance(dc.estimate(hit, vec3(0, 1, 0), u, rng));
        sum += v;
        sum2 += v * v;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

Project floor_and_ball(vec3 centre, float radius) {
    Project p = look_at_project(vec3(0, 2, 4), vec3(0, 0, 0), 50);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.objects.push_back(sphere(centre, radius, diffuse(vec3(0.5f))));
    return p;
}

}  // namespace

TEST(DirectChange, ABallAboveTheFloorHidesPiRSquaredOverHSquaredOfAUniformSky) {
    const float R = 0.3f, h = 1.2f;
    const vec3 sky(0.7f);
    auto scene = build(floor_and_ball(vec3(0.4f, h, -0.2f), R), Image(32, 24), make_constant_probe(256, 128, sky));
    DirectChange dc(*scene);
    const Hit hit = floor_hit(*scene, vec3(0.4f, 0, -0.2f));
    const auto [mean, err] = mean_estimate(dc, hit, 200000, 1);
    const double expected = -luminance(sky) * kPi * double(R * R) / (double(h) * h);
    EXPECT_NEAR(mean, expected, 4 * err + 1e-3 * std::abs(expected));
    EXPECT_LT(err, 0.01 * std::abs(expected));  // the cone sample makes this an easy integral
    EXPECT_GE(dc.bound(hit.p, vec3(0, 1, 0)), std::abs(expected));
}

TEST(DirectChange, TheSunBehindTheBallIsRemovedWholeAndASunBesideItNotAtAll) {
    SunProbe sun;
    const vec3 l = sun.direction();
    const float R = 0.25f;
    const vec3 x(0.1f, 0, 0.3f);
    auto scene = build(floor_and_ball(x + l * 1.5f, R), Image(32, 24), sun.image());
    DirectChange dc(*scene);
    const auto [mean, err] = mean_estimate(dc, floor_hit(*scene, x), 20000, 2);
    const double expected = -luminance(sun.radiance) * Probe(sun.image(), glm::mat3(1), 1).pixel_solid_angle(sun.py) * l.y;
    EXPECT_NEAR(mean, expected, 4 * err + 2e-3 * std::abs(expected));
    // A point whose cone misses the sun: no change, and no ray needed to know it.
    const auto [beside, beside_err] = mean_estimate(dc, floor_hit(*scene, x + vec3(1.5f, 0, 0)), 2000, 3);
    EXPECT_EQ(beside, 0.0);
    EXPECT_EQ(dc.bound(vec3(0, -5, 0), vec3(0, -1, 0)), 0.0);  // the ball is below this horizon
}

TEST(DirectChange, ARealCeilingBehindTheBallIsBlockedAtItsPhotographedRadiance) {
    // A ceiling that the camera sees and that hides the whole probe: what the ball blocks at
    // the floor is the ceiling's photographed radiance, constant here.
    const float R = 0.2f, h = 0.8f;
    Project p = floor_and_ball(vec3(0, h, 0), R);
    p.camera.eye = vec3(0, 0.5f, 3);
    p.camera.target = vec3(0, 2, 0);
    RealProxy ceiling = ground_plane(vec3(0.5f));
    ceiling.name = "ceiling";
    ceiling.transform.translation = vec3(0, 2, 0);
    p.real.push_back(ceiling);
    const vec3 photo_value(0.3f, 0.2f, 0.1f);
    Image photo(64, 48);
    for (size_t i = 0; i < photo.size(); ++i) photo[i] = photo_value;
    auto scene = build(p, photo, make_constant_probe(64, 32, vec3(5.0f)));
    DirectChange dc(*scene);
    const auto [mean, err] = mean_estimate(dc, floor_hit(*scene, vec3(0)), 100000, 4);
    const double expected = -luminance(photo_value) * kPi * double(R * R) / (double(h) * h);
    EXPECT_NEAR(mean, expected, 4 * err + 2e-3 * std::abs(expected));
}

TEST(DirectChange, APointInsideTheBoundingSphereAgreesWithUniformHemisphereIntegration) {
    // A long slab above the floor: its bounding sphere reaches below the floor, so the floor
    // under it is inside the sphere, where the cone sample becomes a cosine-weighted one.
    const vec3 sky(0.4f, 0.5f, 0.6f);
    Project p = floor_and_ball(vec3(0, 0.3f, 0), 0.1f);
    p.objects[0].shape.kind = Shape::Kind::Box;
    p.objects[0].shape.size = vec3(1.2f, 0.1f, 0.3f);
    p.objects[0].transform.translation = vec3(0, 0.35f, 0);
    auto scene = build(p, Image(32, 24), make_constant_probe(128, 64, sky));
    ASSERT_EQ(scene->clusters().size(), 1u);
    DirectChange dc(*scene);
    const Hit hit = floor_hit(*scene, vec3(0.1f, 0, 0.05f));
    ASSERT_LT(glm::length(hit.p - scene->clusters()[0].center), scene->clusters()[0].radius);
    const auto [mean, err] = mean_estimate(dc, hit, 200000, 5);
    // Independent: uniform directions over the hemisphere, blocked where the slab is hit.
    Rng rng(6, 6);
    const int n = 2000000;
    double blocked = 0;
    for (int k = 0; k < n; ++k) {
        const float z = rng.uniform(), r = std::sqrt(std::max(0.0f, 1 - z * z)), a = 2 * kPi * rng.uniform();
        const vec3 w(r * std::cos(a), z, r * std::sin(a));
        if (scene->intersect_virtual(Ray{hit.p + vec3(0, 1e-4f, 0), w})) blocked += z;
    }
    const double expected = -luminance(sky) * blocked / n * 2 * kPi;
    const double expected_err = std::abs(expected) / std::sqrt(blocked);
    EXPECT_NEAR(mean, expected, 4 * std::hypot(err, expected_err));
    EXPECT_LT(std::abs(expected), luminance(sky) * kPi);  // the slab hides part of the sky only
}
