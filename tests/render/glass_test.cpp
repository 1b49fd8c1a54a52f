// A glass sphere focuses the sun into a caustic on the floor, conserves flux, and is invisible
// with an index of refraction of 1.
#include <gtest/gtest.h>

#include <cmath>

#include "render/photon_tracer.h"
#include "render/progressive.h"
#include "assets/scattering.h"
#include "common/test_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {

struct GlassScene {
    SunProbe sun;
    vec3 center{0, 0.55f, 0};
    float radius = 0.5f;
    Project project = look_at_project(vec3(0, 3, 4), vec3(-0.4f, 0, 0), 45);
    std::shared_ptr<RenderScene> scene;
    GlassScene(float ior, vec3 ground_albedo) {
        project.real.push_back(ground_plane(ground_albedo));
        project.objects.push_back(sphere(center, radius, glass(ior)));
        scene = build(project, analytic_ground_photo(project, 96, 72, sun, ground_albedo), sun.image());
    }
};

/// Fraction of the flux entering a glass sphere that reaches the ground, by deterministic
/// splitting of every path over a fine grid of the cross-section (no Monte Carlo).
double fraction_reaching_ground(const RenderScene& scene, vec3 l, vec3 c, float R) {
    Frame f(l);
    const int n = 200;
    double total = 0, ground = 0;
    std::function<void(Ray, double, int)> follow = [&](Ray ray, double w, int depth) {
        if (w < 1e-6 || depth > 12) return;
        Hit h = scene.intersect(ray);
        if (!h) return;                                            // escaped to the sky
        if (!h.surface->is_virtual) { ground += w; return; }
        SpecularEvent refl, refr;
        split_glass(h.surface->material, h, ray.dir, refl, refr);
        follow(Ray{scene.offset_origin(h, refl.dir), refl.dir}, w * refl.weight.x, depth + 1);
        if (refr.weight.x > 0) follow(Ray{scene.offset_origin(h, refr.dir), refr.dir}, w * refr.weight.x, depth + 1);
    };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            vec2 d((i + 0.5f) / n * 2 - 1, (j + 0.5f) / n * 2 - 1);
            if (glm::dot(d, d) >= 1) continue;
            vec3 o = c + l * (2 * R) + (f.t * d.x + f.b * d.y) * R;
            total += 1;
            follow(Ray{o, -l}, 1.0, 0);
        }
    return ground / total;
}

}  // namespace

TEST(Glass, TheCausticPeakOnTheFloorIsBrighterThanItsSunlitSurroundings) {
    GlassScene s(1.5f, vec3(0.5f));
    PhotonPass pass = trace_photons(*s.scene, 5, 1, 1000000);
    PhotonMap map;
    const float r = 0.02f;
    map.build(pass.real, r);
    const double E = s.sun.normal_irradiance() * s.sun.direction().y;
    double peak = -1e30;
    vec3 axis_ground = s.center - s.sun.direction() * (s.center.y / s.sun.direction().y);
    for (float x = -0.6f; x <= 0.6f; x += 0.01f)
        for (float z = -0.6f; z <= 0.6f; z += 0.01f) {
            vec3 p = axis_ground + vec3(x, 0, z);
            peak = std::max(peak, map.gather(p, vec3(0, 1, 0)).x / (kPi * r * r));
        }
    // The total irradiance at the focus (E + dE) is several times the unshadowed floor's.
    EXPECT_GT(E + peak, 3.0 * E) << "peak dE " << peak << " E " << E;
}

TEST(Glass, FluxReachingTheFloorMatchesDeterministicSplittingWithinNoise) {
    GlassScene s(1.5f, vec3(0.0f));  // a black floor: no second bounces to count
    const int64_t N = 1000000;
    PhotonPass pass = trace_photons(*s.scene, 9, 1, N);
    double positive = 0, negative = 0;
    for (const Photon& p : pass.real) (p.flux.x > 0 ? positive : negative) += p.flux.x;
    ASSERT_LT(negative, 0);
    const double measured = positive / -negative;
    const double expected = fraction_reaching_ground(*s.scene, s.sun.direction(), s.center, s.radius);
    // Each photon entering the sphere reaches the floor or not: binomial, 4 sigma.
    const double n_hit = double(pass.stats.hit_virtual);
    const double sigma = std::sqrt(expected * (1 - expected) / n_hit);
    EXPECT_NEAR(measured, expected, 4 * sigma + 2e-3) << "sigma " << sigma;
    EXPECT_GT(expected, 0.8);
    EXPECT_LT(expected, 0.99);
}

TEST(Glass, GlassWithAnIndexOfOneIsInvisible) {
    GlassScene s(1.0f, vec3(0.5f));
    ProgressiveRenderer r(s.scene, settings(200000, 3));
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(r.render_pass());
    Image out = r.image();
    const Image& photo = s.scene->photo();
    double max_rel = 0;
    for (size_t i = 0; i < out.size(); ++i) {
        if (photo[i].x <= 0) continue;
        max_rel = std::max(max_rel, double(std::abs(out[i].x - photo[i].x) / photo[i].x));
    }
    EXPECT_LT(max_rel, 0.01);
}
