// Vanishing lines clicked with Gaussian noise in photos of a known camera, 200 draws a case:
// how often the camera is right, that a wrong one is never silent, and that the stated
// uncertainty covers the error it should.
#include <gtest/gtest.h>

#include "line_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr int kDraws = 200;
constexpr double kClickNoise = 0.5;

/// The figures in the test log and the XML report.
void report(const char* name, const DrawStats& s) {
    std::printf("%s: %s\n", name, s.summary().c_str());
    ::testing::Test::RecordProperty(name, s.summary());
}

/// Coverage of "about 95 %": 200 draws put the rate within 0.90..0.99 unless the stated
/// uncertainty is too small (below) or far too large (above).
void expect_about_95(double rate, const char* what) {
    EXPECT_GE(rate, 0.90) << what << ": the stated uncertainty is too small";
    EXPECT_LE(rate, 0.99) << what << ": the stated uncertainty is too large";
}

}  // namespace

TEST(VanishingCalibrationMonteCarlo, ThreeDirectionsWithShortVerticalEdgesGiveTheFocalWithinFivePercent) {
    const DrawStats s = monte_carlo(ground_lines_and_box_edges(), kDraws, kClickNoise, 0.05, 0.5);
    report("three_directions_short_vertical", s);
    EXPECT_EQ(s.refused, 0);
    EXPECT_GE(s.rate(s.focal_within), 0.95);
    EXPECT_EQ(s.silent_outliers, 0);
}

TEST(VanishingCalibrationMonteCarlo, TwoLongGroundDirectionsGiveTheFocalWithinTwoPercentAndTheRotationWithinHalfADegree) {
    const DrawStats s = monte_carlo(long_ground_lines(), kDraws, kClickNoise, 0.02, 0.5);
    report("two_long_ground_directions", s);
    EXPECT_EQ(s.refused, 0);
    EXPECT_GE(s.rate(s.focal_within), 0.95);
    EXPECT_GE(s.rate(s.rotation_within), 0.95);
}

TEST(VanishingCalibrationMonteCarlo, TheStatedUncertaintyCoversTheErrorInAboutNinetyFivePercentOfDraws) {
    for (const auto& [name, scene] :
         {std::pair{"coverage_three_directions", ground_lines_and_box_edges()},
          std::pair{"coverage_two_directions", long_ground_lines()}}) {
        SCOPED_TRACE(name);
        const DrawStats s = monte_carlo(scene, kDraws, kClickNoise, 0.05, 0.5);
        report(name, s);
        expect_about_95(s.rate(s.focal_covered), "focal length");
        expect_about_95(s.rate(s.rotation_covered), "rotation");
        expect_about_95(s.rate(s.position_covered), "position");
    }
}

TEST(VanishingCalibrationMonteCarlo, WeakLinesClickedAsPreciselyAsStatedNeverGiveASilentlyWrongFocalLength) {
    // Only a box's short edges, clicked at 2 px and said to be (--click-sigma 2): some draws
    // are far off, each must warn. Said to be 0.5 px, nine segments leave five residuals to
    // reveal the sloppier clicks, and by chance they sometimes do not: about 1 draw in 500
    // is then off by more than 20 % silently (docs/calibration.md), which no check of the
    // result can prevent, only an honest click precision.
    const DrawStats s = monte_carlo(box_edges(), kDraws, 2.0, 0.05, 0.5,
                                    [](VanishingInput& in) { in.click_sigma_px = 2.0; });
    report("box_edges_2px", s);
    EXPECT_GT(s.outliers, 0) << "no draw over 20 %: the case no longer tests the warning";
    EXPECT_EQ(s.silent_outliers, 0);
}

TEST(VanishingCalibrationMonteCarlo, LinesParallelInTheImageAreSolvedUnderNoise) {
    const DrawStats s = monte_carlo(parallel_x_lines(), kDraws, kClickNoise, 0.05, 0.5);
    report("parallel_x_lines", s);
    EXPECT_EQ(s.refused, 0);
    EXPECT_GE(s.rate(s.focal_within), 0.95);
    EXPECT_EQ(s.silent_outliers, 0);
    const DrawStats g = monte_carlo(parallel_x_lines(), kDraws, kClickNoise, 0.05, 0.5,
                                    [](VanishingInput& in) {
                                        in.y.clear();
                                        in.focal_px = 800;
                                    });
    report("parallel_x_lines_given_focal", g);
    EXPECT_EQ(g.refused, 0);
    EXPECT_GE(g.rate(g.rotation_within), 0.9);
}

TEST(VanishingCalibrationMonteCarlo, GivenTheFocalLengthShortVerticalEdgesSharpenTheRotationInsteadOfOutvotingLongLines) {
    // Fitted on their own and weighted equally, three 60 px vertical edges once tilted the
    // camera by degrees; weighted by their length they only add what they know.
    auto given = [](VanishingInput& in) { in.focal_px = 800; };
    const DrawStats ground = monte_carlo(ground_lines(), kDraws, kClickNoise, 0.05, 0.5, given);
    const DrawStats all =
        monte_carlo(ground_lines_and_box_edges(), kDraws, kClickNoise, 0.05, 0.5, given);
    report("ground_lines_given_focal", ground);
    report("ground_lines_and_box_edges_given_focal", all);
    EXPECT_EQ(all.refused, 0);
    EXPECT_GE(all.rotation_within, ground.rotation_within);
    EXPECT_LE(all.worst_rotation_deg, 2.0);  // never the degrees of an outvoted fit
    expect_about_95(all.rate(all.rotation_covered), "rotation");
}
