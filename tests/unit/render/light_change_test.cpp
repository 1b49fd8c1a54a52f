// A virtual lamp's light added to the photograph, against closed forms: a point light over a
// real floor adds rho/pi I cos / d^2; a real box shadows it; a spot changes nothing outside
// its cone; an area light's face is drawn where the camera sees it; a virtual ball is lit.
#include <gtest/gtest.h>

#include <cmath>

#include "common/test_scenes.h"
#include "render/progressive.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr int kW = 96, kH = 72;
const vec3 kAlbedo(0.5f, 0.4f, 0.3f);

/// A floor seen from above at an angle, a grey photo, a black probe: all the change is the lamp's.
Project lamp_room(const VirtualLight& lamp) {
    Project p = look_at_project(vec3(0, 3, 3), vec3(0, 0, 0), 60);
    p.real.push_back(ground_plane(kAlbedo));
    p.lights.push_back(lamp);
    return p;
}

VirtualLight lamp(VirtualLight::Kind kind, vec3 at, float power) {
    VirtualLight l;
    l.kind = kind;
    l.transform.translation = at;
    l.power_w = power;
    return l;
}

struct Rendered {
    std::shared_ptr<RenderScene> scene;
    Image image, dL, alpha;
};

Rendered render(const Project& p, int passes, Image photo = Image(kW, kH, vec3(0.2f))) {
    Rendered r;
    r.scene = build(p, std::move(photo), make_constant_probe(64, 32, vec3(0)));
    RenderSettings rs = settings(20000, 5);
    rs.adaptive_threshold = 0;
    ProgressiveRenderer renderer(r.scene, rs);
    for (int i = 0; i < passes; ++i) EXPECT_TRUE(renderer.render_pass());
    r.image = renderer.image();
    r.dL = renderer.dL_layer();
    r.alpha = renderer.alpha_layer();
    return r;
}

/// The floor point pixel (x, y)'s centre sees (false where it sees no floor).
bool floor_point(const RenderScene& s, int x, int y, vec3& p) {
    const Ray r = s.camera_ray(float(x), float(y));
    if (r.dir.y >= 0) return false;
    p = r.org + r.dir * (-r.org.y / r.dir.y);
    return true;
}

}  // namespace

TEST(LightChange, APointLightAddsRhoOverPiTimesItsIrradianceToTheFloor) {
    const vec3 at(0.3f, 1.2f, -0.2f);
    const Rendered r = render(lamp_room(lamp(VirtualLight::Kind::Point, at, 60)), 4);
    double worst = 0, sum = 0, signed_sum = 0;
    int n = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            vec3 p;
            if (!floor_point(*r.scene, x, y, p)) continue;
            const vec3 d = at - p;
            const double E = 60 / (4 * kPi) * d.y / std::pow(glm::length(d), 3.0f);
            const double expected = kAlbedo.y * kInvPi * E;
            const double error = std::abs(r.dL.at(x, y).y - expected) / expected;
            signed_sum += (r.dL.at(x, y).y - expected) / expected;
            worst = std::max(worst, error);
            sum += error;
            ++n;
        }
    ASSERT_GT(n, kW * kH / 2);
    // Four jittered samples per pixel against the value at its centre: apart where the light
    // changes fast across a pixel, but not on average.
    EXPECT_LT(std::abs(signed_sum / n), 0.002);
    EXPECT_LT(sum / n, 0.01);
    EXPECT_LT(worst, 0.06);
}

