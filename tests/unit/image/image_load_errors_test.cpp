#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "base/error.h"
#include "image/image_io.h"
#include "image_test_util.h"

using namespace dp;
using dp::test::random_image;
using dp::test::TempDir;

namespace {

// Loading must throw InputError whose message names the file, the field and `reason`.
void expect_input_error(const std::string& path, const std::string& field,
                        const std::string& reason) {
    try {
        load_image(path, field);
        ADD_FAILURE() << "no InputError for " << path;
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(path), std::string::npos) << what;
        EXPECT_NE(what.find(field), std::string::npos) << what;
        EXPECT_NE(what.find(reason), std::string::npos) << what;
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(e.field(), field);
    }
}

void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
}

void truncate_to_half(const std::string& path) {
    const auto size = std::filesystem::file_size(path);
    ASSERT_GT(size, 100u);
    std::filesystem::resize_file(path, size / 2);
}

}  // namespace

TEST(ImageLoadErrors, MissingFileThrowsInputErrorNamingPathAndField) {
    TempDir dir;
    expect_input_error(dir.file("absent.exr"), "background", "file not found");
    expect_input_error(dir.file("absent.png"), "photo", "file not found");
}

TEST(ImageLoadErrors, TruncatedExrThrowsInputErrorInsteadOfCrashing) {
    TempDir dir;
    // Noise keeps the compressed pixel data large, so half the file cuts into it.
    const Image image = random_image(64, 64, 21, -1.0f, 1.0f);
    const std::string path = dir.file("cut.exr");
    save_exr(path, {{"", &image}, {"albedo", &image}});
    truncate_to_half(path);
    expect_input_error(path, "background", "cannot read image");
    EXPECT_THROW(load_exr_layer(path, "albedo"), InputError);
}

TEST(ImageLoadErrors, TruncatedPngThrowsInputError) {
    TempDir dir;
    const Image image = random_image(64, 64, 22, 0.0f, 1.0f);
    const std::string path = dir.file("cut.png");
    save_ldr(path, image);
    truncate_to_half(path);
    expect_input_error(path, "photo", "cannot read image");
}

TEST(ImageLoadErrors, GarbageBytesWithPngExtensionThrowInputError) {
    TempDir dir;
    const std::string path = dir.file("garbage.png");
    write_bytes(path, std::string(300, '\x5a') + "not an image at all");
    expect_input_error(path, "photo", "not a PNG file (its first bytes are 5a 5a 5a 5a");
}

TEST(ImageLoadErrors, GarbageBytesWithExrExtensionThrowInputError) {
    TempDir dir;
    const std::string path = dir.file("garbage.exr");
    write_bytes(path, std::string(300, '\x11'));
    expect_input_error(path, "background", "not an OpenEXR file (its first bytes are 11 11 11 11");
}

TEST(ImageLoadErrors, GarbageWithUnknownExtensionSaysTheFormatIsUnrecognised) {
    TempDir dir;
    const std::string path = dir.file("garbage.xyz");
    write_bytes(path, std::string(300, '\x33'));
    expect_input_error(path, "mask", "unrecognised extension '.xyz'");
}

TEST(ImageLoadErrors, EmptyFileThrowsInputErrorSayingZeroSize) {
    TempDir dir;
    const std::string path = dir.file("empty.png");
    write_bytes(path, "");
    expect_input_error(path, "photo", "zero size");
    const std::string exr = dir.file("empty.exr");
    write_bytes(exr, "");
    expect_input_error(exr, "background", "zero size");
}

TEST(ImageLoadErrors, DirectoryInsteadOfFileThrowsInputError) {
    TempDir dir;
    std::filesystem::create_directory(dir.file("folder.png"));
    expect_input_error(dir.file("folder.png"), "photo", "is a folder");
}
