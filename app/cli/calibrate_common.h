#pragma once
// Shared pieces of the `diffphoton calibrate` subcommands: reading points from the command
// line or a JSON file, focal-length options, and writing the camera into a project.
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "calibration/calibration.h"
#include "calibration/vanishing.h"
#include "commands.h"
#include "outputs.h"

namespace dp::cli {

/// "x,y" (or `n` comma-separated numbers) as given to `option`; throws InputError naming the
/// option and the text.
std::vector<double> parse_numbers(const std::string& text, size_t n, const std::string& option);
ImagePoint parse_point(const std::string& text, const std::string& option);
LineSegment parse_segment(const std::string& text, const std::string& option);

/// Reads a JSON document; throws InputError naming the file for unreadable or invalid JSON.
nlohmann::json read_json(const std::string& path);
/// `n` finite numbers at `doc[key]...`; `field` names the place in error messages.
std::vector<double> json_numbers(const nlohmann::json& j, size_t n, const std::string& file,
                                 const std::string& field);

/// Where the focal length comes from: pixels, millimetres with a sensor width, or EXIF.
struct FocalOptions {
    std::optional<double> focal_px, focal_mm, sensor_width_mm;
    bool exif = false;
    /// Adds --focal, --focal-mm, --sensor-width and --exif to `sub`.
    void add_to(CLI::App* sub);
    bool given() const { return focal_px || focal_mm || exif; }
    /// The focal length in pixels for a `width` x `height` photo (as it loads: upright), or
    /// nullopt if none was given. The sensor width is across the sensor's rows: the photo's
    /// width, or its height where the photo's EXIF orientation turns it a quarter (a phone's
    /// portrait photo). Throws InputError for a focal length <= 0, --focal-mm without
    /// --sensor-width, or --exif with a photo whose EXIF data cannot give it.
    std::optional<double> resolve(const std::string& photo, int width, int height) const;
};

/// The photograph's size: from --size WxH or by loading `photo`. Throws InputError.
struct ImageSize {
    int width = 0, height = 0;
};
ImageSize image_size(const std::string& photo, const std::string& size_text);

/// Puts the calibrated camera into the project at `project_path` and saves it. An existing
/// project keeps everything else; if its photo exists at another resolution of the same aspect
/// ratio, the intrinsics are scaled to it (a different aspect ratio is an InputError). A
/// missing project is created with `photo` as its photograph (a placeholder to fill in if
/// `photo` is empty: the camera was matched on a --size) and a probe path to fill in. A camera
/// the project would not load again with is refused (save_calibrated), the old file kept.
void write_camera(const std::string& project_path, const CalibrationResult& result,
                  const std::string& photo);

/// check_outputs for a camera calibration, before its work: the project (created, or updated in
/// place) and the command's `extra` outputs (--poses, --extract-photo), none of which may be
/// one of `read` (the command's own inputs: photos, points files) or, where the project exists,
/// a file it reads; the project file itself only the project output may replace.
void check_camera_outputs(const std::string& project_path, std::vector<Output> extra, ReadSet read, bool force);

/// Prints the camera, the error figure ("rms_px <value>", or "rms_px n/a" for NaN) and the
/// uncertainty ("uncertainty: fx 495 ± 12 px ..."), and the result's warnings on stderr.
void print_result(const CalibrationResult& r, const std::string& method);

/// The last result print_result saw, as JSON (`calibrate ... --json` prints it on stdout, every
/// other line going to stderr); null before any.
nlohmann::json& last_result_json();

/// `calibrate rectangle`, `points` and `vanishing` (cmd_calibrate_points.cpp).
std::vector<Command> add_calibrate_point_commands(CLI::App& calibrate);
/// `calibrate auto` (cmd_calibrate_auto.cpp).
Command add_calibrate_auto_command(CLI::App& calibrate);

}  // namespace dp::cli
