#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include "image/image_io.h"
#include "image_test_util.h"

using namespace dp;
using dp::test::random_image;
using dp::test::TempDir;

TEST(ImageIo, PngRoundTripStaysWithinHalfACodeValueInSrgb) {
    TempDir dir;
    const Image image = random_image(31, 17, 11, 0.0f, 0.9f);
    const std::string path = dir.file("round.png");
    save_ldr(path, image);

    ImageLoadReport report;
    report.linear_source = true;  // must be reset by the load
    const Image loaded = load_image(path, "photo", &report);
    ASSERT_EQ(loaded.width(), image.width());
    ASSERT_EQ(loaded.height(), image.height());
    EXPECT_FALSE(report.linear_source);
    EXPECT_EQ(report.clipped, 0u);
    float worst = 0.0f;
    for (size_t i = 0; i < image.size(); ++i)
        for (int c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(linear_to_srgb(loaded[i][c]) -
                                             linear_to_srgb(image[i][c])));
    // Quantisation to the nearest code value; 1/255 would also pass a floor-based encoder.
    EXPECT_LE(worst, 0.5f / 255.0f + 1e-5f);
}

TEST(ImageIo, SaveLdrScalesByExposureClampsAndWritesNanAsBlack) {
    TempDir dir;
    Image image(4, 1);
    image.at(0, 0) = vec3(0.25f, 0.1f, 0.05f);
    image.at(1, 0) = vec3(2.0f, 0.5f, 1.0f);
    image.at(2, 0) = vec3(std::numeric_limits<float>::quiet_NaN(), -1.0f, 0.0f);
    image.at(3, 0) = vec3(std::numeric_limits<float>::infinity(), 0.0f, 0.0f);
    const std::string path = dir.file("exposed.png");
    save_ldr(path, image, 1.0f);

    const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
    ASSERT_EQ(bgr.type(), CV_8UC3);
    auto code = [](float linear) { return int(std::lround(linear_to_srgb(linear) * 255.0f)); };
    auto px = [&](int x) { return bgr.at<cv::Vec3b>(0, x); };
    EXPECT_EQ(px(0)[2], code(0.5f));  // red 0.25 doubled
    EXPECT_EQ(px(0)[1], code(0.2f));
    EXPECT_EQ(px(0)[0], code(0.1f));
    EXPECT_EQ(px(1)[2], 255);  // 4.0 clamps
    EXPECT_EQ(px(1)[1], 255);  // exactly 1.0
    EXPECT_EQ(px(1)[0], 255);
    EXPECT_EQ(px(2), cv::Vec3b(0, 0, 0));  // NaN and negative become black
    EXPECT_EQ(px(3)[2], 255);
}

TEST(ImageIo, JpegIsChosenByExtensionAndLoadsBackClose) {
    TempDir dir;
    const Image image(16, 16, vec3(0.2f, 0.4f, 0.05f));
    const std::string path = dir.file("flat.JPG");
    save_ldr(path, image);
    const cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(raw.empty());
    const Image loaded = load_image(path);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(linear_to_srgb(loaded.at(8, 8)[c]), linear_to_srgb(image.at(8, 8)[c]),
                    3.0f / 255.0f);
    // The JPEG signature proves the encoder followed the extension.
    std::FILE* f = std::fopen(path.c_str(), "rb");
    ASSERT_NE(f, nullptr);
    unsigned char magic[2] = {};
    EXPECT_EQ(std::fread(magic, 1, 2, f), 2u);
    std::fclose(f);
    EXPECT_EQ(magic[0], 0xFF);
    EXPECT_EQ(magic[1], 0xD8);
}

TEST(ImageIo, SaveLdrRejectsExtensionsItCannotWrite) {
    TempDir dir;
    const Image image(2, 2);
    EXPECT_THROW(save_ldr(dir.file("out.exr"), image), std::invalid_argument);
    EXPECT_THROW(save_ldr(dir.file("out"), image), std::invalid_argument);
    EXPECT_THROW(save_ldr(dir.file("missing/out.png"), image), std::runtime_error);
}

