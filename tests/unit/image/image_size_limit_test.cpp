// Decoding is bounded from the header: a file declaring more pixels than the limit is refused
// before anything is allocated, whatever its own size.
#include <gtest/gtest.h>

#include <ImfHeader.h>
#include <ImfStdIO.h>
#include <ImfVersion.h>
#include <ImfXdr.h>

#include <fstream>
#include <string>

#include "base/error.h"
#include "image/image_io.h"
#include "forged_headers.h"
#include "image_test_util.h"

using namespace dp;
using dp::test::TempDir;
using namespace dp::test;

namespace {

void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
}

/// An EXR's magic number, version and header declaring width x height, and no pixels.
void write_exr_header(const std::string& path, int width, int height) {
    Imf::Header header(width, height);
    Imf::StdOFStream out(path.c_str());
    Imf::Xdr::write<Imf::StreamIO>(out, Imf::MAGIC);
    Imf::Xdr::write<Imf::StreamIO>(out, Imf::EXR_VERSION);
    header.writeTo(out);
}

/// The refusal from the header: names the file and field, the declared size and the limit.
void expect_refused(const std::string& path, const std::string& size_text) {
    try {
        load_image(path, "probe.path");
        ADD_FAILURE() << "no InputError for " << path;
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.field(), "probe.path");
        EXPECT_NE(what.find(size_text), std::string::npos) << what;
        EXPECT_NE(what.find("of memory, more than the limit"), std::string::npos) << what;
    }
}

}  // namespace

TEST(ImageSizeLimit, APngBombIsRefusedFromItsHeader) {
    TempDir dir;
    const std::string path = dir.file("bomb.png");
    write_bytes(path, png_declaring(100000, 100000, 16));
    expect_refused(path, "100000 x 100000 pixels");
}

TEST(ImageSizeLimit, AnExrBombIsRefusedFromItsHeader) {
    TempDir dir;
    const std::string path = dir.file("bomb.exr");
    write_exr_header(path, 2000000000, 2000000000);
    expect_refused(path, "2000000000 x 2000000000 pixels");
}

TEST(ImageSizeLimit, AnHdrBombIsRefusedFromItsHeader) {
    TempDir dir;
    const std::string path = dir.file("bomb.hdr");
    write_bytes(path, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 20000 +X 40000\n");
    expect_refused(path, "40000 x 20000 pixels");
}

TEST(ImageSizeLimit, ALargeValidProbeIsRefusedWithItsFigure) {
    // 32768 x 16384 is 2^29 pixels, twice the limit; its header alone is enough to say so.
    TempDir dir;
    const std::string path = dir.file("big.exr");
    write_exr_header(path, 32768, 16384);
    expect_refused(path, "32768 x 16384 pixels");
}

TEST(ImageSizeLimit, HeadersGiveTheSizeOfEveryFormat) {
    TempDir dir;
    int w = 0, h = 0;
    write_bytes(dir.file("a.png"), png_declaring(640, 480, 16));
    ASSERT_TRUE(read_image_size(dir.file("a.png"), w, h));
    EXPECT_EQ(w, 640);
    EXPECT_EQ(h, 480);
    write_bytes(dir.file("a.hdr"), "#?RGBE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=1\n\n-Y 17 +X 33\n");
    ASSERT_TRUE(read_image_size(dir.file("a.hdr"), w, h));
    EXPECT_EQ(w, 33);
    EXPECT_EQ(h, 17);
    write_exr_header(dir.file("a.exr"), 31, 7);
    ASSERT_TRUE(read_image_size(dir.file("a.exr"), w, h));
    EXPECT_EQ(w, 31);
    EXPECT_EQ(h, 7);
}

TEST(ImageSizeLimit, TheLimitIsAtMost2To28Pixels) {
    EXPECT_LE(max_decoded_image_pixels(), kMaxImagePixels);
    EXPECT_GT(max_decoded_image_pixels(), 0u);
    const int64_t limit = int64_t(max_decoded_image_pixels());
    EXPECT_NO_THROW(check_image_size("x.exr", "photo.path", limit, 1));
    EXPECT_THROW(check_image_size("x.exr", "photo.path", limit + 1, 1), InputError);
    EXPECT_THROW(check_image_size("x.exr", "photo.path", 16385, 16384), InputError);
}

// A JPEG, PNG, EXR, HDR or BMP whose header gives no size is refused rather than handed to a
// decoder that would guess (a JPEG whose frame header says height 0 made OpenCV allocate 2 GB).
TEST(ImageSizeLimit, AHeaderThatGivesNoSizeIsRefusedBeforeDecoding) {
    TempDir dir;
    const std::string jpeg = dir.file("zero_height.jpg");
    // SOI, then a baseline frame header (SOF0) declaring 0 rows of 640 columns, then end of image.
    write_bytes(jpeg, std::string("\xFF\xD8\xFF\xC0\x00\x11\x08\x00\x00\x02\x80\x03"
                                  "\x01\x22\x00\x02\x11\x01\x03\x11\x01\xFF\xD9",
                                  23));
    const std::string png = dir.file("zero_width.png");
    write_bytes(png, png_declaring(0, 480, 16));
    for (const std::string& path : {jpeg, png}) {
        try {
            load_image(path, "photo.path");
            ADD_FAILURE() << "no InputError for " << path;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("header gives no valid size"), std::string::npos) << e.what();
            EXPECT_EQ(e.field(), "photo.path");
        }
    }
}
