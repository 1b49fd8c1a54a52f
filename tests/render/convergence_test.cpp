// Progressive photon mapping is consistent: error against a high-photon reference falls as
// passes accumulate, at roughly the rate the radius schedule predicts.
#include <gtest/gtest.h>

#include <cmath>

#include "render/progressive.h"
#include "common/test_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {

double rmse(const Image& a, const Image& b) {
    double s = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        vec3 d = a[i] - b[i];
        s += glm::dot(d, d) / 3.0;
    }
    return std::sqrt(s / a.size());
}

/// A soft shadow's first gather radius, as the project gives it.
const RenderSettings project_settings = [] {
    RenderSettings s;
    s.initial_radius = 0.08f;
    return s;
}();

std::shared_ptr<RenderScene> soft_shadow_scene() {
    Project p = look_at_project(vec3(0, 2.2f, 3), vec3(-0.3f, 0.2f, 0), 40);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.objects.push_back(sphere(vec3(0, 0.5f, 0), 0.5f, diffuse(vec3(0.6f))));
    Image probe = make_sun_sky_probe(256, 128, glm::normalize(vec3(1, 1.5f, 0.3f)), vec3(800.0f), 3.0f,
                                     vec3(0.2f, 0.35f, 0.8f), vec3(0.7f, 0.8f, 0.9f));
    return build(p, Image(64, 48, vec3(0.5f)), probe);
}

}  // namespace

TEST(Convergence, ErrorAgainstAHighPhotonReferenceFallsAsPassesGrow) {
    auto scene = soft_shadow_scene();
    ProgressiveRenderer reference(scene, settings(400000, 1000, project_settings));
    for (int i = 0; i < 48; ++i) ASSERT_TRUE(reference.render_pass());
    Image truth = reference.image();

    ProgressiveRenderer r(scene, settings(50000, 7, project_settings));
    std::vector<double> log_n, log_e;
    for (int pass = 1; pass <= 32; ++pass) {
        ASSERT_TRUE(r.render_pass());
        if ((pass & (pass - 1)) == 0) {  // 1, 2, 4, ..., 32
            double e = rmse(r.image(), truth);
            log_n.push_back(std::log(double(pass)));
            log_e.push_back(std::log(e));
            std::printf("passes %2d  rmse %.5f\n", pass, e);
        }
    }
    // Least-squares slope of log(error) against log(passes).
    double mn = 0, me = 0;
    for (size_t i = 0; i < log_n.size(); ++i) mn += log_n[i], me += log_e[i];
    mn /= log_n.size();
    me /= log_e.size();
    double num = 0, den = 0;
    for (size_t i = 0; i < log_n.size(); ++i) num += (log_n[i] - mn) * (log_e[i] - me), den += (log_n[i] - mn) * (log_n[i] - mn);
    double slope = num / den;
    std::printf("slope %.3f\n", slope);
    EXPECT_LT(slope, -0.25);
    EXPECT_LT(std::exp(log_e.back()), 0.5 * std::exp(log_e.front()));
}
