// EXIF orientation: a JPEG loads upright, as viewers show it (a phone's portrait photo is
// stored landscape with orientation 6 or 8), and the size read from its header says the same.
#include <gtest/gtest.h>

#include <fstream>

#include "common/exif_jpeg.h"
#include "image/image_io.h"
#include "image_test_util.h"

using namespace dp;
using namespace dp::test;

namespace {

void write(const std::string& path, const std::vector<uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

/// Which corner of `image` holds the bright square: 0 top-left, 1 top-right, 2 bottom-left,
/// 3 bottom-right; -1 when none or more than one is bright.
int bright_corner(const Image& image) {
    const int w = image.width(), h = image.height();
    const int xs[4] = {2, w - 3, 2, w - 3}, ys[4] = {2, 2, h - 3, h - 3};
    int found = -1;
    for (int i = 0; i < 4; ++i) {
        if (image.at(xs[i], ys[i]).x > 0.5f) {
            if (found >= 0) return -1;
            found = i;
        }
    }
    return found;
}

/// Loads a 64x48 marked JPEG with `orientation` and checks size and corner both ways.
void expect_upright(int orientation, bool big_endian, int width, int height, int corner) {
    TempDir dir;
    const std::string path = dir.file("photo.jpg");
    write(path, with_exif_orientation(marked_jpeg(64, 48), orientation, big_endian));
    const Image image = load_image(path);
    EXPECT_EQ(image.width(), width) << "orientation " << orientation;
    EXPECT_EQ(image.height(), height) << "orientation " << orientation;
    EXPECT_EQ(bright_corner(image), corner) << "orientation " << orientation;
    int w = 0, h = 0;
    ASSERT_TRUE(read_image_size(path, w, h));
    EXPECT_EQ(w, width) << "header size, orientation " << orientation;
    EXPECT_EQ(h, height) << "header size, orientation " << orientation;
}

}  // namespace

TEST(ImageOrientation, AJpegWithoutOrientationLoadsAsStored) {
    TempDir dir;
    write(dir.file("plain.jpg"), marked_jpeg(64, 48));
    const Image image = load_image(dir.file("plain.jpg"));
    EXPECT_EQ(image.width(), 64);
    EXPECT_EQ(bright_corner(image), 0);
    expect_upright(1, false, 64, 48, 0);
}

TEST(ImageOrientation, OrientationSixTurnsThePictureAQuarterClockwise) {
    // The stored top-left corner ends up top right; the landscape becomes portrait.
    expect_upright(6, false, 48, 64, 1);
    expect_upright(6, true, 48, 64, 1);
}

TEST(ImageOrientation, OrientationEightTurnsThePictureAQuarterAnticlockwise) {
    expect_upright(8, false, 48, 64, 2);
    expect_upright(8, true, 48, 64, 2);
}

TEST(ImageOrientation, OrientationThreeTurnsItHalfWayRoundKeepingTheSize) {
    expect_upright(3, false, 64, 48, 3);
}

TEST(ImageOrientation, AnOutOfRangeOrientationIsIgnoredBothWays) {
    expect_upright(9, false, 64, 48, 0);
}
