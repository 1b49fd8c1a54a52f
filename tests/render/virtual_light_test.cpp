// The virtual lights in the reference renderers: the path tracer against closed forms (a point
// and a spot over a real plane of known albedo), and the progressive renderer against the path
// tracer on a room corner lit by a rect light, the independent check of its lights.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/test_scenes.h"
#include "reference/path_tracer.h"
#include "reference/standard_differential.h"
#include "render/progressive.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr vec3 kRho{0.6f, 0.5f, 0.4f};

VirtualLight light(VirtualLight::Kind kind, vec3 position, float power, vec3 colour = vec3(1.0f)) {
    VirtualLight l;
    l.name = light_kind_name(kind);
    l.kind = kind;
    l.transform.translation = position;
    l.power_w = power;
    l.colour = colour;
    return l;
}

/// A real plane of albedo kRho under a black probe, lit by `l` alone.
Project plane_under(const VirtualLight& l) {
    Project p = look_at_project(vec3(0, 2.0f, 3.0f), vec3(0, 0, 0), 50);
    p.real.push_back(ground_plane(kRho));
    p.lights.push_back(l);
    return p;
}

/// The radiance the plane sends back along `ray` from a point or spot light: rho/pi * I(w) cos / d^2.
vec3 closed_form(const RenderScene& scene, const VirtualLight& l, const Ray& ray) {
    const Hit hit = scene.intersect(ray);
    if (!hit) return vec3(0);
    const vec3 to = l.transform.translation - hit.p;
    const float d2 = glm::dot(to, to);
    const vec3 w = to / std::sqrt(d2);
    if (w.y <= 0) return vec3(0);
    float falloff = 1.0f;
    if (l.kind == VirtualLight::Kind::Spot) {  // the cone about -Y (cos = w.y), Blender's smoothstep edge
        const float cos_half = std::cos(0.5f * glm::radians(l.spot_angle_deg));
        const float x = std::clamp((w.y - cos_half) / ((1 - cos_half) * l.spot_blend), 0.0f, 1.0f);
        falloff = x * x * (3 - 2 * x);
    }
    const vec3 I = l.colour * (l.power_w / (4 * kPi)) * falloff;
    return kRho * kInvPi * I * (w.y / d2);
}

/// The path tracer's image of `p` (deterministic per camera ray here: one light, nothing for a
/// bounce to reach) against the closed form averaged over the same camera rays; returns the
/// largest relative error and the image's mean luminance.
void expect_closed_form(const VirtualLight& l, double* max_rel, double* mean) {
    constexpr int W = 32, H = 24, kSpp = 8;
    const Project p = plane_under(l);
    SceneAssets assets;
    assets.photo = Image(W, H);
    assets.probe_latlong = Image(64, 32);  // black: the light alone
    const RenderScene scene(p, assets);
    ReferenceOptions o;
    o.samples_per_pixel = kSpp;
    o.max_depth = 4;
    o.show_probe = false;
    const Image img = render_reference(scene, o);
    *max_rel = 0;
    *mean = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            vec3 expected(0);
            for (int s = 0; s < kSpp; ++s)
                expected += closed_form(scene, l, reference_camera_ray(scene, o.seed, x, y, uint64_t(s)));
            expected /= float(kSpp);
            const vec3 got = img.at(x, y);
            const float scale = std::max(luminance(expected), 1e-6f);
            *max_rel = std::max(*max_rel, double(glm::length(got - expected) / scale));
            *mean += luminance(got) / double(W * H);
        }
}

}  // namespace

TEST(VirtualLights, APointLightOverARealPlaneMatchesTheClosedForm) {
    double max_rel = 0, mean = 0;
    expect_closed_form(light(VirtualLight::Kind::Point, vec3(0.3f, 1.5f, 0.2f), 100.0f, vec3(1, 0.8f, 0.6f)), &max_rel,
                       &mean);
    std::printf("point: largest relative error %.2e, mean luminance %.4f\n", max_rel, mean);
    EXPECT_GT(mean, 0.05);
    EXPECT_LT(max_rel, 1e-3);
}

TEST(VirtualLights, ASpotLightOverARealPlaneMatchesTheClosedFormInsideAndOutsideItsCone) {
    VirtualLight spot = light(VirtualLight::Kind::Spot, vec3(-0.2f, 1.2f, 0.0f), 300.0f);
    spot.spot_angle_deg = 60;
    spot.spot_blend = 0.3f;
    double max_rel = 0, mean = 0;
    expect_closed_form(spot, &max_rel, &mean);
    std::printf("spot: largest relative error %.2e, mean luminance %.4f\n", max_rel, mean);
    EXPECT_GT(mean, 0.02);
    EXPECT_LT(max_rel, 1e-3);
}

