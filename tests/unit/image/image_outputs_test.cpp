// Outputs: view transforms, 16-bit and half-float files, JPEG quality and metadata carried over.
#include <gtest/gtest.h>

#include <algorithm>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "base/error.h"
#include "image/display_transform.h"
#include "image/image_io.h"
#include "image_test_util.h"

using namespace dp;
using dp::test::TempDir;

namespace {

std::vector<uint16_t> read_u16(const std::string& path, OIIO::TypeDesc* stored = nullptr) {
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in);
    if (!in) return {};
    if (stored) *stored = in->spec().format;
    std::vector<uint16_t> codes(size_t(in->spec().width) * in->spec().height * in->spec().nchannels);
    in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::UINT16, codes.data());
    return codes;
}

}  // namespace

TEST(ImageOutputs, TheStandardViewGivesBackEveryEightBitCodeOfAnUntouchedPhoto) {
    TempDir dir;
    // Every code value in each channel, shifted per channel.
    OIIO::ImageSpec spec(256, 1, 3, OIIO::TypeDesc::UINT8);
    std::vector<uint8_t> codes(256 * 3);
    for (int i = 0; i < 256; ++i)
        for (int c = 0; c < 3; ++c) codes[size_t(3 * i + c)] = uint8_t((i + 85 * c) % 256);
    const std::string in_path = dir.file("photo.png");
    auto out = OIIO::ImageOutput::create(in_path);
    ASSERT_TRUE(out && out->open(in_path, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, codes.data()));
    out->close();

    save_display_image(dir.file("out.png"), load_image(in_path, "photo"), DisplayTransform());
    const std::vector<uint16_t> written = read_u16(dir.file("out.png"));
    ASSERT_EQ(written.size(), codes.size());
    for (size_t i = 0; i < codes.size(); ++i) ASSERT_EQ(written[i], uint16_t(codes[i] * 257)) << "at " << i;
}

TEST(ImageOutputs, ASixteenBitPngKeepsWhatEightBitsWouldRound) {
    TempDir dir;
    Image image(2, 1);
    image.at(0, 0) = vec3(0.2140f);  // between two 8-bit codes
    image.at(1, 0) = vec3(1e-4f);
    ImageWriteOptions options;
    options.format = SampleFormat::U16;
    save_display_image(dir.file("deep.png"), image, DisplayTransform(), options);
    OIIO::TypeDesc stored;
    const std::vector<uint16_t> codes = read_u16(dir.file("deep.png"), &stored);
    EXPECT_EQ(stored, OIIO::TypeDesc::UINT16);
    ASSERT_EQ(codes.size(), 6u);
    EXPECT_EQ(codes[0], uint16_t(std::lround(linear_to_srgb(0.2140f) * 65535.0)));
    EXPECT_EQ(codes[3], uint16_t(std::lround(linear_to_srgb(1e-4f) * 65535.0)));
}

TEST(ImageOutputs, AHalfFloatExrStoresHalvesAndReadsBackWithinTheirPrecision) {
    TempDir dir;
    const Image image = dp::test::random_image(8, 4, 5, 0.0f, 20.0f);
    ImageWriteOptions options;
    options.format = SampleFormat::Half;
    save_exr(dir.file("half.exr"), {{"", &image}, {"dL", &image}}, options);
    auto in = OIIO::ImageInput::open(dir.file("half.exr"));
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::HALF);
    const Image back = load_exr_layer(dir.file("half.exr"), "dL");
    for (size_t i = 0; i < image.size(); ++i)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[i][c], image[i][c], image[i][c] * 1e-3f + 1e-6f);
}