TEST(LightChange, ARealBoxShadowsTheLampAndTheLampNeverDarkensAnything) {
    const vec3 at(0, 1.5f, 0);
    Project p = lamp_room(lamp(VirtualLight::Kind::Point, at, 80));
    RealProxy box;
    box.name = "crate";
    box.shape.kind = Shape::Kind::Box;
    box.shape.size = vec3(0.4f);
    box.transform.translation = vec3(0, 0.8f, 0);
    p.real.push_back(box);
    const Rendered r = render(p, 2);
    int shadowed = 0, lit = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            EXPECT_GE(r.dL.at(x, y).x, 0.0f);
            vec3 q;
            if (!floor_point(*r.scene, x, y, q) || r.scene->intersect(r.scene->camera_ray(float(x), float(y))).surface->index != 0)
                continue;
            // The box's shadow on the floor: the segment towards the lamp meets the box.
            const vec3 to = at - q;
            const float t = (0.6f - q.y) / to.y;  // the box's underside
            const vec3 h = q + t * to;
            // Lit: the segment passes the box's top face (its widest shadow) with a margin; the
            // floor between that and the underside's shadow sees only bounce light.
            const vec3 top = q + (1.0f - q.y) / to.y * to;
            const double direct = kAlbedo.x * kInvPi * 80 / (4 * kPi) * to.y / std::pow(glm::length(to), 3.0f);
            if (std::abs(h.x) < 0.15f && std::abs(h.z) < 0.15f) {
                // Only the light the floor and the box bounce into the shadow.
                EXPECT_LT(r.dL.at(x, y).x, 0.02 * direct) << x << "," << y;
                ++shadowed;
            } else if (std::abs(top.x) > 0.25f || std::abs(top.z) > 0.25f) {
                EXPECT_GT(r.dL.at(x, y).x, 0.0f) << x << "," << y;
                ++lit;
            }
        }
    EXPECT_GT(shadowed, 20);
    EXPECT_GT(lit, 1000);
}

TEST(LightChange, ASpotLeavesThePhotoBitForBitOutsideItsCone) {
    VirtualLight spot = lamp(VirtualLight::Kind::Spot, vec3(0, 1, 0), 100);
    spot.spot_angle_deg = 50;
    const Image photo(kW, kH, vec3(0.2f, 0.25f, 0.3f));
    const Rendered r = render(lamp_room(spot), 2, photo);
    int inside = 0, outside = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            vec3 q;
            if (!floor_point(*r.scene, x, y, q)) continue;
            const float off_axis = std::atan2(glm::length(vec2(q.x, q.z)), 1.0f);
            if (off_axis > glm::radians(27.0f)) {
                ++outside;
                EXPECT_EQ(r.image.at(x, y), photo.at(x, y)) << x << "," << y;
            } else if (off_axis < glm::radians(15.0f)) {
                ++inside;
                EXPECT_GT(r.image.at(x, y).x, photo.at(x, y).x * 1.5f);
            }
        }
    EXPECT_GT(inside, 20);
    EXPECT_GT(outside, 1000);
}

TEST(LightChange, TheCameraSeesAnAreaLightsFaceAndItsLightDoublesWithItsPower) {
    // A disk turned to face the camera (its axis towards the eye), hanging above the floor.
    VirtualLight disk = lamp(VirtualLight::Kind::Disk, vec3(0, 1, 0), 40);
    disk.size = vec2(0.4f);
    disk.transform.rotation_deg = vec3(-45, 0, 0);  // -Y turned towards +Z and up: the eye at (0, 3, 3)
    Project p = lamp_room(disk);
    const Rendered r = render(p, 2);
    const float L = 40 / (kPi * kPi * 0.04f);
    const Camera& cam = r.scene->camera();
    vec2 px;
    ASSERT_TRUE(cam.project(vec3(0, 1, 0), px));
    const int cx = int(px.x), cy = int(px.y);
    EXPECT_NEAR(r.image.at(cx, cy).x, L, 1e-3 * L);
    EXPECT_EQ(r.alpha.at(cx, cy).x, 1.0f);
    // Twice the power, twice the light on the floor in front of it.
    p.lights[0].power_w = 80;
    const Rendered twice = render(p, 2);
    ASSERT_TRUE(cam.project(vec3(0, 0, 1), px));
    const float once = r.dL.at(int(px.x), int(px.y)).x;
    ASSERT_GT(once, 0.0f);
    EXPECT_NEAR(twice.dL.at(int(px.x), int(px.y)).x, 2 * once, 0.05 * once);
}

