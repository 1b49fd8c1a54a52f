// Light the real surroundings send at a virtual object and that it sends back onto them: under
// a white ball resting on a white floor in sunlight from straight above, the umbra is lit only
// by sunlight the floor reflects up to the ball and the ball reflects back down.
#include <gtest/gtest.h>

#include <cmath>

#include "common/test_scenes.h"
#include "reference/path_tracer.h"
#include "render/progressive.h"

using namespace dp;
using namespace dp::test;

TEST(SurroundLight, TheUmbraUnderABallIsLitByTheFloorViaTheBallAsInThePathTracer) {
    SunProbe sun;
    sun.px = 0;  // near the zenith
    sun.py = 2;
    const vec3 white(0.8f);
    Project p = look_at_project(vec3(0, 1.2f, 2.2f), vec3(0, 0.1f, 0), 45);
    p.real.push_back(ground_plane(white));
    p.objects.push_back(sphere(vec3(0, 0.5f, 0), 0.5f, diffuse(white)));
    p.render.initial_radius = 0.05f;
    const int w = 64, h = 48;
    auto scene = build(p, analytic_ground_photo(p, w, h, sun, white), sun.image());

    ReferenceOptions ro;
    ro.samples_per_pixel = 512;
    ro.seed = 3;
    const Image truth = render_reference(*scene, ro);
    ProgressiveRenderer r(scene, settings(200000, 5, p.render));
    for (int i = 0; i < 24; ++i) ASSERT_TRUE(r.render_pass());
    const Image out = r.image();

    // Floor pixels inside the umbra (under the ball, sun overhead) that the ball does not hide.
    const Camera& cam = scene->camera();
    double sum_truth = 0, sum_out = 0, sum_lit = 0;
    int n = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Ray ray = cam.generate_ray(float(x), float(y));
            if (ray.dir.y >= 0) continue;
            const vec3 g = ray.org - ray.dir * (ray.org.y / ray.dir.y);
            const vec3 oc = vec3(0, 0.5f, 0) - ray.org;
            const bool hidden = glm::length(oc - glm::dot(oc, ray.dir) * ray.dir) < 0.55f;
            const float d = std::hypot(g.x, g.z);
            if (hidden || d < 0.15f || d > 0.42f) continue;
            sum_truth += luminance(truth.at(x, y));
            sum_out += luminance(out.at(x, y));
            sum_lit += luminance(scene->photo().at(x, y));
            ++n;
        }
    ASSERT_GT(n, 15);
    std::printf("umbra: %d pixels, truth %.4f, differential %.4f, sunlit floor %.4f\n", n, sum_truth / n,
                sum_out / n, sum_lit / n);
    // The bounce light is a few % of the sunlit floor; without it the umbra would be black.
    EXPECT_GT(sum_truth / sum_lit, 0.01);
    EXPECT_NEAR(sum_out / sum_truth, 1.0, 0.15);
}
