#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <exiv2/exiv2.hpp>
#include <opencv2/imgcodecs.hpp>

#include "base/error.h"
#include "calibration/exif.h"
#include "common/input_error.h"
#include "image/image_io.h"

using namespace dp;
using dp::test::input_error_message;

namespace {

class Exif : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("dp_exif_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    /// A 640x480 JPEG without EXIF (OpenCV writes none).
    std::string plain_jpeg(const std::string& name) {
        std::string path = (dir_ / name).string();
        cv::imwrite(path, cv::Mat(480, 640, CV_8UC3, cv::Scalar(90, 120, 150)));
        return path;
    }
    /// The same with the given EXIF tags written by exiv2 (the name's extension chooses the
    /// format: .jpg, .tif, .png).
    std::string jpeg_with(const std::string& name,
                          const std::vector<std::pair<std::string, std::string>>& tags) {
        std::string path = plain_jpeg(name);
        auto image = Exiv2::ImageFactory::open(path);
        image->readMetadata();
        Exiv2::ExifData& exif = image->exifData();
        for (const auto& [key, value] : tags) exif[key] = value;
        image->writeMetadata();
        return path;
    }
    std::filesystem::path dir_;
};

}  // namespace

TEST_F(Exif, ThirtyFiveMillimetreEquivalentGivesTheFocalOnTheDiagonal) {
    auto path = jpeg_with("phone.jpg", {{"Exif.Image.Make", "Acme"},
                                         {"Exif.Photo.FocalLength", "425/100"},
                                         {"Exif.Photo.FocalLengthIn35mmFilm", "26"}});
    ExifFocal f = read_exif_focal(path);
    EXPECT_EQ(f.width, 640);
    EXPECT_EQ(f.height, 480);
    EXPECT_DOUBLE_EQ(f.focal_mm, 4.25);
    // 26 mm on the 43.27 mm diagonal of full frame; the image diagonal is 800 px.
    EXPECT_NEAR(f.focal_px, 26.0 * 800.0 / std::hypot(36.0, 24.0), 1e-9);
    EXPECT_EQ(f.camera, "Acme");
}

TEST_F(Exif, FocalPlaneResolutionGivesTheSensorWidth) {
    // 50 mm lens; 640 px across a 16 mm wide sensor: 40 px/mm = 1016 px/inch.
    auto path = jpeg_with("dslr.jpg", {{"Exif.Photo.FocalLength", "50/1"},
                                        {"Exif.Photo.FocalPlaneXResolution", "1016/1"},
                                        {"Exif.Photo.FocalPlaneResolutionUnit", "2"}});
    ExifFocal f = read_exif_focal(path);
    EXPECT_NEAR(f.sensor_width_mm, 16.0, 1e-9);
    EXPECT_NEAR(f.focal_px, 50.0 * 640.0 / 16.0, 1e-9);
}

TEST_F(Exif, AGivenSensorWidthWinsOverTheTags) {
    auto path = jpeg_with("given.jpg", {{"Exif.Photo.FocalLength", "35/1"},
                                         {"Exif.Photo.FocalLengthIn35mmFilm", "52"}});
    EXPECT_NEAR(read_exif_focal(path, 23.5).focal_px, 35.0 * 640.0 / 23.5, 1e-9);
}

TEST_F(Exif, MissingOrUnusableExifIsAnInputError) {
    EXPECT_NE(input_error_message([&] { read_exif_focal(plain_jpeg("plain.jpg")); }).find("no EXIF data"),
              std::string::npos);
    EXPECT_NE(input_error_message([&] { read_exif_focal((dir_ / "missing.jpg").string()); })
                  .find("file not found"),
              std::string::npos);
    std::ofstream((dir_ / "garbage.jpg").string()) << "not an image at all";
    EXPECT_NE(input_error_message([&] { read_exif_focal((dir_ / "garbage.jpg").string()); })
                  .find("cannot read the file's metadata"),
              std::string::npos);
    auto no_focal = jpeg_with("nofocal.jpg", {{"Exif.Image.Make", "Acme"}});
    EXPECT_NE(input_error_message([&] { read_exif_focal(no_focal); }).find("no focal length"),
              std::string::npos);
    auto no_sensor = jpeg_with("nosensor.jpg", {{"Exif.Photo.FocalLength", "50/1"}});
    EXPECT_NE(input_error_message([&] { read_exif_focal(no_sensor); }).find("give the sensor width"),
              std::string::npos);
}