TEST(LightChange, ALampLightsAVirtualBallWhoseShadowFallsOnTheFloor) {
    const vec3 at(0, 2, 0);
    Project p = lamp_room(lamp(VirtualLight::Kind::Point, at, 100));
    p.objects.push_back(sphere(vec3(0, 0.5f, 0), 0.3f, diffuse(vec3(0.6f))));
    const Rendered r = render(p, 4);
    const Camera& cam = r.scene->camera();
    vec2 px;
    // The ball's top, facing the lamp 1.2 m away: 0.6/pi I / d^2, plus a little floor bounce.
    ASSERT_TRUE(cam.project(vec3(0, 0.8f, 0.02f), px));
    const double top = 0.6 * kInvPi * 100 / (4 * kPi) / (1.2 * 1.2);
    EXPECT_NEAR(r.image.at(int(px.x), int(px.y)).x, top, 0.1 * top);
    // In front of the ball, in its shadow from the lamp: none of the lamp's direct light, only
    // what the floor and the ball bounce there (a sixth of the light without the ball at most).
    ASSERT_TRUE(cam.project(vec3(0, 0, 0.25f), px));
    p.objects.clear();
    const Rendered bare = render(p, 4);
    const float without = bare.dL.at(int(px.x), int(px.y)).x;
    EXPECT_NEAR(without, 0.5 * kInvPi * 100 / (4 * kPi) * 2 / std::pow(glm::length(at - vec3(0, 0, 0.25f)), 3.0f),
                0.03 * without);
    EXPECT_LT(r.dL.at(int(px.x), int(px.y)).x, without / 6);
}

TEST(LightChange, AGlowingBallLightsTheFloorAsASphericalLampDoes) {
    // A sphere of radiance L and radius R, its centre h above a floor point: E = pi L R^2 / h^2.
    Project p = look_at_project(vec3(0, 3, 3), vec3(0, 0, 0), 60);
    p.real.push_back(ground_plane(kAlbedo));
    Material glow;
    glow.kind = Material::Kind::Principled;
    glow.albedo.rgb = vec3(0);
    glow.principled.specular = 0;
    glow.principled.emission = vec3(5);
    const float R = 0.2f, h = 1.0f;
    p.objects.push_back(sphere(vec3(0, h, 0), R, glow));
    const Rendered r = render(p, 8);
    const Camera& cam = r.scene->camera();
    int n = 0;
    double sum = 0, expected_sum = 0;
    for (int k = 0; k < 24; ++k) {
        // A ring of floor points around the ball's foot.
        const float a = 2 * kPi * float(k) / 24;
        const vec3 q(0.7f * std::cos(a), 0, 0.7f * std::sin(a));
        vec2 px;
        if (!cam.project(q, px) || r.scene->intersect_virtual(r.scene->camera_ray(std::round(px.x), std::round(px.y)))) continue;
        const vec3 seen = r.scene->intersect(r.scene->camera_ray(std::round(px.x), std::round(px.y))).p;
        const vec3 to = vec3(0, h, 0) - seen;
        const double d2 = glm::dot(to, to), cos_q = to.y / std::sqrt(d2);
        // Off the axis: the sphere subtends sin^2 = R^2/d^2 and is seen at cos_q.
        expected_sum += kAlbedo.x * 5.0 * R * R / d2 * cos_q;
        sum += r.dL.at(int(std::round(px.x)), int(std::round(px.y))).x;
        ++n;
    }
    ASSERT_GT(n, 16);
    EXPECT_NEAR(sum / expected_sum, 1.0, 0.02);
    // The camera sees the ball at its emission.
    vec2 px;
    ASSERT_TRUE(cam.project(vec3(0, h, 0), px));
    EXPECT_NEAR(r.image.at(int(px.x), int(px.y)).x, 5.0f, 0.05f);
}
