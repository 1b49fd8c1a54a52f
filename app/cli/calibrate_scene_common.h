#pragma once
// Shared pieces of `diffphoton calibrate proxy|albedo|probe`: each reads a project, updates its
// scene from the photograph and writes it back.
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "camera/camera.h"
#include "outputs.h"
#include "scene/project.h"

namespace dp::cli {

/// Rethrows an error of the reconstruction calls, which name no file, labelled with the project
/// whose camera, photo and probe the given points and figures refer to.
[[noreturn]] void rethrow_for(const InputError& e, const std::string& project);

/// The photo's size and the camera that took it (the photo file is read for its size).
Camera project_camera(const Project& p);

/// Where a photo value clips, in the photo's units after the project's exposure: `given` (file
/// units) when set, 0.99 for an 8-bit photo (sRGB 254 and 255), none for EXR/HDR.
float clip_level(const Project& p, const std::optional<float>& given);

/// check_outputs for `calibrate proxy|albedo|probe`, before the work: the project `p` written
/// back to `input` or to `output` (-o), and `extra` outputs (albedo textures), none of which may
/// be a file the project reads; only the project output may replace the input project file.
void check_scene_outputs(const Project& p, const std::string& input, const std::string& output,
                         std::vector<Output> extra, bool force);

/// Saves a calibration's project `p` to `path` once it passes what loading it again checks: the
/// project loader's checks (save_project runs them) and the scene's checks of its placement
/// (check_placement) for the photo's size, or `width` x `height` where the photo cannot be read
/// (a new project's placeholder). Throws InputError naming `path` and the field, the old file
/// kept as it was.
void save_calibrated(const Project& p, const std::string& path, int width = 0, int height = 0);

/// save_calibrated to `output`, or back to `input` when no output was given, and says where.
void write_back(const Project& p, const std::string& input, const std::string& output);

}  // namespace dp::cli
