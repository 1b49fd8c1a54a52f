// Standard differential rendering, the baseline of the benchmarks: photo + (L_new - L_old).
#include <gtest/gtest.h>

#include <cmath>

#include "common/test_scenes.h"
#include "reference/standard_differential.h"

using namespace dp;
using namespace dp::test;

namespace {

using Sampling = StandardDifferentialRenderer::Sampling;

struct SunScene {
    SunProbe sun;
    Project project;
    Image photo;
    std::shared_ptr<RenderScene> scene;

    explicit SunScene(bool with_sphere) {
        sun.px = 0;  // near the zenith: the umbra lies straight under the sphere
        sun.py = 2;
        project = look_at_project(vec3(0, 2.5f, 4), vec3(0, 0, 0), 45);
        project.real.push_back(ground_plane(vec3(0.5f)));
        if (with_sphere) project.objects.push_back(sphere(vec3(0, 1, 0), 0.5f, diffuse(vec3(0.5f))));
        photo = analytic_ground_photo(project, 48, 36, sun, vec3(0.5f));
        scene = build(project, photo, sun.image());
    }
    /// Pixels whose centre ray reaches the ground well inside the umbra without meeting the sphere.
    std::vector<size_t> umbra_pixels() const {
        std::vector<size_t> out;
        const Camera& cam = scene->camera();
        for (int y = 0; y < cam.height(); ++y)
            for (int x = 0; x < cam.width(); ++x) {
                Ray r = cam.generate_ray(float(x), float(y));
                if (r.dir.y >= 0) continue;
                const float t = -r.org.y / r.dir.y;
                const vec3 p = r.org + t * r.dir;
                const vec3 oc = vec3(0, 1, 0) - r.org;
                const float miss = glm::length(oc - glm::dot(oc, r.dir) * r.dir);
                if (std::hypot(p.x, p.z) < 0.3f && miss > 0.55f) out.push_back(size_t(y) * cam.width() + x);
            }
        return out;
    }
};

}  // namespace

TEST(StandardDifferential, CorrelatedSamplingWithoutVirtualObjectsGivesThePhotoBitForBit) {
    SunScene s(false);
    StandardDifferentialRenderer r(s.scene, s.project.render, Sampling::Correlated, 2);
    ASSERT_TRUE(r.render_pass());
    EXPECT_TRUE(r.image() == s.photo);
    EXPECT_EQ(r.stats().samples_per_pixel, 2u);
}

TEST(StandardDifferential, IndependentSimulationsWithoutVirtualObjectsAverageToThePhoto) {
    SunScene s(false);
    StandardDifferentialRenderer r(s.scene, s.project.render, Sampling::Independent, 8);
    ASSERT_TRUE(r.render_pass());
    const Image d = r.dL_layer();
    double sum = 0, sum2 = 0, photo_sum = 0;
    size_t nonzero = 0;
    for (size_t i = 0; i < d.size(); ++i) {
        sum += d[i].y;
        sum2 += double(d[i].y) * d[i].y;
        photo_sum += s.photo[i].y;
        nonzero += d[i].y != 0;
    }
    const double n = double(d.size()), mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
    EXPECT_GT(nonzero, d.size() / 4) << "independent simulations must not cancel exactly";
    EXPECT_LT(std::abs(mean), 4 * sd / std::sqrt(n) + 1e-3 * photo_sum / n);
}

TEST(StandardDifferential, TheUmbraOfASphereUnderTheSunIsBlack) {
    SunScene s(true);
    for (Sampling sampling : {Sampling::Correlated, Sampling::Independent}) {
        StandardDifferentialRenderer r(s.scene, s.project.render, sampling, 4);
        ASSERT_TRUE(r.render_pass());
        const Image img = r.image();
        const std::vector<size_t> umbra = s.umbra_pixels();
        ASSERT_GT(umbra.size(), 10u);
        double lit = 0, shadow = 0;
        for (size_t i : umbra) {
            lit += s.photo[i].y;
            shadow += img[i].y;
        }
        // Only light bounced off the grey sphere reaches the umbra: a few % of the sunlit floor.
        EXPECT_LT(shadow / lit, 0.08) << "sampling " << int(sampling);
        EXPECT_GT(shadow / lit, -0.02) << "sampling " << int(sampling);
    }
}

TEST(StandardDifferential, PixelsOnTheObjectShowTheNewSimulationAndCountInAlpha) {
    SunScene s(true);
    StandardDifferentialRenderer r(s.scene, s.project.render, Sampling::Correlated, 4);
    ASSERT_TRUE(r.render_pass());
    vec2 px;
    ASSERT_TRUE(s.scene->camera().project(vec3(0, 1.5f, 0), px));  // the sphere's sunlit top
    const int x = int(std::lround(px.x)), y = int(std::lround(px.y + 2));
    EXPECT_FLOAT_EQ(r.alpha_layer().at(x, y).x, 1.0f);
    // A diffuse sphere lit from above: rho/pi * E * cos, cos close to 1 near the top.
    const double top = 0.5 / kPi * s.sun.normal_irradiance();
    EXPECT_GT(r.image().at(x, y).y, 0.6 * top);
    EXPECT_LT(r.image().at(x, y).y, 1.1 * top);
}

TEST(StandardDifferential, ACancelledPassAccumulatesNothing) {
    SunScene s(true);
    StandardDifferentialRenderer r(s.scene, s.project.render, Sampling::Correlated, 1);
    std::atomic<bool> cancel{true};
    EXPECT_FALSE(r.render_pass(&cancel));
    EXPECT_EQ(r.passes(), 0);
    EXPECT_TRUE(r.image() == s.photo);
}
