// Plates as compositors and phones write them: display windows, multilayer EXRs, ICC profiles
// and colour spaces on the way in.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <lcms2.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "base/error.h"
#include "image/display_transform.h"
#include "image/icc_profile.h"
#include "image/image_io.h"
#include "image_test_util.h"

using namespace dp;
using dp::test::TempDir;

namespace {

/// Writes a float EXR with the given channels (interleaved values per pixel) and windows.
void write_exr(const std::string& path, int w, int h, const std::vector<std::string>& channels,
               const std::vector<float>& pixels, int x = 0, int y = 0, int full_w = 0, int full_h = 0) {
    OIIO::ImageSpec spec(w, h, int(channels.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames = channels;
    spec.x = x;
    spec.y = y;
    spec.full_x = 0;
    spec.full_y = 0;
    spec.full_width = full_w ? full_w : w;
    spec.full_height = full_h ? full_h : h;
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out && out->open(path, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
}

/// Writes an 8-bit RGB image (by extension) of one colour, tagged with `icc` when given.
void write_png(const std::string& path, int w, int h, const uint8_t rgb[3], const std::vector<uint8_t>& icc = {}) {
    OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
    if (!icc.empty()) spec.attribute("ICCProfile", OIIO::TypeDesc(OIIO::TypeDesc::UINT8, int(icc.size())), icc.data());
    std::vector<uint8_t> pixels(size_t(w) * h * 3);
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = rgb[i % 3];
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out && out->open(path, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    out->close();
}

const std::array<glm::dvec2, 3> kP3 = {glm::dvec2(0.680, 0.320), glm::dvec2(0.265, 0.690), glm::dvec2(0.150, 0.060)};
const std::array<glm::dvec2, 3> kRec709 = {glm::dvec2(0.64, 0.33), glm::dvec2(0.30, 0.60), glm::dvec2(0.15, 0.06)};
const glm::dvec2 kD65(0.3127, 0.3290);

/// A LUT-based input profile (ICC v4, A2B0 a 17^3 grid from RGB codes to PCS Lab) sampled from
/// the matrix profile `matrix`: the kind camera and scanner vendors ship.
std::vector<uint8_t> lut_profile_sampling(const std::vector<uint8_t>& matrix, const char* description) {
    cmsHPROFILE src = cmsOpenProfileFromMem(matrix.data(), cmsUInt32Number(matrix.size()));
    cmsHPROFILE lab = cmsCreateLab4Profile(nullptr);
    cmsHTRANSFORM to_lab = cmsCreateTransform(src, TYPE_RGB_16, lab, TYPE_Lab_16, INTENT_RELATIVE_COLORIMETRIC, 0);
    cmsHPROFILE out = cmsCreateProfilePlaceholder(nullptr);
    cmsSetProfileVersion(out, 4.3);
    cmsSetDeviceClass(out, cmsSigInputClass);
    cmsSetColorSpace(out, cmsSigRgbData);
    cmsSetPCS(out, cmsSigLabData);
    cmsPipeline* lut = cmsPipelineAlloc(nullptr, 3, 3);
    cmsStage* grid = cmsStageAllocCLut16bit(nullptr, 17, 3, 3, nullptr);  // in one JPEG APP2 segment
    cmsStageSampleCLut16bit(
        grid,
        [](const cmsUInt16Number in[], cmsUInt16Number result[], void* t) -> cmsInt32Number {
            cmsDoTransform(static_cast<cmsHTRANSFORM>(t), in, result, 1);
            return TRUE;
        },
        to_lab, 0);
    // lutAtoBType's layout: A curves, the grid, B curves (both the identity here).
    cmsPipelineInsertStage(lut, cmsAT_END, cmsStageAllocToneCurves(nullptr, 3, nullptr));
    cmsPipelineInsertStage(lut, cmsAT_END, grid);
    cmsPipelineInsertStage(lut, cmsAT_END, cmsStageAllocToneCurves(nullptr, 3, nullptr));
    cmsWriteTag(out, cmsSigAToB0Tag, lut);
    cmsWriteTag(out, cmsSigMediaWhitePointTag, cmsD50_XYZ());
    cmsMLU* mlu = cmsMLUalloc(nullptr, 1);
    cmsMLUsetASCII(mlu, "en", "US", description);
    cmsWriteTag(out, cmsSigProfileDescriptionTag, mlu);
    cmsUInt32Number size = 0;
    cmsSaveProfileToMem(out, nullptr, &size);
    std::vector<uint8_t> bytes(size);
    cmsSaveProfileToMem(out, bytes.data(), &size);
    cmsMLUfree(mlu);
    cmsPipelineFree(lut);
    cmsDeleteTransform(to_lab);
    cmsCloseProfile(out);
    cmsCloseProfile(lab);
    cmsCloseProfile(src);
    return bytes;
}

}  // namespace

TEST(ImagePlates, AnExrLoadsAsItsDisplayWindowWithBlackOutsideTheDataWindow) {
    TempDir dir;
    const std::string path = dir.file("bbox.exr");
    // A 4x3 data window at (5, 2) in a 10x8 display window: a Nuke plate with a bounding box.
    std::vector<float> pixels(4 * 3 * 3, 0.5f);
    write_exr(path, 4, 3, {"R", "G", "B"}, pixels, 5, 2, 10, 8);
    ImageLoadReport report;
    const Image image = load_image(path, "photo", &report);
    ASSERT_EQ(image.width(), 10);
    ASSERT_EQ(image.height(), 8);
    EXPECT_TRUE(report.window_differs);
    EXPECT_EQ(report.data_x, 5);
    EXPECT_EQ(report.data_y, 2);
    EXPECT_EQ(image.at(5, 2), vec3(0.5f));
    EXPECT_EQ(image.at(8, 4), vec3(0.5f));
    EXPECT_EQ(image.at(4, 2), vec3(0.0f));
    EXPECT_EQ(image.at(5, 5), vec3(0.0f));
    int w = 0, h = 0;
    ASSERT_TRUE(read_image_size(path, w, h));
    EXPECT_EQ(w, 10);  // the header's size is the one the image loads at
    EXPECT_EQ(h, 8);
}

TEST(ImagePlates, ABlenderMultilayerRenderLoadsItsCombinedPassOrTheLayerAskedFor) {
    TempDir dir;
    const std::string path = dir.file("multilayer.exr");
    const std::vector<std::string> channels = {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B",
                                               "ViewLayer.Combined.A", "ViewLayer.Shadow.R", "ViewLayer.Shadow.G",
                                               "ViewLayer.Shadow.B", "ViewLayer.Depth.Z"};
    std::vector<float> pixels;
    for (int i = 0; i < 6; ++i) pixels.insert(pixels.end(), {0.1f, 0.2f, 0.3f, 1.0f, 0.7f, 0.8f, 0.9f, 5.0f});
    write_exr(path, 3, 2, channels, pixels);

    ImageLoadReport report;
    const Image combined = load_image(path, "photo", &report);
    EXPECT_EQ(report.layer, "ViewLayer.Combined");
    ASSERT_EQ(report.layers.size(), 2u);
    EXPECT_EQ(combined.at(2, 1), vec3(0.1f, 0.2f, 0.3f));

    ImageLoadOptions options;
    options.layer = "ViewLayer.Shadow";
    EXPECT_EQ(load_image(path, "photo", nullptr, options).at(0, 0), vec3(0.7f, 0.8f, 0.9f));

    options.layer = "ViewLayer.Mist";
    try {
        load_image(path, "photo", nullptr, options);
        FAIL() << "an unknown layer must be refused";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("ViewLayer.Combined"), std::string::npos) << e.what();
    }
}

TEST(ImagePlates, APlateWithTwoCombinedLayersIsRefusedUnlessOneIsNamed) {
    TempDir dir;
    const std::string path = dir.file("two.exr");
    const std::vector<std::string> channels = {"Composite.Combined.R", "Composite.Combined.G", "Composite.Combined.B",
                                               "ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B"};
    std::vector<float> pixels;
    for (int i = 0; i < 4; ++i) pixels.insert(pixels.end(), {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f});
    write_exr(path, 2, 2, channels, pixels);
    try {
        load_image(path, "photo.path");
        FAIL() << "two Combined layers were not refused";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.field(), "photo.path");
        EXPECT_NE(what.find("2 Combined layers (\"Composite.Combined\", \"ViewLayer.Combined\")"), std::string::npos) << what;
    }
    ImageLoadOptions options;
    options.layer = "ViewLayer.Combined";
    EXPECT_EQ(load_image(path, "photo", nullptr, options).at(1, 1), vec3(0.4f, 0.5f, 0.6f));
}

TEST(ImagePlates, ADisplayP3PhotoIsConvertedToLinearRec709ByItsIccProfile) {
    TempDir dir;
    const uint8_t red[3] = {255, 0, 0};
    write_png(dir.file("p3.png"), 2, 2, red, make_icc_rgb_profile("Display P3", kP3, kD65, true, 0));
    ImageLoadReport report;
    const Image image = load_image(dir.file("p3.png"), "photo", &report);
    EXPECT_EQ(report.icc_profile, "Display P3");
    EXPECT_TRUE(report.icc_converted);
    // P3's red lies outside sRGB: (1.2249, -0.0421, -0.0196) in linear Rec.709 (ITU-R BT.2087's
    // matrix through XYZ); the profile's s15Fixed16 numbers allow about 1e-3.
    EXPECT_NEAR(image.at(0, 0).x, 1.2249f, 3e-3f);
    EXPECT_NEAR(image.at(0, 0).y, -0.0421f, 3e-3f);
    EXPECT_NEAR(image.at(0, 0).z, -0.0196f, 3e-3f);
}

TEST(ImagePlates, AColourSpaceGivenForAPhotoWinsOverItsIccProfile) {
    TempDir dir;
    const uint8_t colour[3] = {200, 97, 13};
    write_png(dir.file("p3.png"), 2, 2, colour, make_icc_rgb_profile("Display P3", kP3, kD65, true, 0));
    write_png(dir.file("plain.png"), 2, 2, colour);
    for (const char* space : {"srgb", "linear"}) {
        ImageLoadOptions options;
        options.colorspace = space;
        ImageLoadReport report;
        const Image given = load_image(dir.file("p3.png"), "photo", &report, options);
        // Check: read as the space says, exactly as the untagged file is, not by the profile.
        EXPECT_FALSE(report.icc_converted) << space;
        EXPECT_EQ(report.colorspace, space);
        EXPECT_TRUE(dp::test::bit_identical(given, load_image(dir.file("plain.png"), "photo", nullptr, options))) << space;
    }
    // Left automatic, the profile is read (guard: the two readings differ).
    ImageLoadReport report;
    load_image(dir.file("p3.png"), "photo", &report);
    EXPECT_TRUE(report.icc_converted);
}

TEST(ImagePlates, AnSrgbTaggedPhotoLoadsExactlyAsAnUntaggedOne) {
    TempDir dir;
    const uint8_t colour[3] = {200, 97, 13};
    write_png(dir.file("plain.png"), 2, 2, colour);
    write_png(dir.file("tagged.png"), 2, 2, colour, make_icc_rgb_profile("sRGB", kRec709, kD65, true, 0));
    ImageLoadReport report;
    const Image tagged = load_image(dir.file("tagged.png"), "photo", &report);
    EXPECT_FALSE(report.icc_converted);
    EXPECT_TRUE(dp::test::bit_identical(tagged, load_image(dir.file("plain.png"), "photo")));
}

TEST(ImagePlates, AnUnreadableIccProfileIsReportedAndThePhotoReadAsSrgb) {
    TempDir dir;
    std::vector<uint8_t> grey = make_icc_rgb_profile("Grey thing", kRec709, kD65, false, 2.2);
    std::memcpy(grey.data() + 16, "GRAY", 4);
    const uint8_t colour[3] = {128, 128, 128};
    // libpng refuses a grey profile in an RGB file; JPEG carries whatever it is given.
    write_png(dir.file("grey.jpg"), 8, 8, colour, grey);
    ImageLoadReport report;
    const Image image = load_image(dir.file("grey.jpg"), "photo", &report);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("Grey thing"), std::string::npos) << report.warnings[0];
    EXPECT_NEAR(image.at(0, 0).x, srgb_to_linear(128.0f / 255.0f), 0.01f);
}

TEST(ImagePlates, ASixteenBitTiffCanBeMarkedLinear) {
    TempDir dir;
    const std::string path = dir.file("linear.tif");
    OIIO::ImageSpec spec(2, 1, 3, OIIO::TypeDesc::UINT16);
    const uint16_t pixels[6] = {32768, 0, 65535, 16384, 100, 0};
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out && out->open(path, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT16, pixels));
    out->close();

