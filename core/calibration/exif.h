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
    /// The image's size in pixels as it loads: upright by its EXIF orientation (a phone's
    /// portrait photo, stored landscape with orientation 6 or 8, is taller than wide).
    int width = 0, height = 0;
    /// Exif.Image.Orientation as applied (1 to 8; 1: none, or a PNG, which loads as stored).
    int orientation = 1;
    double focal_px = 0;             ///< the result: fx = fy in pixels
    std::string method;              ///< how focal_px was derived, for messages
    std::string camera;              ///< Exif.Image.Make + Model, if present
};

/// Reads the focal length from `path`'s EXIF data and converts it to pixels: from the sensor
/// width (`sensor_width_mm` if given, else the focal-plane resolution tags), or else from the
/// 35 mm equivalent focal length (defined on the frame diagonal, 43.27 mm). The sensor's width
/// is along the rows of the image as stored (the sensor's own axes, the longer side for most
/// cameras), whatever the orientation; the size returned is the upright one, as load_image
/// turns JPEG and TIFF (and raw files as their converters will), so orientations 5 to 8 swap
/// width and height and leave the focal length in pixels as it is. Throws InputError naming
/// the file for an unreadable file, missing EXIF data, no focal length, or no way to convert
/// it to pixels.
ExifFocal read_exif_focal(const std::string& path, std::optional<double> sensor_width_mm = {});

/// The EXIF orientation (1 to 8) that read_exif_focal and load_image apply to `path`; 1 for a
/// file without EXIF data or one that cannot be read, and for a PNG (loaded as stored).
/// Orientations 5 to 8 turn the picture a quarter: the sensor's rows run down the photo.
int exif_orientation(const std::string& path);

}  // namespace dp
