// The reader takes an image's format from its name and checks the file's first bytes, and bounds
// what it decodes by what the header declares: a misnamed or forged file is refused at once,
// naming the file, the field and what was found, before any decoder sees it.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "base/error.h"
#include "image/display_transform.h"
#include "image/image_io.h"
#include "forged_headers.h"
#include "image_test_util.h"

using namespace dp;
using dp::test::random_image;
using dp::test::TempDir;
using namespace dp::test;

namespace {

void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
}


/// The InputError load_image throws for `path` as `field`; fails the test when there is none.
std::string refusal(const std::string& path, const std::string& field = "photo.path") {
    try {
        load_image(path, field);
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(e.field(), field);
        return e.what();
    }
    ADD_FAILURE() << "no InputError for " << path;
    return "";
}

}  // namespace

TEST(ImageFormat, ZerosNamedAsEachFormatAreRefusedByTheirFirstBytes) {
    TempDir dir;
    const std::pair<const char*, const char*> cases[] = {
        {"zeros.png", "not a PNG file (its first bytes are 00 00 00 00"},
        {"zeros.exr", "not an OpenEXR file (its first bytes are 00 00 00 00"},
        {"zeros.jpg", "not a JPEG file"},
        {"zeros.jpeg", "not a JPEG file"},
        {"zeros.hdr", "not a Radiance HDR file"},
        {"zeros.tif", "not a TIFF file"},
        {"zeros.bmp", "not a BMP file"},
    };
    for (const auto& [name, text] : cases) {
        const std::string path = dir.file(name);
        write_bytes(path, std::string(4096, '\0'));
        const std::string what = refusal(path);
        EXPECT_NE(what.find(text), std::string::npos) << what;
        EXPECT_NE(what.find("field 'photo.path'"), std::string::npos) << what;
    }
}

TEST(ImageFormat, ALargeZeroFilledFileIsRefusedWithoutBeingRead) {
    // 200 MB of zeros named as a PNG went to OpenImageIO's DICOM reader for 23 s.
    TempDir dir;
    const std::string path = dir.file("photo.png");
    write_bytes(path, "");
    std::filesystem::resize_file(path, 200u << 20);
    const auto start = std::chrono::steady_clock::now();
    const std::string what = refusal(path);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_NE(what.find("not a PNG file"), std::string::npos) << what;
    EXPECT_LT(seconds, 1.0);
}

TEST(ImageFormat, AFileOfAnotherFormatIsToldItsRightName) {
    TempDir dir;
    const Image image = random_image(8, 6, 3, 0.0f, 1.0f);
    save_ldr(dir.file("real.jpg"), image);
    std::filesystem::copy_file(dir.file("real.jpg"), dir.file("renamed.png"));
    const std::string what = refusal(dir.file("renamed.png"));
    EXPECT_NE(what.find("not a PNG file (its first bytes are ff d8 ff"), std::string::npos) << what;
    EXPECT_NE(what.find("those of a JPEG file: name it .jpg"), std::string::npos) << what;
}

TEST(ImageFormat, AnExtensionOfNoDocumentedFormatIsRefusedWhateverTheContent) {
    // OpenImageIO would read a PNG named .xyz by its content; the reader goes by the name.
    TempDir dir;
    save_ldr(dir.file("real.png"), random_image(4, 4, 5, 0.0f, 1.0f));
    std::filesystem::copy_file(dir.file("real.png"), dir.file("picture.xyz"));
    const std::string what = refusal(dir.file("picture.xyz"));
    EXPECT_NE(what.find("unrecognised extension '.xyz'"), std::string::npos) << what;
    EXPECT_NE(what.find(".exr, .hdr, .png, .jpg, .jpeg, .tif, .tiff, .bmp"), std::string::npos) << what;
}

TEST(ImageFormat, ExtensionsAreReadWhateverTheirCase) {
    TempDir dir;
    const Image image = random_image(5, 4, 9, 0.0f, 1.0f);
    save_ldr(dir.file("a.png"), image);
    std::filesystem::copy_file(dir.file("a.png"), dir.file("UPPER.PNG"));
    EXPECT_EQ(load_image(dir.file("UPPER.PNG"), "photo.path").width(), 5);
}

TEST(ImageFormat, EmbeddedBytesAreNamedByTheirContent) {
    EXPECT_EQ(image_extension_for_content("\x89PNG\r\n\x1a\n....", 12), "png");
    EXPECT_EQ(image_extension_for_content("\xFF\xD8\xFF\xE0", 4), "jpg");
    EXPECT_EQ(image_extension_for_content("\x76\x2f\x31\x01", 4), "exr");
    EXPECT_EQ(image_extension_for_content("#?RADIANCE", 10), "hdr");
    EXPECT_EQ(image_extension_for_content("II*\0", 4), "tif");
    EXPECT_EQ(image_extension_for_content("BM", 2), "bmp");
    EXPECT_EQ(image_extension_for_content("GIF89a", 6), "");
    EXPECT_EQ(image_extension_for_content("", 0), "");
}