namespace {

constexpr int kW = 64, kH = 48;

/// A real floor and back wall, a diffuse virtual ball, a rect light above and in front of it
/// and a disk light facing the camera, under a dim sky.
Project lit_corner(bool ball = true) {
    Project p = look_at_project(vec3(0, 1.6f, 3.4f), vec3(0, 0.6f, 0), 45);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.real.push_back(wall_proxy(-1.2f, vec3(0.7f, 0.6f, 0.5f)));
    if (ball) p.objects.push_back(sphere(vec3(0.1f, 0.45f, -0.2f), 0.45f, diffuse(vec3(0.3f, 0.6f, 0.8f))));
    VirtualLight rect = light(VirtualLight::Kind::Rect, vec3(-0.9f, 1.9f, 0.4f), 150.0f, vec3(1, 0.9f, 0.8f));
    rect.size = vec2(0.5f, 0.4f);
    rect.transform.rotation_deg = vec3(0, 0, -25);  // tipped towards the ball
    p.lights.push_back(rect);
    // A small disk by the wall facing the camera: its face is in view.
    VirtualLight disk = light(VirtualLight::Kind::Disk, vec3(0.9f, 1.3f, -0.6f), 20.0f, vec3(0.8f, 0.9f, 1));
    disk.size = vec2(0.25f);
    disk.transform.rotation_deg = vec3(-90, 0, 0);  // shines along +z
    p.lights.push_back(disk);
    return p;
}

Image dim_sky() {
    return make_sun_sky_probe(128, 64, glm::normalize(vec3(1, 1.3f, 0.4f)), vec3(20.0f), 6.0f,
                              vec3(0.05f, 0.08f, 0.15f),
                              vec3(0.1f, 0.1f, 0.12f));
}

Image path_traced(const Project& p, const Image& probe, bool with_virtual, int spp, uint64_t seed) {
    SceneAssets assets;
    assets.photo = Image(kW, kH);
    assets.probe_latlong = probe;
    const RenderScene scene(p, assets);
    ReferenceOptions o;
    o.samples_per_pixel = spp;
    o.include_virtual = with_virtual;
    o.seed = seed;
    return render_reference(scene, o);
}

double mse(const Image& a, const Image& b) {
    double se = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        const vec3 d = a[i] - b[i];
        se += glm::dot(d, d) / 3.0;
    }
    return se / double(a.size());
}

double mean_luminance(const Image& a) {
    double sum = 0;
    for (size_t i = 0; i < a.size(); ++i) sum += luminance(a[i]);
    return sum / double(a.size());
}

struct Agreement {
    double excess = 0;       ///< error against the truth over what the two sides' noise explains
    double mean_sigmas = 0;  ///< the mean difference over its standard error
    double change = 0;       ///< mean luminance the ball and the light add to the photo
};

/// Two renders `out1`, `out2` (other seeds) against two path-traced truths (other seeds): each
/// side's per-pixel variance is half its pair's mean squared difference. `excess` is
/// mse(out1, truth1) over the sum of the two variances (about 1 where both estimate the same
/// image), `mean_sigmas` the difference of the pairs' means over its standard error.
Agreement agreement(const Image& out1, const Image& out2, const Image& truth1, const Image& truth2,
                    const Image& photo) {
    Agreement a;
    const double var_out = 0.5 * mse(out1, out2), var_truth = 0.5 * mse(truth1, truth2);
    a.excess = mse(out1, truth1) / (var_out + var_truth);
    const double n = double(out1.size());
    const double diff = 0.5 * (mean_luminance(out1) + mean_luminance(out2)) -
                        0.5 * (mean_luminance(truth1) + mean_luminance(truth2));
    a.mean_sigmas = diff / std::sqrt(0.5 * (var_out + var_truth) / n);
    a.change = mean_luminance(truth1) - mean_luminance(photo);
    return a;
}

/// The photo (real proxies under the sky, many samples: its noise is common to both renders
/// of a method and would count as their error) and the two truths of `lit_corner`.
struct Truth {
    explicit Truth(bool ball = true) : project(lit_corner(ball)) {}
    explicit Truth(Project p) : project(std::move(p)) {}
    Truth(Project p, Image sky) : project(std::move(p)), probe(std::move(sky)) {}
    Project project;
    Image probe = dim_sky();
    Image photo = path_traced(project, probe, false, 2048, 11);
    Image t1 = path_traced(project, probe, true, 512, 12), t2 = path_traced(project, probe, true, 512, 13);
};

Image progressive(const Truth& t, uint64_t seed, int passes = 24) {
    ProgressiveRenderer r(build(t.project, t.photo, t.probe), settings(100000, seed));
    for (int i = 0; i < passes; ++i) r.render_pass();
    return r.image();
}

