#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "base/euler.h"
#include "base/rng.h"
#include "image/image_io.h"
#include "probe/probe.h"

using namespace dp;

TEST(RealProbe, BlenderSunsetGivesTheExactIrradianceUnderImportanceSampling) {
    const std::string path = "/usr/share/blender/datafiles/studiolights/world/sunset.exr";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "Blender's studio lights not installed";
    Image img = load_image(path, "probe");
    ASSERT_FALSE(img.empty());
    const int w = img.width(), h = img.height();
    const float intensity = 1.5f;
    // A turn about Y keeps the upward plane's normal at probe-space +Y.
    Probe probe(img, euler_xyz_deg(vec3(0, 40, 0)), intensity);
    ASSERT_GT(probe.total_luminance_power(), 0.0);

    // Exact irradiance of the piecewise-constant map on an upward plane: within a row band,
    // the integral of max(cos theta, 0) over solid angle is (2 pi / W) (c_top^2 - c_bottom^2) / 2
    // with both cosines clamped at 0.
    const double pi = std::numbers::pi;
    dvec3 exact(0);
    for (int j = 0; j < h; ++j) {
        double c0 = std::max(0.0, std::cos(pi * j / h));
        double c1 = std::max(0.0, std::cos(pi * (j + 1) / h));
        double band = 2 * pi / w * (c0 * c0 - c1 * c1) / 2;
        for (int i = 0; i < w; ++i) exact += dvec3(img.at(i, j)) * double(intensity) * band;
    }

    const int n = 1000000;
    Rng rng(21, 3);
    dvec3 sum(0), sum_sq(0);
    for (int k = 0; k < n; ++k) {
        ProbeSample s = probe.sample(rng.uniform(), rng.uniform(), rng.uniform());
        ASSERT_GT(s.pdf, 0.0f);
        dvec3 f = dvec3(s.radiance) * double(std::max(0.0f, s.dir.y)) / double(s.pdf);
        sum += f;
        sum_sq += f * f;
    }
    dvec3 mean = sum / double(n);
    for (int c = 0; c < 3; ++c) {
        double stderr_c = std::sqrt(std::max(0.0, sum_sq[c] / n - mean[c] * mean[c]) / n);
        EXPECT_NEAR(mean[c], exact[c], std::max(5 * stderr_c, 1e-3 * exact[c]))
            << "channel " << c << ", map " << w << "x" << h;
        EXPECT_NEAR(mean[c], exact[c], 0.02 * exact[c]) << "channel " << c;
    }
}