TEST(ImageHeaderSize, AKilobyteJpegDeclaring16000x16000IsRefusedFromItsHeader) {
    // 16000 x 16000 is within the pixel limit of a machine of 12.3 GB or more, but a complete
    // JPEG of it takes at least one bit a luma block: 500 kB. The decoder would allocate 4.9 GB
    // before finding the data missing.
    TempDir dir;
    const std::string path = dir.file("bomb.jpg");
    write_bytes(path, jpeg_declaring(16000, 16000, 1000));
    const std::string what = refusal(path);
    EXPECT_NE(what.find("16000 x 16000 pixels"), std::string::npos) << what;
    if (max_decoded_image_pixels() >= 16000u * 16000u) {
        EXPECT_NE(what.find("declares 16000 x 16000 pixels, which a file of 1037 bytes cannot hold"), std::string::npos)
            << what;
        EXPECT_NE(what.find("a complete JPEG of that size takes at least 500000 bytes"), std::string::npos) << what;
    }
}

TEST(ImageHeaderSize, APngTooShortForItsRowsIsRefusedFromItsHeader) {
    TempDir dir;
    const std::string path = dir.file("bomb.png");
    // Signature and IHDR of an 8000 x 8000 picture: its rows, deflated, take at least 62 kB.
    write_bytes(path, png_declaring(8000, 8000, 1000));
    const std::string what = refusal(path);
    EXPECT_NE(what.find("declares 8000 x 8000 pixels"), std::string::npos) << what;
    EXPECT_NE(what.find("deflate packs at most 1032 bytes"), std::string::npos) << what;
}

TEST(ImageHeaderSize, AnHdrAndABmpTooShortForTheirRowsAreRefused) {
    TempDir dir;
    write_bytes(dir.file("bomb.hdr"), "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8000 +X 8000\n" + std::string(1000, '\0'));
    EXPECT_NE(refusal(dir.file("bomb.hdr")).find("declares 8000 x 8000 pixels"), std::string::npos);
    // BITMAPINFOHEADER of 8000 x 8000 at 24 bits, uncompressed: 192 MB of rows.
    std::string bmp = "BM" + le32(1054) + le32(0) + le32(54) + le32(40) + le32(8000) + le32(8000) + le16(1) +
                      le16(24) + le32(0) + le32(0) + le32(0) + le32(0) + le32(0) + le32(0);
    write_bytes(dir.file("bomb.bmp"), bmp + std::string(1000, '\0'));
    const std::string what = refusal(dir.file("bomb.bmp"));
    EXPECT_NE(what.find("declares 8000 x 8000 pixels"), std::string::npos) << what;
    EXPECT_NE(what.find("stored uncompressed"), std::string::npos) << what;
}

TEST(ImageHeaderSize, ATiffIsMeasuredFromItsHeaderToo) {
    TempDir dir;
    write_bytes(dir.file("small.tif"), tiff_declaring(640, 480));
    int w = 0, h = 0;
    ASSERT_TRUE(read_image_size(dir.file("small.tif"), w, h));
    EXPECT_EQ(w, 640);
    EXPECT_EQ(h, 480);
    write_bytes(dir.file("bomb.tif"), tiff_declaring(100000, 100000));
    const std::string what = refusal(dir.file("bomb.tif"));
    EXPECT_NE(what.find("100000 x 100000 pixels"), std::string::npos) << what;
    EXPECT_NE(what.find("of memory, more than the limit"), std::string::npos) << what;
}

TEST(ImageHeaderSize, AnUncompressedTiffTooShortForItsSamplesIsRefused) {
    // Within the pixel limit, but 50 bytes cannot hold 2048 x 2048 samples stored as they are:
    // the decoder would allocate the picture and fill it with zeros.
    TempDir dir;
    write_bytes(dir.file("short.tif"), tiff_declaring(2048, 2048));
    const std::string what = refusal(dir.file("short.tif"));
    EXPECT_NE(what.find("declares 2048 x 2048 pixels"), std::string::npos) << what;
    EXPECT_NE(what.find("uncompressed, it holds at least a bit per sample"), std::string::npos) << what;
}

TEST(ImageHeaderSize, CompleteFilesOfEveryFormatStillLoad) {
    TempDir dir;
    const Image image = random_image(64, 48, 17, 0.0f, 1.0f);
    for (const char* name : {"a.png", "a.jpg", "a.tif"}) {
        save_display_image(dir.file(name), image, DisplayTransform());
        EXPECT_EQ(load_image(dir.file(name), "photo.path").width(), 64) << name;
    }
    save_exr(dir.file("a.exr"), {{"", &image}});
    EXPECT_EQ(load_image(dir.file("a.exr"), "photo.path").height(), 48);
}

TEST(ImageHeaderSize, AFifoIsNeitherMeasuredNorOpened) {
    TempDir dir;
    const std::string path = dir.file("pipe.png");
    ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
    int w = 0, h = 0;
    EXPECT_FALSE(read_image_size(path, w, h));  // would block on open
    EXPECT_NE(refusal(path).find("is a FIFO"), std::string::npos);
    EXPECT_TRUE(read_image_metadata(path).empty());
}
