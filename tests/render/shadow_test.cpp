// A diffuse sphere over a plane under one bright probe pixel: the umbra is known exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "render/photon_tracer.h"
#include "render/progressive.h"
#include "common/test_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {

struct ShadowScene {
    SunProbe sun;
    vec3 albedo{0.5f};
    vec3 center{0, 1, 0};
    float radius = 0.5f;
    int w = 160, h = 120;
    Project project = look_at_project(vec3(0, 5, 6), vec3(-0.6f, 0, 0), 45);
    std::shared_ptr<RenderScene> scene;

    ShadowScene() {
        project.real.push_back(ground_plane(albedo));
        project.objects.push_back(sphere(center, radius, diffuse(vec3(0.5f))));
        project.render.photons_per_pass = 200000;
        // ~500 photons of the umbra per gather disk and pass: ~2.2% noise per pixel after
        // four passes, so 10% per pixel is a 4-sigma bound.
        project.render.initial_radius = 0.03f;
        scene = build(project, analytic_ground_photo(project, w, h, sun, albedo), sun.image());
    }
    /// Distance from the sphere's centre to the line from ground point x towards the sun.
    float line_distance(vec3 x) const {
        return distance_to_line(center, x, sun.direction());
    }
};

}  // namespace

TEST(DirectionalShadow, InsideTheUmbraTheChangeCancelsThePhotoWithinTwoPercent) {
    ShadowScene s;
    ProgressiveRenderer renderer(s.scene, settings(200000, 7, s.project.render));
    for (int i = 0; i < 4; ++i) ASSERT_TRUE(renderer.render_pass());
    Image out = renderer.image();
    Image dL = renderer.dL_layer();
    const Camera& cam = s.scene->camera();
    double sum_ratio = 0;
    int count = 0;
    for (int y = 0; y < s.h; ++y)
        for (int x = 0; x < s.w; ++x) {
            Ray r = cam.generate_ray(float(x), float(y));
            if (r.dir.y >= 0) continue;
            vec3 p = r.org + r.dir * (-r.org.y / r.dir.y);
            // Deep inside the umbra: the pixel footprint and gather radius stay in shadow.
            if (s.line_distance(p) > 0.75f * s.radius) continue;
            if (s.scene->intersect_virtual(r)) continue;  // the sphere hides the ground here
            float photo = s.scene->photo().at(x, y).x;
            ASSERT_GT(photo, 0);
            sum_ratio += -dL.at(x, y).x / photo;
            EXPECT_NEAR(out.at(x, y).x / photo, 0.0f, 0.1f) << "pixel " << x << "," << y;
            ++count;
        }
    ASSERT_GT(count, 50);
    EXPECT_NEAR(sum_ratio / count, 1.0, 0.02);
}

TEST(DirectionalShadow, UmbraAreaMatchesTheSpheresProjectionOntoTheGround) {
    ShadowScene s;
    PhotonPass pass = trace_photons(*s.scene, 3, 1, 1000000);
    PhotonMap map;
    const float r = 0.02f;
    map.build(pass.real, r);
    const double E = s.sun.normal_irradiance() * s.sun.direction().y;  // on the ground
    // Count ground samples darkened by more than half, on a grid around the shadow.
    const float step = 0.01f;
    int shadowed = 0;
    vec3 c = s.center - s.sun.direction() * (s.center.y / s.sun.direction().y);
    for (float x = c.x - 1.5f; x < c.x + 1.5f; x += step)
        for (float z = c.z - 1.5f; z < c.z + 1.5f; z += step) {
            double dE = map.gather(vec3(x, 0, z), vec3(0, 1, 0)).x / (kPi * r * r);
            if (dE < -0.5 * E) ++shadowed;
        }
    double area = shadowed * double(step) * step;
    double expected = kPi * s.radius * s.radius / s.sun.direction().y;  // ellipse pi R^2 / sin(elev)
    EXPECT_NEAR(area / expected, 1.0, 0.03) << "area " << area << " expected " << expected;
}

TEST(DirectionalShadow, NegativeFluxEqualsTheFluxThroughTheSpheresCrossSection) {
    ShadowScene s;
    const int64_t N = 1000000;
    // The probe's photons alone: light from the floor also darkens and lightens it elsewhere.
    PhotonPass pass = trace_photons(*s.scene, 11, 1, N, nullptr, {.from_surroundings = false});
    double negative = 0, photon_flux = 0;
    int64_t n_negative = 0;
    for (const Photon& p : pass.real)
        if (p.flux.x < 0) {
            negative += p.flux.x;
            photon_flux = -p.flux.x;
            ++n_negative;
        }
    ASSERT_GT(n_negative, 0);
    const double expected = s.sun.normal_irradiance() * kPi * s.radius * s.radius;
    // Each photon carries the same flux; the hit count is binomial(N, p): 4 sigma bound.
    const double p = double(n_negative) / N;
    const double sigma = photon_flux * std::sqrt(N * p * (1 - p));
    EXPECT_NEAR(-negative, expected, 4 * sigma + 1e-9 * expected)
        << "sigma " << sigma << " (" << 100 * sigma / expected << "% of the flux)";
    // No photon lands anywhere but behind the sphere on the first segment.
    EXPECT_EQ(pass.stats.hit_virtual, uint64_t(n_negative));
}
