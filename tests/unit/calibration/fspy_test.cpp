#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "base/error.h"
#include "calibration/fspy.h"
#include "common/input_error.h"
#include "common/fspy_files.h"

using namespace dp;
using dp::test::input_error_message;
using dp::test::write_fspy;
using json = nlohmann::json;

namespace {

std::vector<uint8_t> small_png() {
    std::vector<uint8_t> bytes;
    cv::imencode(".png", cv::Mat(6, 8, CV_8UC3, cv::Scalar(10, 20, 30)), bytes);
    return bytes;
}

/// State as fSpy saves it, with a Blender camera-to-world matrix and fSpy's relative
/// principal point.
json state_for(const std::vector<std::vector<double>>& camera_to_world, double hfov, double ppx,
               double ppy, int w, int h, const char* unit = "Meters") {
    return json{{"calibrationSettingsBase",
                 {{"referenceDistanceAxis", "xPositive"},
                  {"referenceDistance", 1.0},
                  {"referenceDistanceUnit", unit}}},
                {"cameraParameters",
                 {{"principalPoint", {{"x", ppx}, {"y", ppy}}},
                  {"cameraTransform", {{"rows", camera_to_world}}},
                  {"horizontalFieldOfView", hfov},
                  {"imageWidth", w},
                  {"imageHeight", h},
                  {"relativeFocalLength", 1.0 / std::tan(0.5 * hfov)}}}};
}

class Fspy : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("dp_fspy_" + std::string(
                                 ::testing::UnitTest::GetInstance()->current_test_info()->name()));
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string file(const std::string& name) const { return (dir_ / name).string(); }
    std::filesystem::path dir_;
};

}  // namespace