Image standard(const Truth& t, uint64_t seed) {
    RenderSettings rs;
    rs.seed = seed;
    StandardDifferentialRenderer r(build(t.project, t.photo, t.probe), rs,
                                   StandardDifferentialRenderer::Sampling::Correlated, 128);
    for (int i = 0; i < 2; ++i) r.render_pass();
    return r.image();
}

/// Two progressive renders of `t` (seeds 3 and 4) against its truths: the picture changes by
/// more than `min_change` either way, the error is what the two sides' noise explains, the means agree.
void expect_progressive_agrees(const char* what, const Truth& t, double min_change, int passes = 24) {
    const Agreement a = agreement(progressive(t, 3, passes), progressive(t, 4, passes), t.t1, t.t2, t.photo);
    std::printf("%s: error over the noise %.3f, mean difference %.2f sigma, change %.4f\n", what, a.excess,
                a.mean_sigmas, a.change);
    EXPECT_GT(std::abs(a.change), min_change);
    EXPECT_LT(a.excess, 1.3);
    EXPECT_LT(std::abs(a.mean_sigmas), 4.0);
}

}  // namespace

TEST(VirtualLights, TheProgressiveRendererAgreesWithThePathTracerOnARectLitCorner) {
    const Truth t;
    expect_progressive_agrees("progressive", t, 0.2);
}

/// The corner with no lamp: a glowing ball lights it, beside a rough gold ball that reflects it
/// (next-event estimation and the gold's lobe share the glow by MIS) and the diffuse ball.
Project glowing_corner() {
    Project p = lit_corner();
    p.lights.clear();
    Material glow;
    glow.kind = Material::Kind::Principled;
    glow.albedo.rgb = vec3(0.2f);
    glow.principled.roughness = 0.6f;
    glow.principled.emission = vec3(6, 4, 2);
    p.objects.push_back(sphere(vec3(-0.75f, 0.25f, 0.3f), 0.2f, glow));
    Material gold;
    gold.kind = Material::Kind::Principled;
    gold.albedo.rgb = vec3(1.0f, 0.78f, 0.34f);
    gold.principled.metallic = 1;
    gold.principled.roughness = 0.35f;
    p.objects.push_back(sphere(vec3(-0.55f, 0.2f, -0.55f), 0.2f, gold));
    return p;
}

TEST(VirtualLights, TheProgressiveRendererAgreesWithThePathTracerOnAGlowingBallLightingTheCorner) {
    const Truth t(glowing_corner());
    expect_progressive_agrees("glowing ball", t, 0.05);
}

TEST(VirtualLights, TheProgressiveRendererAgreesWithThePathTracerOnAGlossyFloor) {
    // The corner's floor varnished: it reflects the ball and the lamp's face, and stops
    // reflecting the wall and sky the ball hides.
    Project p = lit_corner();
    p.real[0].gloss = Gloss{0.1f, 0.15f};
    const Truth t(p);
    expect_progressive_agrees("glossy floor", t, 0.2);
}

TEST(VirtualLights, TheProgressiveRendererAgreesWithThePathTracerWithLightsAlone) {
    // No object: the first gather radius cannot come from the objects' size (from the scene's
    // scale, set by the 40 m floor, the bounce light on the wall came out 10% short).
    const Truth t(false);
    expect_progressive_agrees("lights alone", t, 0.2);
}

TEST(VirtualLights, TheStandardDifferentialRendererAgreesWithThePathTracerOnARectLitCorner) {
    const Truth t;
    const Agreement a = agreement(standard(t, 5), standard(t, 6), t.t1, t.t2, t.photo);
    std::printf("standard differential: error over the noise %.3f, mean difference %.2f sigma\n", a.excess,
                a.mean_sigmas);
    EXPECT_LT(a.excess, 1.3);
    EXPECT_LT(std::abs(a.mean_sigmas), 4.0);
}

TEST(VirtualLights, TheStandardDifferentialRendererDrawsALightsFaceOverThePhoto) {
    // Where the camera sees the disk's face the composite is the face, not the photo plus a
    // change (alpha 1, as the progressive renderer draws it); beside the face, the real wall.
    const Project p = lit_corner();
    const auto scene = build(p, Image(kW, kH), dim_sky());
    StandardDifferentialRenderer r(scene, RenderSettings{}, StandardDifferentialRenderer::Sampling::Correlated, 4);
    r.render_pass();
    ProgressiveRenderer pr(scene, settings(1000, 1));
    pr.render_pass();
    vec2 px, beside;
    ASSERT_TRUE(scene->camera().project(p.lights[1].transform.translation, px));
    ASSERT_TRUE(scene->camera().project(p.lights[1].transform.translation + vec3(0.4f, 0, 0), beside));
    const auto at = [](const Image& img, vec2 q) { return img.at(int(std::lround(q.x)), int(std::lround(q.y))).x; };
    EXPECT_EQ(at(r.alpha_layer(), px), 1.0f);
    EXPECT_EQ(at(pr.alpha_layer(), px), 1.0f);
    EXPECT_EQ(at(r.alpha_layer(), beside), 0.0f);
}

