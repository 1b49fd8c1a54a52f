// The virtual lights' placement and sampling against closed forms: the irradiance of a point,
// a spot's cone, a rectangle and a disk; photon flux equal to the power; faces seen from the
// front only.
#include <gtest/gtest.h>

#include <cmath>

#include "assets/virtual_lights.h"

using namespace dp;

namespace {

VirtualLight light(VirtualLight::Kind kind, vec3 at, float power) {
    VirtualLight l;
    l.kind = kind;
    l.transform.translation = at;
    l.power_w = power;
    return l;
}

/// Mean and standard error of the irradiance light 0 of `set` sends to `x` facing `n`.
std::pair<double, double> irradiance(const LightSet& set, vec3 x, vec3 n, int samples) {
    Rng rng(3, 1);
    double sum = 0, sum2 = 0;
    for (int k = 0; k < samples; ++k) {
        const LightSample s = set.sample(0, x, vec2(rng.uniform(), rng.uniform()));
        const double e = double(s.weight.x) * std::max(0.0f, glm::dot(n, s.dir));
        sum += e;
        sum2 += e * e;
    }
    const double mean = sum / samples;
    return {mean, std::sqrt(std::max(0.0, sum2 / samples - mean * mean) / samples)};
}

/// Irradiance at distance h below the centre of a Lambertian a x b rectangle of radiance L
/// facing it: four corner form factors (Howell's catalogue, C-11).
double rectangle_irradiance(double L, double a, double b, double h) {
    const double X = 0.5 * a / h, Y = 0.5 * b / h;
    const double sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
    const double corner = (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) / (2 * kPi);
    return kPi * L * 4 * corner;
}

}  // namespace

TEST(VirtualLights, APointLightGivesPowerOverFourPiDistanceSquared) {
    const LightSet set({light(VirtualLight::Kind::Point, vec3(0, 2, 0), 100)});
    const LightSample s = set.sample(0, vec3(1, 0, 0), vec2(0.3f, 0.7f));
    const double d2 = 5;
    EXPECT_NEAR(s.weight.x, 100 / (4 * kPi * d2), 1e-6);
    EXPECT_NEAR(s.dist, std::sqrt(d2), 1e-6);
    EXPECT_NEAR(glm::dot(s.dir, glm::normalize(vec3(-1, 2, 0))), 1, 1e-6);
    EXPECT_NEAR(set.total_power(), 100, 1e-3);  // white: the luminance of its flux is its power
}

TEST(VirtualLights, ASpotShinesDownItsAxisInsideItsConeOnlyWithASoftEdge) {
    VirtualLight l = light(VirtualLight::Kind::Spot, vec3(0, 1, 0), 100);
    l.spot_angle_deg = 60;
    l.spot_blend = 0.2f;
    const LightSet set({l});
    const PlacedLight& p = set.lights()[0];
    EXPECT_NEAR(glm::dot(p.axis, vec3(0, -1, 0)), 1, 1e-6);
    // On the axis: a point light's intensity; past 30 degrees off it: nothing.
    EXPECT_NEAR(set.sample(0, vec3(0, 0, 0), vec2(0.5f)).weight.x, 100 / (4 * kPi), 1e-5);
    const float inside = std::tan(glm::radians(29.9f)), outside = std::tan(glm::radians(30.1f));
    EXPECT_EQ(set.sample(0, vec3(outside, 0, 0), vec2(0.5f)).weight.x, 0.0f);
    const float edge = set.sample(0, vec3(inside, 0, 0), vec2(0.5f)).weight.x;
    EXPECT_GT(edge, 0.0f);
    EXPECT_LT(edge, 0.05f * 100 / (4 * kPi));  // the blend fades it out towards the edge
    // Turned by 90 degrees about Z, it shines along +X.
    l.transform.rotation_deg = vec3(0, 0, 90);
    EXPECT_NEAR(glm::dot(LightSet({l}).lights()[0].axis, vec3(1, 0, 0)), 1, 1e-6);
}

TEST(VirtualLights, ARectangleAndADiskMatchTheirFormFactors) {
    VirtualLight r = light(VirtualLight::Kind::Rect, vec3(0, 1.5f, 0), 200);
    r.size = vec2(1.0f, 0.5f);
    r.transform.scale = vec3(2, 1, 1);  // a 2 x 0.5 m face
    const LightSet rect({r});
    const double L = 200 / (kPi * 2 * 0.5);
    EXPECT_NEAR(rect.lights()[0].radiance.x, L, 1e-3);
    const auto [e_rect, err_rect] = irradiance(rect, vec3(0), vec3(0, 1, 0), 400000);
    const double expected_rect = rectangle_irradiance(L, 2, 0.5, 1.5);
    EXPECT_NEAR(e_rect, expected_rect, 4 * err_rect);
    EXPECT_LT(err_rect, 0.01 * expected_rect);

    VirtualLight d = light(VirtualLight::Kind::Disk, vec3(0, 1, 0), 50);
    d.size = vec2(1.2f);
    const LightSet disk({d});
    const double Ld = 50 / (kPi * kPi * 0.36);
    const auto [e_disk, err_disk] = irradiance(disk, vec3(0), vec3(0, 1, 0), 400000);
    const double expected_disk = kPi * Ld * 0.36 / (0.36 + 1.0);
    EXPECT_NEAR(e_disk, expected_disk, 4 * err_disk);
    // Above the face (behind it) nothing arrives.
    EXPECT_EQ(irradiance(disk, vec3(0, 2, 0), vec3(0, -1, 0), 100).first, 0.0);
}

