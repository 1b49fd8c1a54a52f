// The imported fSpy camera against the control points the fSpy user placed: the vanishing
// lines of each axis pass through that axis's vanishing point, and the origin point is where
// world (0, 0, 0) projects. On real projects written by fSpy (landscape) and on a portrait
// project written here the way fSpy 1.0 writes it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "calibration/fspy.h"
#include "common/fspy_files.h"

using namespace dp;
using namespace dp::test;

namespace {

namespace fs = std::filesystem;

/// fSpy's own files (DP_FSPY_SAMPLES_DIR, tests/CMakeLists.txt), not kept in this repository.
fs::path sample(const std::string& name) { return fs::path(DP_FSPY_SAMPLES_DIR) / name; }

void expect_matches_control_points(const fs::path& path, int lines) {
    if (!fs::exists(path)) GTEST_SKIP() << "fSpy sample not found: " << path;
    const FspyImport f = read_fspy(path.string());
    const ControlPointErrors e = control_point_errors(read_fspy_state(path.string()), f.result);
    EXPECT_EQ(e.lines, lines);
    EXPECT_LT(e.lines_px, 0.5);
    EXPECT_LT(e.origin_px, 0.5);
}

/// A portrait camera as fSpy 1.0 would save it, from control points made by projecting a box
/// through a known camera: the state, and the camera's pixel intrinsics.
struct PortraitScene {
    static constexpr int W = 1728, H = 2592;  // a portrait photo of fSpy 1.0.3's own example
    static constexpr double f = 1972.5, cx = 0.5 * W - 0.5 + 37, cy = 0.5 * H - 0.5 - 52;
    glm::dmat3 R;  ///< Blender camera-to-world (columns: right, up, backwards)
    glm::dvec3 C{3.1, -5.4, 1.7};

    PortraitScene() {
        const glm::dvec3 target(0.4, 0.3, 0.5);
        const glm::dvec3 back = glm::normalize(C - target);
        const glm::dvec3 right = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), back));
        // A little roll, as a hand-held phone has.
        const glm::dvec3 up0 = glm::cross(back, right);
        const double roll = 0.06;
        R = glm::dmat3(std::cos(roll) * right + std::sin(roll) * up0,
                       -std::sin(roll) * right + std::cos(roll) * up0, back);
    }

    /// A Blender world point in fSpy's relative image coordinates ([0, 1], y down).
    json relative(const glm::dvec3& X) const {
        const glm::dvec3 c = glm::transpose(R) * (X - C);  // Blender camera: -Z forward, +Y up
        const double u = f * c.x / -c.z + cx, v = f * -c.y / -c.z + cy;
        return {{"x", (u + 0.5) / W}, {"y", (v + 0.5) / H}};
    }
    /// fSpy's image plane (the longer side spans [-1, 1], +y up) from pixels.
    json plane(double u, double v) const {
        const double half = 0.5 * std::max(W, H);
        return {{"x", (u + 0.5 - 0.5 * W) / half}, {"y", (0.5 * H - (v + 0.5)) / half}};
    }
    json vanishing_point(const glm::dvec3& d) const {
        const glm::dvec3 c = glm::transpose(R) * d;
        return plane(f * c.x / -c.z + cx, f * -c.y / -c.z + cy);
    }
    json segment(const glm::dvec3& a, const glm::dvec3& b) const {
        return json::array({relative(a), relative(b)});
    }
    static json rows(const glm::dmat4& m) {
        json out = json::array();
        for (int r = 0; r < 4; ++r) out.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
        return out;
    }

    /// The camera parameters fSpy 1.0 computes: its "horizontal" field of view across the
    /// longer side (here the height), and its vertical one from it over the aspect.
    json camera_parameters() const {
        const double rel = f / (0.5 * std::max(W, H));
        const double aspect = double(W) / H;
        glm::dmat4 M(R);
        M[3] = glm::dvec4(C, 1);
        return {{"principalPoint", plane(cx, cy)},
                {"viewTransform", {{"rows", rows(glm::inverse(M))}}},
                {"cameraTransform", {{"rows", rows(M)}}},
                {"horizontalFieldOfView", 2 * std::atan(1 / rel)},
                {"verticalFieldOfView", 2 * std::atan(1 / (aspect * rel))},
                {"vanishingPoints",
                 {vanishing_point({1, 0, 0}), vanishing_point({0, 1, 0}), vanishing_point({0, 0, 1})}},
                {"vanishingPointAxes", {"xPositive", "yPositive", "zPositive"}},
                {"relativeFocalLength", rel},
                {"imageWidth", W},
                {"imageHeight", H}};
    }

    /// The project state: two vanishing points from a 1.2 x 0.8 x 1.0 m box's edges, the
    /// principal point placed by hand, the origin at a corner of the box.
    json state() const {
        const double a = 1.2, b = 0.8, h = 1.0;
        return {
            {"globalSettings", {{"calibrationMode", "TwoVanishingPoints"}}},
            {"calibrationSettingsBase",
             {{"referenceDistanceAxis", "xPositive"},
              {"referenceDistance", a},
              {"referenceDistanceUnit", "Meters"},
              {"firstVanishingPointAxis", "xPositive"},
              {"secondVanishingPointAxis", "yPositive"}}},
            {"calibrationSettings2VP", {{"principalPointMode", "Manual"}, {"quadModeEnabled", false}}},
            {"controlPointsStateBase",
             {{"principalPoint", {{"x", (cx + 0.5) / W}, {"y", (cy + 0.5) / H}}},
              {"origin", relative({0, 0, 0})},
              {"firstVanishingPoint",
               {{"lineSegments", {segment({0, 0, 0}, {a, 0, 0}), segment({0, b, h}, {a, b, h})}}}}}},
            {"controlPointsState2VP",
             {{"secondVanishingPoint",
               {{"lineSegments", {segment({a, 0, 0}, {a, b, 0}), segment({0, 0, h}, {0, b, h})}}}},
              {"thirdVanishingPoint",
               {{"lineSegments", {segment({a, 0, 0}, {a, 0, h}), segment({0, b, 0}, {0, b, h})}}}}}},
            {"cameraParameters", camera_parameters()}};
    }
};

