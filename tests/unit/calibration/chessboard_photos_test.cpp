// Calibration from real photographs: OpenCV's own chessboard samples (Debian package opencv-doc).
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include <opencv2/imgproc.hpp>

#include "base/error.h"
#include "calibration/chessboard.h"
#include "common/input_error.h"
#include "image/image_io.h"

using namespace dp;

namespace {

const char* kSampleDir = "/usr/share/doc/opencv-doc/examples/data";

/// left01.jpg ... left14.jpg as the package ships them (left10 is not among them).
std::vector<std::string> sample_photos() {
    std::vector<std::string> paths;
    for (int i = 1; i <= 14; ++i) {
        char name[32];
        std::snprintf(name, sizeof(name), "/left%02d.jpg", i);
        std::string path = kSampleDir + std::string(name);
        if (std::filesystem::exists(path)) paths.push_back(path);
    }
    return paths;
}

const ChessboardSpec kBoard{9, 6, 0.025};

/// Detected once for all tests of this file.
const std::vector<ChessboardView>& sample_views() {
    static const std::vector<ChessboardView> views = [] {
        std::vector<ChessboardView> v;
        for (const std::string& p : sample_photos()) v.push_back(detect_chessboard(p, kBoard));
        return v;
    }();
    return views;
}

}  // namespace

TEST(ChessboardPhotos, TheSamplePhotosAreInstalled) {
    // Missing data must fail, not skip: scripts/install-deps.sh installs opencv-doc.
    EXPECT_GE(sample_photos().size(), 13u) << "install opencv-doc (scripts/install-deps.sh)";
}

TEST(ChessboardPhotos, CalibrationOfOpenCvSamplesHasSubHalfPixelError) {
    const auto& views = sample_views();
    ASSERT_GE(views.size(), 13u);
    ChessboardCalibration c = calibrate_chessboard(views, kBoard);
    RecordProperty("rms_px", std::to_string(c.result.rms_px));
    EXPECT_LT(c.result.rms_px, 0.5);
    // A plausible lens for a 640x480 webcam: the principal point near the centre.
    const Intrinsics& k = c.result.intrinsics;
    EXPECT_NEAR(k.cx, 319.5, 40);
    EXPECT_NEAR(k.cy, 239.5, 40);
    EXPECT_NEAR(k.fx / k.fy, 1.0, 0.02);
    for (size_t i = 0; i < views.size(); ++i) EXPECT_LT(c.view_rms_px[i], 0.5) << views[i].source;
}

TEST(ChessboardPhotos, EachPoseProjectsTheBoardPlaneOntoTheDetectedCorners) {
    const auto& views = sample_views();
    ASSERT_GE(views.size(), 13u);
    ChessboardCalibration c = calibrate_chessboard(views, kBoard);
    for (size_t i = 0; i < views.size(); ++i) {
        SCOPED_TRACE(views[i].source);
        CalibrationResult r = c.result;
        r.pose = c.poses[i];
        // Through the project's camera (float, distortion in Camera::project).
        Camera cam = r.camera();
        double sum = 0, worst = 0;
        for (size_t j = 0; j < views[i].corners.size(); ++j) {
            const glm::dvec3& w = c.world_corners[i][j];
            EXPECT_NEAR(w.y, 0.0, 1e-12);  // on the ground plane
            vec2 px;
            ASSERT_TRUE(cam.project(vec3(w), px));
            double d = glm::length(glm::dvec2(px) - views[i].corners[j]);
            sum += d * d;
            worst = std::max(worst, d);
        }
        EXPECT_LT(std::sqrt(sum / double(views[i].corners.size())), 0.5);
        EXPECT_LT(worst, 1.5);
        // The camera looks at the board from above.
        EXPECT_GT(cam.position().y, 0.0f);
    }
}

TEST(ChessboardPhotos, ASinglePhotoWithTheCalibratedLensGivesTheSamePose) {
    const auto& views = sample_views();
    ASSERT_GE(views.size(), 13u);
    ChessboardCalibration c = calibrate_chessboard(views, kBoard);
    CalibrationResult single = chessboard_pose(views[2], kBoard, c.result.intrinsics);
    EXPECT_LT(single.rms_px, 0.5);
    EXPECT_LT(glm::length(single.pose.position() - c.poses[2].position()),
              0.01 * glm::length(c.poses[2].position()));
}

TEST(ChessboardPhotos, APhotoWithoutTheBoardIsAnInputError) {
    try {
        detect_chessboard(std::string(kSampleDir) + "/HappyFish.jpg", kBoard);
        FAIL() << "no exception";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("no chessboard with 9x6 inner corners"),
                  std::string::npos)
            << e.what();
    }
}

TEST(ChessboardPhotos, ALargePhotoGivesTheSameCornersAsTheSmallOne) {
    // left01 enlarged four times (2560x1920): searched downscaled, refined at full size.
    const std::string path = std::string(kSampleDir) + "/left01.jpg";
    Image small = load_image(path);
    cv::Mat src(small.height(), small.width(), CV_32FC3, small.data()), big;
    cv::resize(src, big, cv::Size(), 4, 4, cv::INTER_CUBIC);
    Image large(big.cols, big.rows);
    std::memcpy(large.data(), big.ptr<float>(), large.size() * sizeof(vec3));
    ChessboardView a = detect_chessboard(small, kBoard, "small");
    ChessboardView b = detect_chessboard(large, kBoard, "large");
    ASSERT_EQ(a.corners.size(), b.corners.size());
    // Within 0.4 px of the original photo: the two refinements see differently blurred edges.
    for (size_t i = 0; i < a.corners.size(); ++i) {
        const ImagePoint expected = (a.corners[i] + 0.5) * 4.0 - 0.5;
        EXPECT_LT(glm::length(b.corners[i] - expected), 4 * 0.4) << "corner " << i;
    }
}