    ImageLoadOptions linear;
    linear.colorspace = "linear";
    ImageLoadReport report;
    const Image image = load_image(path, "photo", &report, linear);
    EXPECT_TRUE(report.linear_source);
    EXPECT_FLOAT_EQ(image.at(0, 0).x, 32768.0f / 65535.0f);
    EXPECT_EQ(report.clipped, 1u);  // the first pixel's blue is at the top code
    // Unmarked, the same codes are sRGB.
    EXPECT_FLOAT_EQ(load_image(path, "photo").at(0, 0).x, srgb_to_linear(32768.0f / 65535.0f));
}

TEST(ImagePlates, AnOpenColorIoColourSpaceIsConvertedToSceneLinear) {
    if (ocio_config_path().empty()) GTEST_SKIP() << "no OpenColorIO config (Blender's or $OCIO)";
    TempDir dir;
    const std::string path = dir.file("acescg.exr");
    write_exr(path, 1, 1, {"R", "G", "B"}, {1.0f, 0.0f, 0.0f});
    ImageLoadOptions options;
    options.colorspace = "Linear ACEScg";
    const Image image = load_image(path, "photo", nullptr, options);
    // ACEScg red in linear Rec.709 is about (1.705, -0.130, -0.024).
    EXPECT_NEAR(image.at(0, 0).x, 1.705f, 0.01f);
    EXPECT_NEAR(image.at(0, 0).y, -0.130f, 0.01f);
    EXPECT_NEAR(image.at(0, 0).z, -0.024f, 0.01f);
    options.colorspace = "Not A Space";
    EXPECT_THROW(load_image(path, "photo", nullptr, options), InputError);
}

