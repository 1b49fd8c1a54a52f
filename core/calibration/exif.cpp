#include "calibration/exif.h"

#include <cmath>
#include <filesystem>
#include <utility>

#include <exiv2/exiv2.hpp>

#include "base/error.h"
#include "base/input_file.h"

namespace dp {
namespace {

/// Millimetres per FocalPlaneResolutionUnit (2: inch, 3: centimetre, 4: millimetre,
/// 5: micrometre); 0 for unknown units.
double unit_mm(long unit) {
    switch (unit) {
        case 2: return 25.4;
        case 3: return 10.0;
        case 4: return 1.0;
        case 5: return 0.001;
        default: return 0.0;
    }
}

double number(const Exiv2::ExifData& exif, const char* key) {
    auto it = exif.findKey(Exiv2::ExifKey(key));
    if (it == exif.end() || it->count() == 0) return 0;
    const double v = double(it->toFloat());
    return std::isfinite(v) ? v : 0;
}

/// The orientation the loader applies: Exif.Image.Orientation, 1 to 8 (1 where absent or out
/// of range). It leaves a PNG as stored whatever its tag says, so the tag does not count there.
int applied_orientation(const Exiv2::Image& image) {
    if (image.mimeType() == "image/png") return 1;
    const double v = number(image.exifData(), "Exif.Image.Orientation");
    return v >= 1 && v <= 8 && v == std::floor(v) ? int(v) : 1;
}

}  // namespace

ExifFocal read_exif_focal(const std::string& path, std::optional<double> sensor_width_mm) {
    if (!std::filesystem::is_regular_file(path))
        throw InputError(path, "", "file not found (or not a regular file)");
    Exiv2::Image::AutoPtr image;
    try {
        image = Exiv2::ImageFactory::open(path);
        if (!image.get()) throw InputError(path, "", "cannot read the file's metadata");
        image->readMetadata();
    } catch (const Exiv2::AnyError& e) {
        throw InputError(path, "", std::string("cannot read the file's metadata: ") + e.what());
    }
    const Exiv2::ExifData& exif = image->exifData();
    if (exif.empty())
        throw InputError(path, "",
                         "the file has no EXIF data, so its focal length is unknown; give the "
                         "focal length instead");
    ExifFocal r;
    r.width = image->pixelWidth();
    r.height = image->pixelHeight();
    if (r.width <= 0 || r.height <= 0) {
        r.width = int(number(exif, "Exif.Photo.PixelXDimension"));
        r.height = int(number(exif, "Exif.Photo.PixelYDimension"));
    }
    if (r.width <= 0 || r.height <= 0)
        throw InputError(path, "", "the image size cannot be read");
    for (const char* key : {"Exif.Image.Make", "Exif.Image.Model"}) {
        auto it = exif.findKey(Exiv2::ExifKey(key));
        if (it != exif.end()) r.camera += (r.camera.empty() ? "" : " ") + it->toString();
    }
    r.focal_mm = number(exif, "Exif.Photo.FocalLength");
    r.focal_35mm = number(exif, "Exif.Photo.FocalLengthIn35mmFilm");
    if (!(r.focal_mm > 0) && !(r.focal_35mm > 0))
        throw InputError(path, "Exif.Photo.FocalLength",
                         "the EXIF data has no focal length; give the focal length instead");
    if (sensor_width_mm) {
        if (!(*sensor_width_mm > 0))
            throw InputError(path, "sensor-width", "the sensor width must be > 0 mm");
        r.sensor_width_mm = *sensor_width_mm;
    } else {
        // The focal-plane resolution counts sensor pixels per unit at the full sensor width
        // (PixelXDimension), which may differ from the stored image's width.
        const double xres = number(exif, "Exif.Photo.FocalPlaneXResolution");
        const double unit = unit_mm(long(number(exif, "Exif.Photo.FocalPlaneResolutionUnit")));
        double full = number(exif, "Exif.Photo.PixelXDimension");
        if (!(full > 0)) full = r.width;
        if (xres > 0 && unit > 0) r.sensor_width_mm = full / xres * unit;
    }
    if (r.focal_mm > 0 && r.sensor_width_mm > 0) {
        r.focal_px = r.focal_mm * r.width / r.sensor_width_mm;
        r.method = "focal length " + std::to_string(r.focal_mm) + " mm on a " +
                   std::to_string(r.sensor_width_mm) + " mm wide sensor";
    } else if (r.focal_35mm > 0) {
        // 35 mm equivalence is defined on the diagonal of the 36 x 24 mm frame.
        r.focal_px = r.focal_35mm * std::hypot(double(r.width), double(r.height)) /
                     std::hypot(36.0, 24.0);
        r.method = "35 mm equivalent focal length " + std::to_string(r.focal_35mm) + " mm";
    } else {
        throw InputError(path, "Exif.Photo.FocalLength",
                         "the EXIF data gives a focal length (" + std::to_string(r.focal_mm) +
                             " mm) but no sensor size or 35 mm equivalent; give the sensor "
                             "width");
    }
    // The sensor's axes were the stored image's; the photo loads upright.
    r.orientation = applied_orientation(*image);
    if (r.orientation >= 5) {
        std::swap(r.width, r.height);
        r.method += ", turned upright (EXIF orientation " + std::to_string(r.orientation) + ")";
    }
    return r;
}

int exif_orientation(const std::string& path) {
    try {
        check_input_file(path, "", "a photo");  // opening a FIFO would block
    } catch (const InputError&) {
        return 1;  // the photo's own loading says what is wrong with it
    }
    try {
        Exiv2::Image::AutoPtr image = Exiv2::ImageFactory::open(path);
        if (!image.get()) return 1;
        image->readMetadata();
        return applied_orientation(*image);
    } catch (const Exiv2::AnyError&) {
        return 1;  // no metadata to read: the loader turns nothing either
    }
}

}  // namespace dp