class FspyControlPoints : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("dp_fspy_cp_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string file(const std::string& name) const { return (dir_ / name).string(); }
    fs::path dir_;
};

}  // namespace

TEST_F(FspyControlPoints, AShiftedLandscapeProjectMatchesItsVanishingLinesAndOrigin) {
    // Quad mode (the second group from the first's ends) and a principal point from a third
    // vanishing point: 6 lines.
    expect_matches_control_points(sample("shifted_landscape.fspy"), 6);
}

TEST_F(FspyControlPoints, AProjectInMillimetresMatchesItsVanishingLinesAndOrigin) {
    expect_matches_control_points(sample("fspy_github_bug_5.fspy"), 4);
}

TEST_F(FspyControlPoints, APortraitProjectGetsItsFocalLengthAcrossTheHeight) {
    const PortraitScene scene;
    const json state = scene.state();
    std::vector<uint8_t> jpeg;
    cv::imencode(".jpg", cv::Mat(12, 8, CV_8UC3, cv::Scalar(40, 80, 120)), jpeg);
    write_fspy(file("portrait.fspy"), state, jpeg);
    const FspyImport f = read_fspy(file("portrait.fspy"));
    const Intrinsics& k = f.result.intrinsics;
    EXPECT_EQ(k.width, PortraitScene::W);
    EXPECT_EQ(k.height, PortraitScene::H);
    EXPECT_NEAR(k.fx / PortraitScene::f, 1.0, 1e-3);
    EXPECT_NEAR(k.fy / PortraitScene::f, 1.0, 1e-3);
    EXPECT_NEAR(k.cx, PortraitScene::cx, 0.01);
    EXPECT_NEAR(k.cy, PortraitScene::cy, 0.01);
    EXPECT_TRUE(f.result.warnings.empty()) << f.result.warnings.front();
    const ControlPointErrors e = control_point_errors(state, f.result);
    EXPECT_EQ(e.lines, 4);
    EXPECT_LT(e.lines_px, 0.5);
    EXPECT_LT(e.origin_px, 0.5);

    // The field of view taken across the width, as the importer once did (fx 1315 px), moves
    // the vanishing points far enough that the lines miss them by many pixels: the check can
    // tell.
    CalibrationResult across_width = f.result;
    across_width.intrinsics.fx = across_width.intrinsics.fy =
        0.5 * k.width / std::tan(0.5 * state["cameraParameters"]["horizontalFieldOfView"].get<double>());
    EXPECT_GT(control_point_errors(state, across_width).lines_px, 5.0);
}

TEST_F(FspyControlPoints, APortraitProjectWithOnlyTheFieldOfViewMatchesToo) {
    const PortraitScene scene;
    json state = scene.state();
    state["cameraParameters"].erase("relativeFocalLength");
    write_fspy(file("fov.fspy"), state, {});
    const FspyImport f = read_fspy(file("fov.fspy"));
    EXPECT_NEAR(f.result.intrinsics.fx / PortraitScene::f, 1.0, 1e-3);
    const ControlPointErrors e = control_point_errors(state, f.result);
    EXPECT_LT(e.lines_px, 0.5);
    EXPECT_LT(e.origin_px, 0.5);
}

TEST_F(FspyControlPoints, APortraitCameraExportedAsJsonImportsAsTheProjectDoes) {
    const PortraitScene scene;
    const json state = scene.state();
    std::ofstream(file("camera-parameters.json")) << state["cameraParameters"].dump(2);
    const FspyImport f = read_fspy(file("camera-parameters.json"));
    EXPECT_TRUE(f.from_json_export);
    EXPECT_NEAR(f.result.intrinsics.fx / PortraitScene::f, 1.0, 1e-3);
    const ControlPointErrors e = control_point_errors(state, f.result);
    EXPECT_LT(e.lines_px, 0.5);
    EXPECT_LT(e.origin_px, 0.5);
}