TEST(VirtualLights, TheProgressiveRendererAgreesWithThePathTracerWhereABallHidesTheSunsReflection) {
    // No lamp: a small bright sun low behind the ball, whose reflection in the varnished floor
    // the ball now hides from the camera. Left to the gloss lobe's samples, a floor pixel
    // found the sun behind the ball once in many passes and went tens of units negative; and
    // the ball's underside, lit by the floor, took the floor's photographed glint (the gloss
    // the camera sees) as what the floor sends it, 4 to 6 units too bright.
    Project p = lit_corner();
    p.lights.clear();
    p.real.pop_back();  // no wall: it would hide the sun
    p.real[0].gloss = Gloss{0.1f, 0.15f};
    const Image sky = make_sun_sky_probe(256, 128, glm::normalize(vec3(0.0f, 0.5f, -0.86f)), vec3(3000.0f), 1.5f,
                                         vec3(0.05f, 0.08f, 0.15f), vec3(0.1f, 0.1f, 0.12f));
    const Truth t(p, sky);
    // 96 passes: at 24 the renderer's own noise still hid the bias.
    expect_progressive_agrees("sun hidden in a glossy floor", t, 0.5, 96);
}

TEST(VirtualLights, TheUndersideOfABallOnAGlossyFloorSeesTheFloorReflectTheBall) {
    // A bright sky and a strongly varnished floor: under the ball the floor's gloss reflected
    // the sky in the photo, and now reflects the ball's dark underside. Seen from that
    // underside, the floor must send the change too: without it the bottom of the ball came
    // out 2.5% bright on the polished-floor benchmark scene, and 2.8% (9.5 sigma) here. With it
    // 1.4% (4.6 sigma) is left at this strong gloss (F0 0.5), not traced yet (1.2% at F0 0.2):
    // the bound below holds the part that was fixed.
    Project p = lit_corner();
    p.lights.clear();
    p.real.pop_back();
    p.real[0].gloss = Gloss{0.5f, 0.08f};
    p.camera.eye = vec3(0, 0.7f, 3.0f);  // low: the ball's underside in view
    p.camera.target = vec3(0.1f, 0.35f, -0.2f);
    const Image sky = make_sun_sky_probe(128, 64, glm::normalize(vec3(1, 1.3f, 0.4f)), vec3(20.0f), 6.0f,
                                         vec3(0.9f, 0.95f, 1.0f), vec3(1.0f, 1.0f, 1.0f));
    Truth t(p, sky);
    t.t1 = path_traced(p, sky, true, 4096, 12);  // the truths' noise dominated at 512 samples
    t.t2 = path_traced(p, sky, true, 4096, 13);
    // The ball's lowest quarter of pixels (all four renders see the ball there).
    ProgressiveRenderer r3(build(t.project, t.photo, t.probe), settings(100000, 3));
    ProgressiveRenderer r4(build(t.project, t.photo, t.probe), settings(100000, 4));
    for (int i = 0; i < 96; ++i) {
        r3.render_pass();
        r4.render_pass();
    }
    const Image a3 = r3.alpha_layer(), o3 = r3.image(), o4 = r4.image();
    int top = kH, bottom = -1;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            if (a3.at(x, y).x == 1.0f) top = std::min(top, y), bottom = std::max(bottom, y);
    ASSERT_GT(bottom, top);
    const int from = bottom - (bottom - top) / 4;
    double out = 0, truth = 0, var = 0, var_out = 0;
    int n = 0;
    for (int y = from; y <= bottom; ++y)
        for (int x = 0; x < kW; ++x) {
            if (a3.at(x, y).x != 1.0f) continue;
            const double l3 = luminance(o3.at(x, y)), l4 = luminance(o4.at(x, y));
            const double t1 = luminance(t.t1.at(x, y)), t2 = luminance(t.t2.at(x, y));
            out += (l3 + l4) / 2;
            truth += (t1 + t2) / 2;
            var += ((l3 - l4) * (l3 - l4) + (t1 - t2) * (t1 - t2)) / 4;  // of the two pairs' means
            var_out += (l3 - l4) * (l3 - l4) / 4;
            ++n;
        }
    ASSERT_GT(n, 15);
    const double sigmas = (out - truth) / std::sqrt(var);
    std::printf("ball's underside: %d pixels, progressive / truth %.4f, %.2f sigma (renders' share of the "
                "variance %.2f)\n", n, out / truth, sigmas, var_out / var);
    EXPECT_LT(std::abs(out / truth - 1), 0.02);
}
