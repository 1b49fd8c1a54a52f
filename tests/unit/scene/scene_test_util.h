#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace dp::test {

inline std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

/// A fresh folder per test, removed afterwards.
class TempDirTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               ("dp_scene_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
                std::to_string(::getpid()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string write(const std::string& name, const std::string& text) const {
        std::filesystem::path p = dir_ / name;
        std::filesystem::create_directories(p.parent_path());
        std::ofstream(p, std::ios::binary) << text;
        return p.string();
    }
    static std::string read(const std::string& path) { return read_text(path); }

    std::filesystem::path dir_;
};

/// A project using every variant: both albedo forms and "estimate" on real proxies, every shape
/// and material, a mirror-ball probe, an OpenCV camera with distortion, explicit initial radius.
inline const char* kRichProject = R"({
  "schema_version": 1,
  "photo": {"path": "photos/kitchen.jpg", "exposure": -0.5},
  "probe": {"path": "../probes/kitchen_ball.exr", "format": "mirrorball",
            "rotation_deg": [0, 90.5, 0], "intensity": 1.25, "white_balance": [1.1, 1, 0.85]},
  "camera": {"model": "opencv", "fx": 1210.5, "fy": 1208.25, "cx": 959.5, "cy": 539.5,
             "distortion": [-0.11, 0.032, 0.0005, -0.0004, 0.001],
             "rotation": [[0, 0, 1], [0, 1, 0], [-1, 0, 0]],
             "translation": [0.1, -1.4, 3.2]},
  "real": [
    {"name": "floor", "shape": {"type": "plane", "size": [10, 8]},
     "transform": {"translation": [0, 0, -1]}, "albedo": "estimate"},
    {"name": "wall", "shape": {"type": "box", "size": [4, 2.5, 0.1]},
     "transform": {"translation": [0, 1.25, -3], "rotation_deg": [0, 15, 0], "scale": [1, 1, 2]},
     "albedo": [0.6, 0.55, 0.5]},
    {"name": "table", "shape": {"type": "mesh", "path": "/abs/table.obj"},
     "albedo": {"texture": "wood.png"}}
  ],
  "objects": [
    {"name": "ball", "shape": {"type": "sphere", "radius": 0.3},
     "transform": {"translation": [0.2, 0.3, -1]},
     "material": {"type": "glass", "ior": 1.45, "tint": [0.9, 0.95, 1]}},
    {"name": "mirror", "shape": {"type": "box", "size": [1, 1, 0.02]},
     "material": {"type": "mirror", "reflectance": [0.9, 0.9, 0.85]}, "visible": false},
    {"name": "bunny", "shape": {"type": "mesh", "path": "meshes/bunny.obj", "up_axis": "z", "unit_scale": 0.01},
     "material": {"type": "diffuse", "albedo": {"texture": "fur.png"}}, "material_source": "file"},
    {"name": "rug", "shape": {"type": "plane", "size": [1.5, 0.75]},
     "material": {"type": "diffuse", "albedo": [0.8, 0.1, 0.1]}},
    {"shape": {"type": "sphere", "radius": 0.1}}
  ],
  "render": {"photons_per_pass": 500000, "passes": 32, "time_budget_s": 12.5,
             "initial_radius": 0.02, "alpha": 0.7, "max_depth": 12,
             "seed": 18446744073709551615, "threads": 4}
})";

}  // namespace dp::test