TEST_F(Fspy, ABlenderCameraLookingAlongPlusYBecomesOursLookingAlongMinusZ) {
    // Blender: camera 5 m in front of the origin (-Y), 1 m up, rotated 90 degrees about X so
    // it looks along +Y with its up along +Z.
    const std::vector<std::vector<double>> M = {
        {1, 0, 0, 0}, {0, 0, -1, -5}, {0, 1, 0, 1}, {0, 0, 0, 1}};
    write_fspy(file("a.fspy"), state_for(M, 1.0, 0.0, 0.0, 800, 600), small_png());
    FspyImport f = read_fspy(file("a.fspy"));
    Camera cam = f.result.camera();
    EXPECT_NEAR(glm::length(cam.position() - vec3(0, 1, 5)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(cam.forward() - vec3(0, 0, -1)), 0.0f, 1e-5f);
    // World up appears up in the image, world +X to the right.
    vec2 centre, above, right;
    ASSERT_TRUE(cam.project(vec3(0, 1, 0), centre));
    ASSERT_TRUE(cam.project(vec3(0, 1.5f, 0), above));
    ASSERT_TRUE(cam.project(vec3(0.5f, 1, 0), right));
    EXPECT_NEAR(centre.x, 399.5f, 1e-3f);
    EXPECT_NEAR(centre.y, 299.5f, 1e-3f);
    EXPECT_LT(above.y, centre.y);
    EXPECT_GT(right.x, centre.x);
    // A horizontal field of view of 1 radian.
    EXPECT_NEAR(f.result.intrinsics.fx, 400.0 / std::tan(0.5), 1e-9);
    EXPECT_EQ(f.image_extension, ".png");
    EXPECT_EQ(f.image, small_png());
    EXPECT_TRUE(std::isnan(f.result.rms_px));
}

TEST_F(Fspy, AKnownCameraRoundTripsExactly) {
    // Any rotation and position, a shifted principal point, centimetres.
    const double a = 0.4, b = -0.7;
    const glm::dmat3 Rz(glm::dvec3(std::cos(a), std::sin(a), 0),
                        glm::dvec3(-std::sin(a), std::cos(a), 0), glm::dvec3(0, 0, 1));
    const glm::dmat3 Rx(glm::dvec3(1, 0, 0), glm::dvec3(0, std::cos(b), std::sin(b)),
                        glm::dvec3(0, -std::sin(b), std::cos(b)));
    const glm::dmat3 Rb = Rz * Rx;
    const glm::dvec3 Cb(120, -340, 155);  // centimetres, Blender axes
    std::vector<std::vector<double>> M(4, std::vector<double>(4, 0.0));
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) M[size_t(r)][size_t(c)] = Rb[c][r];
        M[size_t(r)][3] = Cb[r];
    }
    M[3][3] = 1;
    // Portrait: the height spans [-1, 1] in fSpy's image plane, and its "horizontal" field
    // of view is across the height, the longer side.
    const int W = 600, H = 900;
    const double hfov = 0.9, ppx = 0.1, ppy = -0.2;
    write_fspy(file("b.fspy"), state_for(M, hfov, ppx, ppy, W, H, "Centimeters"), small_png());
    FspyImport f = read_fspy(file("b.fspy"));
    const Intrinsics& k = f.result.intrinsics;
    EXPECT_EQ(k.width, W);
    EXPECT_EQ(k.height, H);
    EXPECT_NEAR(2 * std::atan(0.5 * H / k.fx), hfov, 1e-12);
    EXPECT_NEAR(k.fy, k.fx, 1e-12);
    // One unit of the image plane is half the height: x in [-2/3, 2/3], y in [-1, 1] (up).
    EXPECT_NEAR(k.cx, 0.5 * W + ppx * 0.5 * H - 0.5, 1e-9);
    EXPECT_NEAR(k.cy, 0.5 * H - ppy * 0.5 * H - 0.5, 1e-9);
    // Position: Blender (x, y, z) cm -> ours (x, z, -y) m.
    const glm::dvec3 c = f.result.pose.position();
    EXPECT_NEAR(c.x, 1.20, 1e-12);
    EXPECT_NEAR(c.y, 1.55, 1e-12);
    EXPECT_NEAR(c.z, 3.40, 1e-12);
    // Directions: the Blender camera's -Z (forward) and +Y (up) map to OpenCV +Z and -Y.
    auto to_ours = [](glm::dvec3 v) { return glm::dvec3(v.x, v.z, -v.y); };
    const glm::dmat3 Rt = glm::transpose(f.result.pose.R);
    const glm::dvec3 fwd = Rt * glm::dvec3(0, 0, 1), up = Rt * glm::dvec3(0, -1, 0);
    EXPECT_NEAR(glm::length(fwd - to_ours(Rb * glm::dvec3(0, 0, -1))), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(up - to_ours(Rb * glm::dvec3(0, 1, 0))), 0.0, 1e-12);
}

