// The asset library: each file decoded once, decoded again when it changes, and what decoding
// finds said as warnings.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <unistd.h>

#include "assets/asset_library.h"
#include "image/image_io.h"

using namespace dp;
namespace fs = std::filesystem;

namespace {

class AssetLibraryTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("dp_assets_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        write("photo.exr", Image(32, 24, vec3(0.5f)));
        write("probe.exr", Image(64, 32, vec3(1.0f)));
        project_.base_dir = dir_;
        project_.photo.path = "photo.exr";
        project_.probe.path = "probe.exr";
    }
    void TearDown() override { fs::remove_all(dir_); }

    void write(const std::string& name, const Image& image) {
        save_exr((dir_ / name).string(), {{"", &image}});
    }
    bool warned(AssetLibrary& library, const std::string& text) {
        for (const std::string& w : library.warnings(project_))
            if (w.find(text) != std::string::npos) return true;
        return false;
    }

    fs::path dir_;
    Project project_;
};

}  // namespace

TEST_F(AssetLibraryTest, DecodesEachFileOnceAndAgainWhenItChanges) {
    AssetLibrary library;
    const auto first = library.photo(project_);
    EXPECT_EQ(library.photo(project_).get(), first.get());  // the same decoded image
    EXPECT_EQ(library.probe(project_).get(), library.probe(project_).get());
    write("photo.exr", Image(32, 24, vec3(0.25f)));
    // A modification time one second on, as a later save would have.
    fs::last_write_time(dir_ / "photo.exr", fs::last_write_time(dir_ / "photo.exr") + std::chrono::seconds(1));
    const auto second = library.photo(project_);
    EXPECT_NE(second.get(), first.get());
    EXPECT_FLOAT_EQ(second->at(0, 0).x, 0.25f);
}

TEST_F(AssetLibraryTest, AProbeOfTheWrongShapeOrWithNegativeValuesIsSaid) {
    AssetLibrary clean;
    clean.probe(project_);
    EXPECT_FALSE(warned(clean, "probe.path"));

    Image square(48, 48, vec3(1.0f));
    for (int x = 0; x < 48; ++x) square.at(x, 3) = vec3(-2.0f, 1.0f, 1.0f);  // 3% of the light
    write("probe.exr", square);
    AssetLibrary library;
    const auto probe = library.probe(project_);
    EXPECT_TRUE(warned(library, "not 2:1"));
    EXPECT_TRUE(warned(library, "48 negative values read as 0"));
    EXPECT_GE(probe->at(3, 3).x, 0.0f);

    project_.probe.format = ProbeSpec::Format::MirrorBall;
    write("probe.exr", Image(64, 32, vec3(1.0f)));
    AssetLibrary ball;
    ball.probe(project_);
    EXPECT_TRUE(warned(ball, "not square"));

    project_.probe.format = ProbeSpec::Format::LatLong;
    write("probe.exr", Image(64, 32, vec3(0.0f)));
    AssetLibrary black;
    black.probe(project_);
    EXPECT_TRUE(warned(black, "the probe is black"));
}
