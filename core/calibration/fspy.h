#pragma once
// Import of fSpy project files (.fspy): a 16-byte header (magic "fspy", version 1, state size,
// image size, little-endian uint32), the state as JSON, then the photograph's bytes.
#include <cstdint>
#include <string>
#include <vector>

#include "calibration/calibration.h"

namespace dp {

struct FspyImport {
    /// The camera in the project's conventions (Y up, metres, OpenCV axes). fSpy stores no
    /// residual, so `rms_px` is NaN.
    CalibrationResult result;
    std::vector<uint8_t> image;  ///< the embedded photograph, as stored
    std::string image_extension;  ///< ".jpg", ".png" or "" (unknown format)
    std::string unit;             ///< fSpy's reference distance unit
};

/// Reads an fSpy project. fSpy's world is Blender's (Z up) and its camera looks along -Z
/// with +Y up; the result is turned into the project's world (Y up: x, y, z -> x, z, -y) and
/// OpenCV camera axes, with lengths converted to metres from the reference distance unit.
/// Throws InputError naming the file for unreadable, truncated or malformed files.
FspyImport read_fspy(const std::string& path);

}  // namespace dp