TEST(VirtualLights, PhotonsCarryEachLightsPowerSharedByPower) {
    VirtualLight spot = light(VirtualLight::Kind::Spot, vec3(0, 1, 0), 80);
    spot.spot_angle_deg = 90;
    spot.spot_blend = 0;
    VirtualLight rect = light(VirtualLight::Kind::Rect, vec3(3, 2, 0), 300);
    rect.colour = vec3(1, 0.5f, 0.25f);
    const LightSet set({light(VirtualLight::Kind::Point, vec3(-3, 1, 0), 120), spot, rect});
    const int n = 400000;
    Rng rng(11, 2);
    dvec3 total(0);
    int from_rect = 0;
    for (int k = 0; k < n; ++k) {
        const LightPhoton p = set.emit(rng, 1.0 / n, 1e-4f);
        ASSERT_TRUE(p.valid);
        total += dvec3(p.flux);
        from_rect += p.ray.org.x > 2;
        if (p.ray.org.x > 2) {
            EXPECT_LT(p.ray.dir.y, 0.0f);  // the face shines down
        }
    }
    // A hard-edged 90-degree spot keeps (1 - cos 45) / 2 of its point's power.
    const double spot_power = 80 * (1 - std::cos(kPi / 4)) / 2;
    const dvec3 expected = dvec3(120 + spot_power) + 300.0 * dvec3(1, 0.5, 0.25);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(total[c], expected[c], 0.01 * expected[c]);
    const double rect_share = 300 * luminance(dvec3(1, 0.5, 0.25)) / set.total_power();
    EXPECT_NEAR(double(from_rect) / n, rect_share, 0.005);
}

TEST(VirtualLights, AnAreaFaceIsSeenFromItsFrontOnlyAndNotWhenHidden) {
    VirtualLight r = light(VirtualLight::Kind::Rect, vec3(0, 2, 0), 100);
    const LightSet set({r});
    float t = 0;
    EXPECT_GT(set.emitted(Ray{vec3(0.1f, 0, 0.1f), vec3(0, 1, 0)}, INFINITY, &t).x, 0.0f);
    EXPECT_NEAR(t, 2, 1e-5);
    EXPECT_EQ(set.emitted(Ray{vec3(0.1f, 0, 0.1f), vec3(0, 1, 0)}, 1.5f).x, 0.0f);  // a surface before it
    EXPECT_EQ(set.emitted(Ray{vec3(0.3f, 0, 0), vec3(0, 1, 0)}, INFINITY).x, 0.0f);  // beside its 0.5 m face
    EXPECT_EQ(set.emitted(Ray{vec3(0, 3, 0), vec3(0, -1, 0)}, INFINITY).x, 0.0f);    // its back
    r.visible = false;
    EXPECT_EQ(LightSet({r}).emitted(Ray{vec3(0), vec3(0, 1, 0)}, INFINITY).x, 0.0f);
}

TEST(VirtualLights, TheIrradianceBoundHoldsAndIsZeroWhereNoLightReaches) {
    VirtualLight spot = light(VirtualLight::Kind::Spot, vec3(0, 2, 0), 100);
    spot.spot_angle_deg = 40;
    VirtualLight disk = light(VirtualLight::Kind::Disk, vec3(2, 1, 0), 100);
    for (const VirtualLight& l : {light(VirtualLight::Kind::Point, vec3(0, 2, 0), 100), spot, disk}) {
        const LightSet set({l});
        for (const vec3 x : {vec3(0), vec3(0.3f, 0, 0.2f), vec3(2.2f, 0, 0), vec3(1.5f, 0.5f, 0)}) {
            const double e = irradiance(set, x, vec3(0, 1, 0), 20000).first;
            EXPECT_GE(set.irradiance_bound(x, vec3(0, 1, 0)), e * 0.999) << light_kind_name(l.kind);
        }
    }
    EXPECT_EQ(LightSet({spot}).irradiance_bound(vec3(3, 0, 0), vec3(0, 1, 0)), 0.0);  // outside its cone
    EXPECT_EQ(LightSet({disk}).irradiance_bound(vec3(2, 2, 0), vec3(0, 1, 0)), 0.0);  // above its face
}