namespace {

/// A phone's tags: 4.25 mm, 26 mm in 35 mm terms.
const std::vector<std::pair<std::string, std::string>> kPhone = {
    {"Exif.Photo.FocalLength", "425/100"}, {"Exif.Photo.FocalLengthIn35mmFilm", "26"}};

std::vector<std::pair<std::string, std::string>> turned(
    std::vector<std::pair<std::string, std::string>> tags, int orientation) {
    tags.push_back({"Exif.Image.Orientation", std::to_string(orientation)});
    return tags;
}

}  // namespace

TEST_F(Exif, APortraitPhotoTurnedBySixOrEightIsUprightWithTheLandscapesFocalLength) {
    // A phone stores its portrait photos landscape, tagged to be turned a quarter.
    const ExifFocal landscape = read_exif_focal(jpeg_with("landscape.jpg", kPhone));
    for (int o : {6, 8}) {
        const std::string path = jpeg_with("portrait" + std::to_string(o) + ".jpg", turned(kPhone, o));
        const ExifFocal f = read_exif_focal(path);
        EXPECT_EQ(f.orientation, o);
        EXPECT_EQ(f.width, 480);
        EXPECT_EQ(f.height, 640);
        EXPECT_DOUBLE_EQ(f.focal_px, landscape.focal_px);
        EXPECT_NE(f.method.find("EXIF orientation " + std::to_string(o)), std::string::npos);
        // The loader turns the picture the same way.
        const Image image = load_image(path);
        EXPECT_EQ(image.width(), f.width);
        EXPECT_EQ(image.height(), f.height);
    }
}

TEST_F(Exif, TheFocalPlaneResolutionIsAlongTheStoredRowsWhateverTheOrientation) {
    // As FocalPlaneResolutionGivesTheSensorWidth, turned: the sensor is still 16 mm wide
    // across the stored 640 px.
    auto path = jpeg_with("dslr8.jpg", turned({{"Exif.Photo.FocalLength", "50/1"},
                                               {"Exif.Photo.FocalPlaneXResolution", "1016/1"},
                                               {"Exif.Photo.FocalPlaneResolutionUnit", "2"}},
                                              8));
    const ExifFocal f = read_exif_focal(path);
    EXPECT_NEAR(f.sensor_width_mm, 16.0, 1e-9);
    EXPECT_NEAR(f.focal_px, 50.0 * 640.0 / 16.0, 1e-9);
    EXPECT_EQ(f.width, 480);
    // So is a sensor width given by hand.
    EXPECT_NEAR(read_exif_focal(path, 23.5).focal_px, 50.0 * 640.0 / 23.5, 1e-9);
}

TEST_F(Exif, OrientationsOneToFourKeepTheSize) {
    for (int o : {1, 2, 3, 4}) {
        const ExifFocal f = read_exif_focal(jpeg_with("o" + std::to_string(o) + ".jpg", turned(kPhone, o)));
        EXPECT_EQ(f.width, 640) << o;
        EXPECT_EQ(f.height, 480) << o;
    }
}

TEST_F(Exif, ATiffIsTurnedUprightAsItLoads) {
    const std::string path = jpeg_with("portrait.tif", turned(kPhone, 6));
    const ExifFocal f = read_exif_focal(path);
    EXPECT_EQ(f.width, 480);
    EXPECT_EQ(load_image(path).width(), 480);
}

TEST_F(Exif, APngLoadsAsStoredSoItsOrientationIsNotApplied) {
    const std::string path = jpeg_with("portrait.png", turned(kPhone, 6));
    const ExifFocal f = read_exif_focal(path);
    EXPECT_EQ(f.orientation, 1);
    EXPECT_EQ(f.width, 640);
    EXPECT_EQ(load_image(path).width(), 640);
}