TEST(ImageOutputs, MetadataGoesIntoTheFileAndAJpegCarriesThePlatesCamera) {
    TempDir dir;
    const Image image = dp::test::random_image(16, 16, 9, 0.0f, 1.0f);
    ImageWriteOptions options;
    options.metadata = {{"Make", "Canon"}, {"Model", "EOS 5D"}, {"FNumber", "2.8"}, {"Exif:FocalLength", "35"}, {"diffphoton:passes", "64"}};
    options.jpeg_quality = 50;
    save_display_image(dir.file("q50.jpg"), image, DisplayTransform(), options);
    options.jpeg_quality = 100;
    save_display_image(dir.file("q100.jpg"), image, DisplayTransform(), options);
    EXPECT_LT(std::filesystem::file_size(dir.file("q50.jpg")), std::filesystem::file_size(dir.file("q100.jpg")));

    const auto metadata = read_image_metadata(dir.file("q50.jpg"));
    auto value = [&](const std::string& name) {
        for (const auto& [n, v] : metadata)
            if (n == name) return v;
        return std::string();
    };
    EXPECT_EQ(value("Make"), "Canon");
    EXPECT_EQ(value("Model"), "EOS 5D");
    EXPECT_NEAR(std::atof(value("FNumber").c_str()), 2.8, 1e-3);
    EXPECT_NEAR(std::atof(value("Exif:FocalLength").c_str()), 35, 1e-3);

    save_exr(dir.file("meta.exr"), {{"", &image}}, options);
    auto in = OIIO::ImageInput::open(dir.file("meta.exr"));
    ASSERT_TRUE(in);
    EXPECT_EQ(std::string(in->spec().get_string_attribute("diffphoton:passes")), "64");
    const std::string software(in->spec().get_string_attribute("Software"));
    EXPECT_EQ(software.rfind("diffphoton", 0), 0u) << software;
}

TEST(ImageOutputs, FilmicRollsOffHighlightsThatStandardClips) {
    if (ocio_config_path().empty()) GTEST_SKIP() << "no OpenColorIO config (Blender's or $OCIO)";
    ViewSettings filmic;
    filmic.view = "Filmic";
    const DisplayTransform view(filmic);
    const vec3 in[3] = {vec3(1.0f), vec3(4.0f), vec3(16.0f)};
    vec3 out[3], standard[3];
    view.apply(in, out, 3);
    DisplayTransform().apply(in, standard, 3);
    EXPECT_EQ(standard[1], vec3(1.0f));  // clipped
    EXPECT_LT(out[0].x, out[1].x);       // still rising above 1.0 ...
    EXPECT_LT(out[1].x, out[2].x);
    EXPECT_LT(out[2].x, 1.0f);           // ... and not yet white at 16
}

TEST(ImageOutputs, ALookIsTakenAsTheConfigNamesItAndAsBlendersMenuDoes) {
    if (ocio_config_path().empty()) GTEST_SKIP() << "no OpenColorIO config (Blender's or $OCIO)";
    const std::vector<std::string> looks = available_looks();
    if (std::find(looks.begin(), looks.end(), "High Contrast") == looks.end()) GTEST_SKIP() << "no \"High Contrast\" look";
    ViewSettings config, menu, none;
    config.view = menu.view = none.view = "Filmic";
    config.look = "High Contrast";
    menu.look = "Filmic - High Contrast";
    const vec3 in[2] = {vec3(0.05f), vec3(0.5f)};
    vec3 a[2], b[2], c[2];
    DisplayTransform(config).apply(in, a, 2);
    DisplayTransform(menu).apply(in, b, 2);
    DisplayTransform(none).apply(in, c, 2);
    EXPECT_EQ(a[0], b[0]);
    EXPECT_EQ(a[1], b[1]);
    EXPECT_NE(a[1], c[1]);  // guard: the look does something
    // Another view's prefix is not taken.
    ViewSettings other = menu;
    other.look = "Standard - High Contrast";
    EXPECT_THROW(DisplayTransform{other}, InputError);
}

TEST(ImageOutputs, AnUnknownViewOrLookIsRefusedWithTheChoices) {
    ViewSettings bad;
    bad.view = "Cinematic";
    try {
        DisplayTransform t(bad);
        FAIL() << "an unknown view must be refused";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("Standard"), std::string::npos) << e.what();
    }
    bad.view = "Standard";
    bad.look = "Extra Punchy";
    EXPECT_THROW(DisplayTransform{bad}, InputError);
}
