// A glossy real floor reflects what is inserted and stops reflecting what it hides, against
// closed forms: a polished floor (F0 = 1) shows a glowing ball at the ball's radiance; a half-
// reflecting floor loses F (Schlick) of the sky where a black ball now stands in its reflection;
// where it reflects no object it keeps the photo bit for bit.
#include <gtest/gtest.h>

#include <cmath>

#include "assets/microfacet.h"
#include "common/test_scenes.h"
#include "render/progressive.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr int kW = 96, kH = 72;
const vec3 kBall(0, 0.6f, -1);
constexpr float kRadius = 0.4f;

/// A black, polished floor (only its gloss can change) and one ball.
Project polished_floor(float f0, float roughness, const Material& ball) {
    Project p = look_at_project(vec3(0, 1.2f, 3), vec3(0, 0.2f, -1), 50);
    RealProxy floor = ground_plane(vec3(0));
    floor.gloss.specular = f0;
    floor.gloss.roughness = roughness;
    p.real.push_back(floor);
    p.objects.push_back(sphere(kBall, kRadius, ball));
    return p;
}

struct Rendered {
    std::shared_ptr<RenderScene> scene;
    Image image, dL;
};

Rendered render(const Project& p, vec3 sky, int passes, const Image& photo) {
    Rendered r;
    r.scene = build(p, photo, make_constant_probe(64, 32, sky));
    RenderSettings rs = settings(20000, 9);
    rs.adaptive_threshold = 0;
    ProgressiveRenderer renderer(r.scene, rs);
    for (int i = 0; i < passes; ++i) EXPECT_TRUE(renderer.render_pass());
    r.image = renderer.image();
    r.dL = renderer.dL_layer();
    return r;
}

/// For floor pixel (x, y): whether the mirror ray of its centre meets the ball well inside its
/// outline, and the cosine of the view against the normal.
bool mirror_meets_ball(const RenderScene& s, int x, int y, float inside, float& cos_view) {
    const Ray r = s.camera_ray(float(x), float(y));
    if (r.dir.y >= 0) return false;
    const vec3 p = r.org + r.dir * (-r.org.y / r.dir.y);
    if (p.z < -6 || s.intersect_virtual(r)) return false;
    const vec3 m(r.dir.x, -r.dir.y, r.dir.z);
    cos_view = -r.dir.y;
    return distance_to_line(kBall, p, m) < inside * kRadius && glm::dot(kBall - p, m) > 0;
}

Material glowing(vec3 radiance) {
    Material m;
    m.kind = Material::Kind::Principled;
    m.albedo.rgb = vec3(0);
    m.principled.roughness = 1;
    m.principled.specular = 0;
    m.principled.emission = radiance;
    return m;
}

}  // namespace

TEST(RealGloss, APolishedFloorReflectsAGlowingBallAtItsRadiance) {
    const Image photo(kW, kH, vec3(0.05f));
    const Rendered r = render(polished_floor(1.0f, 0.0f, glowing(vec3(2, 1, 0.5f))), vec3(0), 4, photo);
    int n = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            float c = 0;
            if (!mirror_meets_ball(*r.scene, x, y, 0.7f, c)) continue;
            // F = 1 at every angle; G2/G1 of a near-mirror is 1 within a percent.
            EXPECT_NEAR(r.dL.at(x, y).x, 2.0f, 0.03f) << x << "," << y;
            EXPECT_NEAR(r.dL.at(x, y).z, 0.5f, 0.01f);
            ++n;
        }
    EXPECT_GT(n, 30);
}

TEST(RealGloss, AFloorStopsReflectingTheSkyABlackBallHidesAndKeepsThePhotoElsewhere) {
    const vec3 sky(0.8f, 0.9f, 1.0f);
    const float f0 = 0.5f;
    Image photo(kW, kH, vec3(0.3f, 0.2f, 0.1f));
    const Rendered r = render(polished_floor(f0, 0.0f, diffuse(vec3(0))), sky, 4, photo);
    int reflected = 0, untouched = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            float c = 0;
            if (mirror_meets_ball(*r.scene, x, y, 0.7f, c)) {
                const float F = f0 + (1 - f0) * schlick_weight(c);
                EXPECT_NEAR(r.dL.at(x, y).z, -F * sky.z, 0.02f * F) << x << "," << y;
                ++reflected;
                continue;
            }
            // Far from the ball's reflection (and not seeing the ball): the photo, bit for bit.
            const Ray ray = r.scene->camera_ray(float(x), float(y));
            if (ray.dir.y >= 0) continue;
            bool edge = false;  // a pixel the ball's outline crosses is part ball
            for (const vec2 d : {vec2(-0.5f), vec2(0.5f), vec2(-0.5f, 0.5f), vec2(0.5f, -0.5f), vec2(0)})
                edge |= bool(r.scene->intersect_virtual(r.scene->camera_ray(float(x) + d.x, float(y) + d.y)));
            if (edge) continue;
            const vec3 p = ray.org + ray.dir * (-ray.org.y / ray.dir.y);
            const vec3 m(ray.dir.x, -ray.dir.y, ray.dir.z);
            if (distance_to_line(kBall, p, m) < 3 * kRadius) continue;
            EXPECT_EQ(r.image.at(x, y), photo.at(x, y)) << x << "," << y;
            ++untouched;
        }
    EXPECT_GT(reflected, 30);
    EXPECT_GT(untouched, 1000);
}

TEST(RealGloss, ARougherFloorSpreadsTheReflectionButKeepsItsLight) {
    // The same glowing ball over a floor of roughness 0.3: the reflection blurs, and what the
    // floor reflects summed over its pixels stays within a few percent of the polished one's
    // (Smith's G loses a little at this roughness).
    const Image photo(kW, kH, vec3(0.05f));
    const Rendered sharp = render(polished_floor(1.0f, 0.0f, glowing(vec3(1))), vec3(0), 8, photo);
    const Rendered rough = render(polished_floor(1.0f, 0.3f, glowing(vec3(1))), vec3(0), 8, photo);
    double sum_sharp = 0, sum_rough = 0;
    int partial_sharp = 0, partial_rough = 0;  // pixels between the reflection and the floor
    for (size_t i = 0; i < sharp.dL.size(); ++i) {
        sum_sharp += sharp.dL[i].x;
        sum_rough += rough.dL[i].x;
        partial_sharp += sharp.dL[i].x > 0.1f && sharp.dL[i].x < 0.9f;
        partial_rough += rough.dL[i].x > 0.1f && rough.dL[i].x < 0.9f;
    }
    ASSERT_GT(sum_sharp, 0);
    EXPECT_GT(partial_rough, 2 * partial_sharp);  // blurred
    EXPECT_NEAR(sum_rough / sum_sharp, 1.0, 0.1);
}
