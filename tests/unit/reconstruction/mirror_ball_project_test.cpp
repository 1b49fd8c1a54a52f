#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "base/error.h"
#include "image/image_io.h"
#include "probe/probe.h"
#include "assets/render_scene.h"
#include "scene/project_io.h"

using namespace dp;
namespace fs = std::filesystem;

namespace {

constexpr double kPiD = std::numbers::pi;

// A smooth, asymmetric environment, evaluated exactly in any direction.
vec3 environment(const dvec3& d) {
    return vec3(float(1.0 + 0.5 * d.x + 0.3 * std::sin(4 * d.y + 2 * d.z)),
                float(1.0 + 0.4 * d.y * d.z + 0.4 * std::cos(3 * d.x - d.y)),
                float(1.0 + 0.5 * d.z * std::cos(2 * d.x + 3 * d.y)));
}

// A unit mirror ball filling a size x size photo, taken by a pinhole camera on +Z looking along
// -Z whose vertical field of view just holds the ball (the layout the project file describes),
// each pixel the reflected environment at its centre.
Image photograph_ball(int size, double fov_deg) {
    Image ball(size, size);
    double half = fov_deg * kPiD / 360, distance = 1 / std::sin(half);
    dvec3 eye(0, 0, distance);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            double a = (x + 0.5 - size / 2.0) / (size / 2.0), b = (size / 2.0 - (y + 0.5)) / (size / 2.0);
            dvec3 view = glm::normalize(dvec3(a * std::tan(half), b * std::tan(half), -1));
            double ov = glm::dot(eye, view), disc = ov * ov - (distance * distance - 1);
            if (disc < 0) continue;
            dvec3 normal = eye + (-ov - std::sqrt(disc)) * view;
            ball.at(x, y) = environment(view - 2 * glm::dot(view, normal) * normal);
        }
    return ball;
}

// Solid-angle weighted mean of |got - want| / |want| over directions more than 30 degrees from
// the back pole (-Z), which a ball shows only in a thin ring at its rim.
double mean_relative_error(const Image& got) {
    double sum = 0, weight = 0;
    for (int j = 0; j < got.height(); ++j)
        for (int i = 0; i < got.width(); ++i) {
            vec3 d = latlong_direction((i + 0.5f) / got.width(), (j + 0.5f) / got.height());
            if (std::acos(std::clamp(-double(d.z), -1.0, 1.0)) < 30 * kPiD / 180) continue;
            double omega = std::sin(kPiD * (j + 0.5) / got.height());
            vec3 want = environment(dvec3(d));
            sum += omega * glm::length(got.at(i, j) - want) / glm::length(want);
            weight += omega;
        }
    return sum / weight;
}

class MirrorBallProject : public ::testing::Test {
protected:
    fs::path dir = fs::temp_directory_path() /
                   ("dp_mirror_ball_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
    void SetUp() override { fs::create_directories(dir); }
    void TearDown() override { fs::remove_all(dir); }
};

}  // namespace

TEST_F(MirrorBallProject, TheProbeCamerasFieldOfViewUnwrapsAWideAngleBallBetterThanOrthographic) {
    const double fov = 60;
    Image ball = photograph_ball(256, fov);
    save_exr((dir / "ball.exr").string(), {{"", &ball}});
    Image photo(8, 8, vec3(0.5f));
    save_exr((dir / "photo.exr").string(), {{"", &photo}});
    Project p;
    p.base_dir = dir;
    p.photo.path = "photo.exr";
    p.probe.path = "ball.exr";
    p.probe.format = ProbeSpec::Format::MirrorBall;

    p.probe.mirror_ball_fov_deg = float(fov);
    double with_fov = mean_relative_error(load_assets(p).probe_latlong);
    p.probe.mirror_ball_fov_deg = 0;
    double orthographic = mean_relative_error(load_assets(p).probe_latlong);
    RecordProperty("mean_relative_error_fov", std::to_string(with_fov));
    RecordProperty("mean_relative_error_orthographic", std::to_string(orthographic));
    EXPECT_LT(with_fov, 0.01);
    EXPECT_GT(orthographic, 3 * with_fov);
}

TEST_F(MirrorBallProject, TheFieldOfViewIsReadWrittenAndChecked) {
    std::string text = R"({"schema_version": 1, "photo": {"path": "p.exr"},
        "probe": {"path": "b.exr", "format": "mirrorball", "mirror_ball_fov_deg": 35},
        "camera": {"model": "lookat", "eye": [0, 1, 5], "target": [0, 0, 0], "vfov_deg": 40}})";
    fs::path file = dir / "p.json";
    std::ofstream(file) << text;
    Project p = load_project(file.string());
    EXPECT_FLOAT_EQ(p.probe.mirror_ball_fov_deg, 35.0f);
    save_project(p, (dir / "q.json").string());
    EXPECT_EQ(load_project((dir / "q.json").string()), p);

    std::string bad = text;
    bad.replace(bad.find("35"), 2, "190");
    std::ofstream(file) << bad;
    try {
        load_project(file.string());
        FAIL() << "no error for a field of view of 190 degrees";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "probe.mirror_ball_fov_deg");
    }
}
