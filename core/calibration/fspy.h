#pragma once
// Import of fSpy's cameras: project files (.fspy: a 16-byte header with magic "fspy", version
// 1, state size and image size as little-endian uint32, then the state as JSON, then the
// photograph's bytes) and the camera parameters fSpy exports as plain JSON (File > Export >
// Camera parameters as JSON: the project state's `cameraParameters` object alone).
#include <cstdint>
#include <string>
#include <vector>

#include "calibration/calibration.h"

namespace dp {

struct FspyImport {
    /// The camera in the project's conventions (Y up, metres, OpenCV axes). fSpy stores no
    /// residual, so `rms_px` is NaN.
    CalibrationResult result;
    std::vector<uint8_t> image;   ///< the embedded photograph, as stored (empty for JSON)
    std::string image_extension;  ///< ".jpg", ".png" or "" (unknown format, or no image)
    /// fSpy's reference distance unit as the file names it ("Meters", "No unit", ...); ""
    /// for the exported JSON, which carries none.
    std::string unit;
    bool from_json_export = false;  ///< the file was the exported camera parameters JSON
};

/// Reads an fSpy project or fSpy's exported camera parameters JSON (told apart by content:
/// the project's "fspy" magic, else a JSON object). fSpy's world is Blender's (Z up) and its
/// camera looks along -Z with +Y up; the result is turned into the project's world (Y up:
/// x, y, z -> x, z, -y) and OpenCV camera axes, with lengths converted to metres from the
/// reference distance unit (the JSON export has none: its lengths are taken as metres, with
/// a warning).
///
/// The focal length comes from `relativeFocalLength`, where fSpy's image plane spans [-1, 1]
/// across the image's longer side, or else from `horizontalFieldOfView`, which fSpy 1.0
/// measures across the longer side too (the height of a portrait image). The principal point
/// is in the same plane (longer side [-1, 1], the aspect kept, +y up).
///
/// Throws InputError naming the file and field for unreadable, truncated or malformed files.
FspyImport read_fspy(const std::string& path);

}  // namespace dp
