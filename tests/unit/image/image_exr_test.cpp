#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfRgbaFile.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/error.h"
#include "image/image_io.h"
#include "image_test_util.h"

using namespace dp;
using dp::test::bit_identical;
using dp::test::random_image;
using dp::test::TempDir;

TEST(ImageIo, ExrRoundTripKeepsEveryLayerBitExact) {
    TempDir dir;
    Image beauty = random_image(37, 21, 1, -5.0f, 5.0f);
    beauty.at(0, 0) = vec3(-0.0f, 1e-40f, 3.0e38f);  // signed zero, subnormal, beyond half range
    beauty.at(36, 20) = vec3(-1e-30f, -7.25f, 1.0f / 3.0f);
    const Image albedo = random_image(37, 21, 2, 0.0f, 1.0f);
    const Image normal = random_image(37, 21, 3, -1.0f, 1.0f);
    const std::string path = dir.file("layers.exr");

    save_exr(path, {{"", &beauty}, {"albedo", &albedo}, {"normal", &normal}});

    EXPECT_TRUE(bit_identical(load_exr_layer(path, ""), beauty));
    EXPECT_TRUE(bit_identical(load_exr_layer(path, "albedo"), albedo));
    EXPECT_TRUE(bit_identical(load_exr_layer(path, "normal"), normal));
}

TEST(ImageIo, LoadImageReadsTheMainLayerOfAMultiLayerExrAsLinear) {
    TempDir dir;
    const Image beauty = random_image(8, 5, 4, -1.0f, 3.0f);
    const Image other = random_image(8, 5, 5, 10.0f, 20.0f);
    const std::string path = dir.file("two.exr");
    save_exr(path, {{"other", &other}, {"", &beauty}});

    ImageLoadReport report;
    report.clipped = 99;  // stale values must be reset by the load
    EXPECT_TRUE(bit_identical(load_image(path, "probe", &report), beauty));
    EXPECT_TRUE(report.linear_source);
    EXPECT_EQ(report.clipped, 0u);
    EXPECT_EQ(report.non_finite_replaced, 0u);
}

TEST(ImageIo, LoadingAnAbsentExrLayerThrowsInputErrorNamingTheLayer) {
    TempDir dir;
    const Image image = random_image(4, 4, 6, 0.0f, 1.0f);
    const std::string path = dir.file("one.exr");
    save_exr(path, {{"albedo", &image}});
    try {
        load_exr_layer(path, "normal");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(path), std::string::npos) << what;
        EXPECT_NE(what.find("normal"), std::string::npos) << what;
        EXPECT_NE(what.find("albedo"), std::string::npos) << what;  // lists what is there
    }
    EXPECT_THROW(load_exr_layer(path, ""), InputError);
}

TEST(ImageIo, NonFiniteExrValuesBecomeZeroAndAreCountedPerChannel) {
    TempDir dir;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    Image image = random_image(6, 4, 7, 0.5f, 2.0f);
    Image expected = image;
    image.at(1, 0).x = nan;
    image.at(2, 1).y = inf;
    image.at(3, 2) = vec3(-inf, 1.5f, nan);
    expected.at(1, 0).x = 0.0f;
    expected.at(2, 1).y = 0.0f;
    expected.at(3, 2) = vec3(0.0f, 1.5f, 0.0f);
    const std::string path = dir.file("nan.exr");
    save_exr(path, {{"", &image}});

    ImageLoadReport report;
    const Image loaded = load_image(path, "background", &report);
    EXPECT_EQ(report.non_finite_replaced, 4u);
    EXPECT_TRUE(bit_identical(loaded, expected));
}

TEST(ImageIo, LuminanceOnlyExrLoadsAsGrey) {
    TempDir dir;
    const int w = 5, h = 3;
    std::vector<float> y(w * h);
    for (int i = 0; i < w * h; ++i) y[i] = 0.1f * float(i) - 0.3f;
    const std::string path = dir.file("grey.exr");
    {
        Imf::Header header(w, h);
        header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
        Imf::FrameBuffer frame;
        frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(y.data()),
                                     sizeof(float), sizeof(float) * w));
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(h);
    }
    const Image loaded = load_image(path);
    ASSERT_EQ(loaded.width(), w);
    ASSERT_EQ(loaded.height(), h);
    for (int i = 0; i < w * h; ++i) EXPECT_EQ(loaded[i], vec3(y[i])) << "pixel " << i;
}