TEST_F(Fspy, BrokenFilesAreInputErrors) {
    std::ofstream(file("text.fspy")) << "hello";
    EXPECT_NE(input_error_message([&] { read_fspy(file("text.fspy")); }).find("not an fSpy project"),
              std::string::npos);
    EXPECT_NE(input_error_message([&] { read_fspy(file("missing.fspy")); }).find("file not found"),
              std::string::npos);
    const std::vector<std::vector<double>> I = {
        {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    write_fspy(file("v2.fspy"), state_for(I, 1.0, 0, 0, 8, 6), small_png(), 2);
    EXPECT_NE(input_error_message([&] { read_fspy(file("v2.fspy")); }).find("unsupported fSpy project version 2"),
              std::string::npos);
    json no_camera = state_for(I, 1.0, 0, 0, 8, 6);
    no_camera["cameraParameters"] = nullptr;
    write_fspy(file("nocam.fspy"), no_camera, small_png());
    EXPECT_NE(input_error_message([&] { read_fspy(file("nocam.fspy")); }).find("no camera parameters"),
              std::string::npos);
    // Truncated: the image announced in the header is missing.
    write_fspy(file("full.fspy"), state_for(I, 1.0, 0, 0, 8, 6), small_png());
    std::filesystem::resize_file(file("full.fspy"), std::filesystem::file_size(file("full.fspy")) - 10);
    EXPECT_NE(input_error_message([&] { read_fspy(file("full.fspy")); }).find("truncated"), std::string::npos);
}

namespace {

const std::vector<std::vector<double>> kLookingAlongPlusY = {
    {1, 0, 0, 0}, {0, 0, -1, -5}, {0, 1, 0, 1}, {0, 0, 0, 1}};

bool has_warning(const FspyImport& f, const std::string& text) {
    for (const std::string& w : f.result.warnings)
        if (w.find(text) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_F(Fspy, NoUnitIsNotAnUnknownUnitButSaysTheLengthsAreTakenAsMetres) {
    write_fspy(file("n.fspy"), state_for(kLookingAlongPlusY, 1.0, 0, 0, 800, 600, "No unit"),
               small_png());
    const FspyImport f = read_fspy(file("n.fspy"));
    EXPECT_EQ(f.unit, "No unit");
    EXPECT_FALSE(has_warning(f, "unknown distance unit"));
    EXPECT_TRUE(has_warning(f, "has no unit"));
    EXPECT_NEAR(f.result.pose.position().z, 5.0, 1e-12);
}

TEST_F(Fspy, YardsOfEarlyFspyVersionsBecomeMetresAsThreeFeetEach) {
    write_fspy(file("y.fspy"), state_for(kLookingAlongPlusY, 1.0, 0, 0, 800, 600, "Yards"),
               small_png());
    const FspyImport f = read_fspy(file("y.fspy"));
    EXPECT_TRUE(f.result.warnings.empty()) << f.result.warnings.front();
    EXPECT_NEAR(f.result.pose.position().z, 5 * 3 * 0.3048, 1e-12);
    EXPECT_NEAR(f.result.pose.position().y, 1 * 3 * 0.3048, 1e-12);
}

TEST_F(Fspy, AnUnknownUnitAndAMissingReferenceDistanceAreWarnedAbout) {
    json s = state_for(kLookingAlongPlusY, 1.0, 0, 0, 800, 600, "Furlongs");
    write_fspy(file("u.fspy"), s, small_png());
    EXPECT_TRUE(has_warning(read_fspy(file("u.fspy")), "unknown distance unit 'Furlongs'"));
    s = state_for(kLookingAlongPlusY, 1.0, 0, 0, 800, 600);
    s["calibrationSettingsBase"]["referenceDistanceAxis"] = nullptr;
    write_fspy(file("r.fspy"), s, small_png());
    EXPECT_TRUE(has_warning(read_fspy(file("r.fspy")), "sets no reference distance"));
}

TEST_F(Fspy, TheExportedCameraParametersJsonIsReadByItsContent) {
    // File > Export > Camera parameters as JSON: the cameraParameters object alone, whatever
    // the file's name.
    const json state = state_for(kLookingAlongPlusY, 1.0, 0.1, -0.05, 800, 600, "Meters");
    write_fspy(file("p.fspy"), state, small_png());
    std::ofstream(file("camera.txt")) << state["cameraParameters"].dump(2);
    const FspyImport project = read_fspy(file("p.fspy"));
    const FspyImport exported = read_fspy(file("camera.txt"));
    EXPECT_FALSE(project.from_json_export);
    EXPECT_TRUE(exported.from_json_export);
    EXPECT_TRUE(exported.image.empty());
    EXPECT_EQ(exported.unit, "");
    EXPECT_TRUE(has_warning(exported, "no distance unit"));
    const Intrinsics &a = project.result.intrinsics, &b = exported.result.intrinsics;
    EXPECT_EQ(b.width, 800);
    EXPECT_DOUBLE_EQ(b.fx, a.fx);
    EXPECT_DOUBLE_EQ(b.cx, a.cx);
    EXPECT_DOUBLE_EQ(b.cy, a.cy);
    EXPECT_NEAR(glm::length(exported.result.pose.position() - project.result.pose.position()),
                0.0, 1e-12);
}

TEST_F(Fspy, AFieldOfViewAloneGivesTheFocalLengthAcrossTheLongerSide) {
    json s = state_for(kLookingAlongPlusY, 0.8, 0, 0, 600, 800);
    s["cameraParameters"].erase("relativeFocalLength");
    write_fspy(file("h.fspy"), s, small_png());
    EXPECT_NEAR(read_fspy(file("h.fspy")).result.intrinsics.fx, 400 / std::tan(0.4), 1e-9);
}

TEST_F(Fspy, AFieldOfViewThatContradictsTheRelativeFocalLengthIsWarnedAbout) {
    json s = state_for(kLookingAlongPlusY, 0.8, 0, 0, 600, 800);
    // Across the width, as fSpy versions before 1.0 wrote it: no warning.
    s["cameraParameters"]["horizontalFieldOfView"] = 2 * std::atan(0.75 * std::tan(0.4));
    write_fspy(file("w.fspy"), s, small_png());
    const FspyImport f = read_fspy(file("w.fspy"));
    EXPECT_TRUE(f.result.warnings.empty()) << f.result.warnings.front();
    EXPECT_NEAR(f.result.intrinsics.fx, 400 / std::tan(0.4), 1e-9);
    s["cameraParameters"]["horizontalFieldOfView"] = 1.3;
    write_fspy(file("x.fspy"), s, small_png());
    EXPECT_TRUE(has_warning(read_fspy(file("x.fspy")), "does not match relativeFocalLength"));
}

TEST_F(Fspy, MalformedCameraFieldsAreInputErrorsNamingTheField) {
    auto message = [&](const std::string& name, const json& state) {
        write_fspy(file(name), state, small_png());
        return input_error_message([&] { read_fspy(file(name)); });
    };
    json s = state_for(kLookingAlongPlusY, 1.0, 0, 0, 800, 600);
    s["cameraParameters"]["imageWidth"] = 0;
    EXPECT_NE(message("w.fspy", s).find("cameraParameters.imageWidth"), std::string::npos);
    s = state_for(kLookingAlongPlusY, 1.0, 0, 0, 800, 600);
    s["cameraParameters"]["cameraTransform"]["rows"][1] = json::array({0, 1});
    EXPECT_NE(message("t.fspy", s).find("cameraParameters.cameraTransform"), std::string::npos);
    s = state_for(kLookingAlongPlusY, 1.0, 0, 0, 800, 600);
    s["cameraParameters"]["principalPoint"] = "centre";
    EXPECT_NE(message("p.fspy", s).find("cameraParameters.principalPoint"), std::string::npos);
    s = state_for(kLookingAlongPlusY, 1.0, 0, 0, 800, 600);
    s["cameraParameters"].erase("relativeFocalLength");
    s["cameraParameters"].erase("horizontalFieldOfView");
    EXPECT_NE(message("f.fspy", s).find("cameraParameters.horizontalFieldOfView"),
              std::string::npos);
    s = state_for(kLookingAlongPlusY, 1.0, 0, 0, 800, 600);
    s["calibrationSettingsBase"]["referenceDistanceUnit"] = 3;
    EXPECT_NE(message("u.fspy", s).find("referenceDistanceUnit"), std::string::npos);
    // A JSON file that is not fSpy's export names what it lacks.
    std::ofstream(file("project.json")) << R"({"photo": {"path": "a.jpg"}})";
    EXPECT_NE(input_error_message([&] { read_fspy(file("project.json")); }).find("no cameraTransform"),
              std::string::npos);
    std::ofstream(file("cut.json")) << R"({"cameraTransform": {"rows": [[1, 0)";
    EXPECT_NE(input_error_message([&] { read_fspy(file("cut.json")); }).find("invalid JSON"),
              std::string::npos);
}