TEST(ImagePlates, AVersion4ProfileReadsAsItsVersion2Twin) {
    TempDir dir;
    const uint8_t colour[3] = {200, 97, 13};
    write_png(dir.file("v2.png"), 2, 2, colour, make_icc_rgb_profile("Display P3", kP3, kD65, true, 0, 2.1));
    write_png(dir.file("v4.png"), 2, 2, colour, make_icc_rgb_profile("Display P3", kP3, kD65, true, 0, 4.3));
    ImageLoadReport report;
    const vec3 v4 = load_image(dir.file("v4.png"), "photo", &report).at(0, 0);
    EXPECT_TRUE(report.icc_converted);
    const vec3 v2 = load_image(dir.file("v2.png"), "photo").at(0, 0);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(v4[c], v2[c], 1e-4f) << c;
}

TEST(ImagePlates, ALutBasedCameraProfileIsReadLikeTheMatrixProfileItSamples) {
    TempDir dir;
    const uint8_t colour[3] = {200, 97, 13};
    // JPEG: libpng drops a profile whose connection space is Lab; JPEG carries any.
    const std::vector<uint8_t> matrix = make_icc_rgb_profile("Display P3", kP3, kD65, true, 0);
    write_png(dir.file("matrix.jpg"), 2, 2, colour, matrix);
    write_png(dir.file("lut.jpg"), 2, 2, colour, lut_profile_sampling(matrix, "Camera LUT"));
    ImageLoadReport report;
    const vec3 lut = load_image(dir.file("lut.jpg"), "photo", &report).at(0, 0);
    EXPECT_EQ(report.icc_profile, "Camera LUT");
    EXPECT_TRUE(report.icc_converted);
    EXPECT_TRUE(report.warnings.empty()) << report.warnings[0];
    const vec3 by_matrix = load_image(dir.file("matrix.jpg"), "photo").at(0, 0);
    const vec3 as_srgb = load_image(dir.file("matrix.jpg"), "photo", nullptr, [] {
        ImageLoadOptions o;
        o.colorspace = "srgb";
        return o;
    }()).at(0, 0);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(lut[c], by_matrix[c], 5e-3f) << c;
    // Guard: read as sRGB (what a LUT profile fell back to before) the pixel differs by more.
    EXPECT_GT(glm::length(as_srgb - by_matrix), 0.05f);
}