TEST(ImageIo, ExrWithAnOffsetDataWindowLoadsItsDataInsideTheDisplayWindow) {
    TempDir dir;
    const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(19, 9));
    const Imath::Box2i window(Imath::V2i(5, 3), Imath::V2i(12, 8));
    const Image image = random_image(8, 6, 8, -2.0f, 2.0f);
    const std::string path = dir.file("window.exr");
    {
        Imf::Header header(display, window);
        Imf::FrameBuffer frame;
        const char* names[3] = {"R", "G", "B"};
        char* base = const_cast<char*>(reinterpret_cast<const char*>(image.data()));
        for (int c = 0; c < 3; ++c) {
            header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
            frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, base + c * sizeof(float), window,
                                                    sizeof(vec3), sizeof(vec3) * 8));
        }
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(6);
    }
    const Image loaded = load_image(path);
    ASSERT_EQ(loaded.width(), 20);
    ASSERT_EQ(loaded.height(), 10);
    Image window_pixels(8, 6);
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 8; ++x) window_pixels.at(x, y) = loaded.at(5 + x, 3 + y);
    EXPECT_TRUE(bit_identical(window_pixels, image));
    EXPECT_EQ(loaded.at(4, 3), vec3(0.0f));  // outside the data window
    EXPECT_EQ(loaded.at(19, 9), vec3(0.0f));
}

TEST(ImageIo, LuminanceChromaExrLoadsInColour) {
    TempDir dir;
    const int w = 16, h = 16;
    std::vector<Imf::Rgba> pixels(w * h, Imf::Rgba(0.8f, 0.1f, 0.05f, 1.0f));
    const std::string path = dir.file("yc.exr");
    {
        Imf::RgbaOutputFile file(path.c_str(), w, h, Imf::WRITE_YC);
        file.setFrameBuffer(pixels.data(), 1, w);
        file.writePixels(h);
    }
    const Image loaded = load_image(path);
    ASSERT_EQ(loaded.width(), w);
    // Luminance/chroma coding is lossy (half floats, subsampled chroma).
    const vec3 c = loaded.at(7, 7);
    EXPECT_NEAR(c.x, 0.8f, 0.03f);
    EXPECT_NEAR(c.y, 0.1f, 0.03f);
    EXPECT_NEAR(c.z, 0.05f, 0.03f);
}

TEST(ImageIo, SavingAnExrIntoAMissingFolderThrowsNamingThePath) {
    TempDir dir;
    const Image image(2, 2, vec3(1.0f));
    const std::string path = dir.file("no_such_folder/out.exr");
    try {
        save_exr(path, {{"", &image}});
        FAIL() << "expected std::runtime_error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir.file("no_such_folder")));
}

TEST(ImageIo, SavingExrLayersOfDifferentSizesIsRejected) {
    TempDir dir;
    const Image a(4, 4), b(4, 5);
    EXPECT_THROW(save_exr(dir.file("bad.exr"), {{"", &a}, {"b", &b}}), std::invalid_argument);
    EXPECT_THROW(save_exr(dir.file("bad.exr"), {{"", &a}, {"", &a}}), std::invalid_argument);
    EXPECT_THROW(save_exr(dir.file("bad.exr"), {}), std::invalid_argument);
}

TEST(ImageIo, BlenderForestProbeLoadsAsFiniteEquirectangularRadiance) {
    const std::string path = "/usr/share/blender/datafiles/studiolights/world/forest.exr";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not installed";
    ImageLoadReport report;
    const Image probe = load_image(path, "probe", &report);
    ASSERT_FALSE(probe.empty());
    EXPECT_EQ(probe.width(), 2 * probe.height());
    EXPECT_TRUE(report.linear_source);
    EXPECT_EQ(report.non_finite_replaced, 0u);
    // The shipped probe holds a few slightly negative channels (resampling ringing, down to
    // about -0.0016); loading keeps them as stored, so only luminance is required positive.
    size_t non_finite = 0, dark = 0;
    float lowest = 0.0f, brightest = 0.0f;
    for (size_t i = 0; i < probe.size(); ++i) {
        if (!is_finite(probe[i])) ++non_finite;
        if (!(luminance(probe[i]) > 0.0f)) ++dark;
        for (int c = 0; c < 3; ++c) {
            lowest = std::min(lowest, probe[i][c]);
            brightest = std::max(brightest, probe[i][c]);
        }
    }
    EXPECT_EQ(non_finite, 0u);
    EXPECT_EQ(dark, 0u) << "pixels without positive luminance";
    EXPECT_GT(lowest, -0.01f);
    EXPECT_GT(brightest, 1.0f) << "a sky probe is high dynamic range";
}