TEST(ImageIo, SaturatedPngPixelsAreCountedAsClippedOncePerPixel) {
    TempDir dir;
    cv::Mat bgr(4, 8, CV_8UC3, cv::Scalar(100, 100, 100));
    bgr.at<cv::Vec3b>(0, 0) = cv::Vec3b(255, 100, 100);
    bgr.at<cv::Vec3b>(1, 3) = cv::Vec3b(100, 255, 255);  // two saturated channels, one pixel
    bgr.at<cv::Vec3b>(3, 7) = cv::Vec3b(255, 255, 255);
    bgr.at<cv::Vec3b>(2, 2) = cv::Vec3b(254, 254, 254);  // bright but not clipped
    const std::string path = dir.file("clipped.png");
    ASSERT_TRUE(cv::imwrite(path, bgr));

    ImageLoadReport report;
    const Image loaded = load_image(path, "photo", &report);
    EXPECT_EQ(report.clipped, 3u);
    EXPECT_FALSE(report.linear_source);
    const float grey = srgb_to_linear(100.0f / 255.0f);
    EXPECT_FLOAT_EQ(loaded.at(5, 0).x, grey);
    // OpenCV stores BGR; the loaded image is RGB.
    EXPECT_FLOAT_EQ(loaded.at(0, 0).z, 1.0f);
    EXPECT_FLOAT_EQ(loaded.at(0, 0).x, grey);
}

TEST(ImageIo, SixteenBitPngDecodesThroughSrgbAndCountsClipping) {
    TempDir dir;
    cv::Mat bgr(2, 3, CV_16UC3, cv::Scalar(1000, 20000, 40000));
    bgr.at<cv::Vec3w>(1, 2) = cv::Vec3w(0, 0, 65535);
    const std::string path = dir.file("deep.png");
    ASSERT_TRUE(cv::imwrite(path, bgr));

    ImageLoadReport report;
    const Image loaded = load_image(path, "photo", &report);
    EXPECT_EQ(report.clipped, 1u);
    EXPECT_NEAR(loaded.at(0, 0).x, srgb_to_linear(40000.0f / 65535.0f), 1e-6);
    EXPECT_NEAR(loaded.at(0, 0).y, srgb_to_linear(20000.0f / 65535.0f), 1e-6);
    EXPECT_NEAR(loaded.at(0, 0).z, srgb_to_linear(1000.0f / 65535.0f), 1e-7);
    EXPECT_FLOAT_EQ(loaded.at(2, 1).x, 1.0f);
}

TEST(ImageIo, RadianceHdrLoadsAsLinearFloat) {
    TempDir dir;
    cv::Mat bgr(3, 4, CV_32FC3, cv::Scalar(0.5f, 2.0f, 10.0f));
    bgr.at<cv::Vec3f>(2, 3) = cv::Vec3f(0.01f, 0.02f, 0.03f);
    const std::string path = dir.file("sky.hdr");
    ASSERT_TRUE(cv::imwrite(path, bgr));

    ImageLoadReport report;
    const Image loaded = load_image(path, "probe", &report);
    EXPECT_TRUE(report.linear_source);
    EXPECT_EQ(report.clipped, 0u);
    // RGBE shares one exponent per pixel: error is relative to the pixel's largest channel.
    EXPECT_NEAR(loaded.at(0, 0).x, 10.0f, 0.1f);
    EXPECT_NEAR(loaded.at(0, 0).y, 2.0f, 0.1f);
    EXPECT_NEAR(loaded.at(0, 0).z, 0.5f, 0.1f);
    EXPECT_NEAR(loaded.at(3, 2).x, 0.03f, 3e-4f);
    EXPECT_NEAR(loaded.at(3, 2).z, 0.01f, 3e-4f);
}

