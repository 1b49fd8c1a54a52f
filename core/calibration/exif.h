#pragma once
// Focal length in pixels from a photograph's EXIF data (read with exiv2).
#include <optional>
#include <string>

namespace dp {

/// What the EXIF data says about the lens.
struct ExifFocal {
    double focal_mm = 0;             ///< Exif.Photo.FocalLength
    double focal_35mm = 0;           ///< Exif.Photo.FocalLengthIn35mmFilm (0 if absent)
    double sensor_width_mm = 0;      ///< from FocalPlaneXResolution, or given (0 if unknown)
    int width = 0, height = 0;       ///< the image's size in pixels
    double focal_px = 0;             ///< the result: fx = fy in pixels
    std::string method;              ///< how focal_px was derived, for messages
    std::string camera;              ///< Exif.Image.Make + Model, if present
};

/// Reads the focal length from `path`'s EXIF data and converts it to pixels of the image as it
/// is stored: from the sensor width (`sensor_width_mm` if given, else the focal-plane
/// resolution tags), or else from the 35 mm equivalent focal length (defined on the frame
/// diagonal, 43.27 mm). Throws InputError naming the file for an unreadable file, missing EXIF
/// data, no focal length, or no way to convert it to pixels.
ExifFocal read_exif_focal(const std::string& path, std::optional<double> sensor_width_mm = {});

}  // namespace dp
