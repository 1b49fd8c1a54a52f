// Rectangle corners and known points clicked with Gaussian noise in a photo of a known camera,
// 200 draws a case: the stated uncertainty of these methods covers the error it should, as
// the vanishing lines' does (vanishing_monte_carlo_test.cpp).
#include <gtest/gtest.h>

#include "calibration/correspondences.h"
#include "line_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr int kDraws = 200;
constexpr double kClickNoise = 0.5;

/// How often the stated uncertainty covered the error: focal length within two standard
/// deviations, rotation and position within their 95 % ellipsoids.
struct Coverage {
    int draws = 0, focal = 0, rotation = 0, position = 0;
    double rate(int n) const { return double(n) / draws; }
    std::string summary() const {
        char buf[160];
        std::snprintf(buf, sizeof(buf), "%d draws: covers focal %.1f %%, rotation %.1f %%, "
                      "position %.1f %%", draws, 100 * rate(focal), 100 * rate(rotation),
                      100 * rate(position));
        return buf;
    }
};

/// A calibration from the clicked image points of the world points, in their order.
using Solve = std::function<CalibrationResult(const std::vector<ImagePoint>&)>;

/// kDraws draws of `solve` on the image points of `world` seen by `scene`'s camera, each
/// coordinate moved by Gaussian noise of kClickNoise px (seeded: reproducible).
Coverage coverage_of_clicks(const LineScene& scene, const std::vector<glm::dvec3>& world,
                            const Solve& solve) {
    std::mt19937 rng(20240601);
    std::normal_distribution<double> gauss(0.0, kClickNoise);
    const glm::dvec3 centre(scene.camera().position());
    Coverage c;
    for (int i = 0; i < kDraws; ++i) {
        std::vector<ImagePoint> clicks;
        for (const glm::dvec3& w : world) {
            const double dv = gauss(rng);  // in two statements: see LineScene::clicks
            const double du = gauss(rng);
            clicks.push_back(scene.pixel(w) + glm::dvec2(du, dv));
        }
        const CalibrationResult r = solve(clicks);
        const Uncertainty& u = r.uncertainty;
        ++c.draws;
        c.focal += !u.focal_free ||
                   std::abs(r.intrinsics.fx - scene.truth.fx) <= 1.96 * u.fx;
        c.rotation += mahalanobis2(rotation_error(r, scene.truth), u.rotation_cov) <= kChi2Dof3Q95;
        c.position += mahalanobis2(r.pose.position() - centre, u.position_cov) <= kChi2Dof3Q95;
    }
    return c;
}

void report(const char* name, const Coverage& c) {
    std::printf("%s: %s\n", name, c.summary().c_str());
    ::testing::Test::RecordProperty(name, c.summary());
}

/// 200 draws put "about 95 %" within 0.90..0.99 unless the stated uncertainty is too small
/// (below) or far too large (above).
void expect_about_95(double rate, const char* what) {
    EXPECT_GE(rate, 0.90) << what << ": the stated uncertainty is too small";
    EXPECT_LE(rate, 0.99) << what << ": the stated uncertainty is too large";
}

}  // namespace

TEST(ClickedPointsMonteCarlo, ARectanglesStatedUncertaintyCoversTheErrorInAboutNinetyFivePercentOfDraws) {
    const LineScene scene = ground_lines();
    const std::vector<glm::dvec3> corners = {{0, 0, 0}, {0.6, 0, 0}, {0.6, 0, 0.4}, {0, 0, 0.4}};
    // The focal length from the rectangle itself: focal length, rotation and position.
    const Coverage estimated = coverage_of_clicks(scene, corners, [&](const auto& c) {
        return calibrate_rectangle(c, 0.6, 0.4, scene.width, scene.height, std::nullopt, "r");
    });
    report("rectangle_focal_estimated", estimated);
    expect_about_95(estimated.rate(estimated.focal), "focal length");
    expect_about_95(estimated.rate(estimated.rotation), "rotation");
    expect_about_95(estimated.rate(estimated.position), "position");
    // The focal length given: the pose alone.
    const Intrinsics k = Intrinsics::centred(scene.width, scene.height, scene.truth.fx);
    const Coverage given = coverage_of_clicks(scene, corners, [&](const auto& c) {
        return calibrate_rectangle(c, 0.6, 0.4, scene.width, scene.height, k, "r");
    });
    report("rectangle_focal_given", given);
    expect_about_95(given.rate(given.rotation), "rotation");
    expect_about_95(given.rate(given.position), "position");
}

TEST(ClickedPointsMonteCarlo, KnownPointsStatedUncertaintyCoversTheErrorInAboutNinetyFivePercentOfDraws) {
    const LineScene scene = ground_lines();
    const std::vector<glm::dvec3> world = {{0, 0, 0},        {0.6, 0, 0},      {0.6, 0, 0.4},
                                           {0, 0, 0.4},      {0.3, 0.5, 0.2},  {0.1, 0.8, -0.3},
                                           {0.5, 0.3, -0.4}, {-0.3, 0.6, 0.1}};
    auto pairs = [&](const std::vector<ImagePoint>& c) {
        std::vector<PointCorrespondence> p;
        for (size_t i = 0; i < world.size(); ++i) p.push_back({world[i], c[i]});
        return p;
    };
    const Coverage estimated = coverage_of_clicks(scene, world, [&](const auto& c) {
        return calibrate_points(pairs(c), scene.width, scene.height, std::nullopt, "p");
    });
    report("points_intrinsics_estimated", estimated);
    expect_about_95(estimated.rate(estimated.focal), "focal length");
    expect_about_95(estimated.rate(estimated.rotation), "rotation");
    expect_about_95(estimated.rate(estimated.position), "position");
    const Intrinsics k = Intrinsics::centred(scene.width, scene.height, scene.truth.fx);
    const Coverage given = coverage_of_clicks(scene, world, [&](const auto& c) {
        return calibrate_points(pairs(c), scene.width, scene.height, k, "p");
    });
    report("points_focal_given", given);
    expect_about_95(given.rate(given.rotation), "rotation");
    expect_about_95(given.rate(given.position), "position");
}
