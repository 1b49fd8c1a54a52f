// The asset library: each file decoded once, decoded again when it changes, and what decoding
// finds said as warnings.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <unistd.h>

#include "assets/asset_library.h"
#include "base/error.h"
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

TEST_F(AssetLibraryTest, TheLitProbeFollowsTheWhiteBalanceAndKeepsOnePerSetting) {
    AssetLibrary library;
    const auto neutral = library.lit_probe(project_);
    EXPECT_EQ(library.lit_probe(project_).get(), neutral.get());
    Project tinted = project_;
    tinted.probe.intensity = 2;
    tinted.probe.white_balance = vec3(1.2f, 1.0f, 0.7f);
    const auto lit = library.lit_probe(tinted);
    ASSERT_NE(lit.get(), neutral.get());
    EXPECT_EQ(lit->probe.pixel_radiance(0), vec3(2.4f, 2.0f, 1.4f));
    EXPECT_EQ(neutral->probe.pixel_radiance(0), vec3(1.0f));
    EXPECT_EQ(library.lit_probe(project_).get(), neutral.get());  // both kept
    // A scene built without the library applies it the same way.
    SceneAssets assets = library.load(tinted);
    const RenderScene scene(tinted, std::move(assets));
    EXPECT_EQ(scene.probe().pixel_radiance(0), vec3(2.4f, 2.0f, 1.4f));
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

TEST_F(AssetLibraryTest, AnAlbedoTextureOutsideZeroToOneIsSaidWithItsShare) {
    Image texture(8, 8, vec3(0.5f));
    for (int x = 0; x < 8; ++x) texture.at(x, 0) = vec3(-5.0f);  // one row of eight: 12.5%
    texture.at(0, 1) = vec3(1e30f);
    write("albedo.exr", texture);
    RealProxy floor;
    floor.shape.kind = Shape::Kind::Plane;
    floor.albedo.kind = Albedo::Kind::Texture;
    floor.albedo.texture_path = "albedo.exr";
    project_.real.push_back(floor);
    AssetLibrary library;
    EXPECT_TRUE(warned(library, "real[0].albedo.texture"));
    EXPECT_TRUE(warned(library, "14% of the texels are outside the albedo range [0, 1]"));
    EXPECT_TRUE(warned(library, "from -5 to 1e+30"));

    write("albedo.exr", Image(8, 8, vec3(0.9f)));
    AssetLibrary clean;
    EXPECT_FALSE(warned(clean, "albedo range"));
}

TEST_F(AssetLibraryTest, AClippedPhotoIsSaidBeyondAVisibleShare) {
    Image photo(20, 10, vec3(0.2f));
    const auto save_png = [&](const Image& image) { save_ldr((dir_ / "photo.png").string(), image); };
    photo.at(0, 5) = vec3(1.0f);  // 0.5% of 200 pixels: a glint, not worth a word
    save_png(photo);
    project_.photo.path = "photo.png";
    AssetLibrary glint;
    EXPECT_FALSE(warned(glint, "clipped"));
    for (int x = 0; x < 20; ++x) photo.at(x, 5) = vec3(0.2f, 3.0f, 0.2f);  // one channel over: clipped
    save_png(photo);
    AssetLibrary library;
    EXPECT_TRUE(warned(library, "photo.path: 10% of the photo's pixels are clipped"));
}

TEST(ProbeSize, AWideProbeIsReducedKeepingItsLight) {
    Image probe(256, 128, vec3(1.0f));
    probe.at(100, 30) = vec3(4096.0f);  // a one-pixel sun
    // The light is the power, radiance times each pixel's solid angle (a band of the sphere).
    auto power = [](const Image& img) {
        double sum = 0;
        for (int j = 0; j < img.height(); ++j)
            for (int i = 0; i < img.width(); ++i)
                sum += img.at(i, j).x * (std::cos(M_PI * j / img.height()) - std::cos(M_PI * (j + 1) / img.height())) /
                       img.width();
        return sum;
    };
    const double before = power(probe);
    std::vector<std::string> warnings;
    limit_probe_size(probe, 64, warnings);
    EXPECT_EQ(probe.width(), 64);
    EXPECT_EQ(probe.height(), 32);
    EXPECT_NEAR(power(probe), before, 1e-6 * before);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("256x128 probe is reduced to 64x32"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("max width 64"), std::string::npos) << warnings[0];

    std::vector<std::string> none;
    limit_probe_size(probe, 64, none);
    EXPECT_TRUE(none.empty());
}

TEST_F(AssetLibraryTest, TheProjectsMaxWidthShrinksTheProbeOnLoadAndSaysSo) {
    write("probe.exr", Image(300, 150, vec3(2.0f)));
    AssetLibrary library;
    EXPECT_EQ(library.probe(project_)->width(), 300);  // automatic: far below 8192
    EXPECT_FALSE(warned(library, "reduced"));
    project_.probe.max_width = 100;
    const auto small = library.probe(project_);
    EXPECT_EQ(small->width(), 100);
    EXPECT_EQ(small->height(), 50);
    EXPECT_TRUE(warned(library, "the 300x150 probe is reduced to 100x50 on load, its light kept"));
    // The lit probe is built from the shrunk map, sharing it with the cache.
    EXPECT_EQ(&library.lit_probe(project_)->probe.image(), small.get());
}

TEST_F(AssetLibraryTest, AHoldoutsMaskIsLoadedAsDataAndAMaskOfAnotherShapeIsWarnedOf) {
    // Left half white; the top right quarter written as sRGB 0.54 (0.25 linear): as stored it
    // is over half and covered, as decoded colour it would not be.
    Image mask(32, 24);
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 32; ++x) mask.at(x, y) = vec3(x < 16 ? 1.0f : 0.25f * (y < 12));
    save_ldr((dir_ / "mask.png").string(), mask);
    project_.holdouts.push_back({"board", "mask.png", 2.5f});
    AssetLibrary library;
    const SceneAssets a = library.load(project_, 0, 0, false);
    ASSERT_EQ(a.holdouts.size(), 1u);
    EXPECT_EQ(a.holdouts[0].depth, 2.5f);
    EXPECT_NEAR(a.holdouts[0].coverage(), 0.75, 1e-9);  // the left half, and the top right quarter
    EXPECT_FALSE(warned(library, "stretched"));
    for (const std::string& w : a.warnings) EXPECT_EQ(w.find("stretched"), std::string::npos) << w;

    save_ldr((dir_ / "square.png").string(), Image(24, 24, vec3(1)));
    project_.holdouts[0].mask = "square.png";
    const SceneAssets b = library.load(project_, 0, 0, false);
    bool stretched = false;
    for (const std::string& w : b.warnings)
        stretched |= w.find("holdouts[0].mask: the mask is 24x24 and the photo 32x24") != std::string::npos;
    EXPECT_TRUE(stretched);

    // A missing mask is an error naming its field.
    project_.holdouts[0].mask = "missing.png";
    try {
        library.load(project_, 0, 0, false);
        FAIL() << "a missing mask loaded";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "holdouts[0].mask");
    }
}