TEST(ChessboardPhotoCalibration, TheLensAndEveryPoseComeWithAnUncertainty) {
    const auto& views = sample_views();
    ASSERT_GE(views.size(), 13u);
    ChessboardCalibration c = calibrate_chessboard(views, kBoard);
    const Uncertainty& u = c.result.uncertainty;
    std::printf("samples: %s\n", uncertainty_text(c.result).c_str());
    EXPECT_TRUE(u.known && u.focal_free && u.principal_free);
    // Thirteen photos of a 54-corner board: the lens to a fraction of a percent.
    EXPECT_GT(u.fx, 0);
    EXPECT_LT(u.fx, 0.01 * c.result.intrinsics.fx);
    EXPECT_GT(u.cx, 0);
    ASSERT_EQ(c.view_uncertainty.size(), views.size());
    for (const Uncertainty& v : c.view_uncertainty) {
        EXPECT_GT(v.rotation_deg, 0);
        EXPECT_LT(v.rotation_deg, 1.0);
        EXPECT_GT(v.position_m, 0);
    }
}

TEST(ChessboardPhotoCalibration, ADuplicatePhotoIsLeftOutOfTheLensFitWithAWarning) {
    const auto& views = sample_views();
    ASSERT_GE(views.size(), 13u);
    const ChessboardCalibration once = calibrate_chessboard(views, kBoard);
    std::vector<ChessboardView> twice = views;
    twice.push_back(views[3]);
    const ChessboardCalibration c = calibrate_chessboard(twice, kBoard);
    EXPECT_EQ(c.duplicate_of.back(), 3);
    EXPECT_EQ(c.duplicate_of[3], -1);
    bool warned = false;
    for (const std::string& w : c.result.warnings)
        warned |= w.find("duplicate photos") != std::string::npos &&
                  w.find(views[3].source) != std::string::npos;
    EXPECT_TRUE(warned);
    EXPECT_EQ(c.result.intrinsics.fx, once.result.intrinsics.fx);  // the same lens fit
    EXPECT_LT(glm::length(c.poses.back().position() - c.poses[3].position()), 1e-5);
    // One photo twice is not two photos.
    EXPECT_NE(dp::test::input_error_message([&] {
                  calibrate_chessboard({views[0], views[0]}, kBoard);
              }).find("at least 2 different photos"),
              std::string::npos);
}

TEST(ChessboardPhotoCalibration, TheWrittenPosesReprojectEveryPhotosCornersWithinHalfAPixel) {
    const auto& views = sample_views();
    ASSERT_GE(views.size(), 13u);
    const ChessboardCalibration c = calibrate_chessboard(views, kBoard);
    // Read back as a user's script would: numbers only, then the project's camera model.
    const nlohmann::json doc = nlohmann::json::parse(chessboard_poses_json(c, views, kBoard));
    const nlohmann::json& k = doc["intrinsics"];
    ASSERT_EQ(doc["photos"].size(), views.size());
    for (size_t i = 0; i < views.size(); ++i) {
        const nlohmann::json& p = doc["photos"][i];
        SCOPED_TRACE(p["photo"].get<std::string>());
        EXPECT_EQ(p["photo"].get<std::string>(), views[i].source);
        CameraSpec cam;
        cam.model = CameraSpec::Model::Intrinsics;
        cam.fx = k["fx"], cam.fy = k["fy"], cam.cx = k["cx"], cam.cy = k["cy"];
        const auto& d = k["distortion"];
        cam.distortion = Distortion{d[0], d[1], d[2], d[3], d[4]};
        for (int r = 0; r < 3; ++r) {
            for (int col = 0; col < 3; ++col) cam.rotation[col][r] = p["rotation"][r][col];
            cam.translation[r] = p["translation"][r];
        }
        const Camera camera = cam.build(k["width"], k["height"]);
        ASSERT_EQ(p["points"].size(), views[i].corners.size());
        double sum = 0;
        for (size_t j = 0; j < views[i].corners.size(); ++j) {
            const auto& w = p["points"][j]["world"];
            // The board's own corners: on the ground, a square apart, the first at the origin.
            const int col = int(j) % kBoard.cols, row = int(j) / kBoard.cols;
            EXPECT_NEAR(double(w[0]), col * kBoard.square_size, 1e-9);
            EXPECT_NEAR(double(w[1]), 0.0, 1e-12);
            EXPECT_NEAR(std::abs(double(w[2])), row * kBoard.square_size, 1e-9);
            vec2 px;
            ASSERT_TRUE(camera.project(vec3(float(w[0]), float(w[1]), float(w[2])), px));
            const double e = glm::length(glm::dvec2(px) - views[i].corners[j]);
            sum += e * e;
        }
        const double rms = std::sqrt(sum / double(views[i].corners.size()));
        EXPECT_LT(rms, 0.5);
        EXPECT_NEAR(rms, p["rms_px"].get<double>(), 1e-3);
    }
}
