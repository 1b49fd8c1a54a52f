// `diffphoton calibrate`: the parent command, and its camera subcommands from a chessboard,
// EXIF data and fSpy projects (the ones from clicked points are in cmd_calibrate_points.cpp).
#include <cstdio>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <memory>

#include "base/atomic_file.h"
#include "base/error.h"
#include "calibrate_common.h"
#include "calibration/chessboard.h"
#include "calibration/exif.h"
#include "calibration/fspy.h"
#include "commands.h"
#include "image/image_io.h"
#include "common.h"
#include "scene/project_io.h"

namespace dp::cli {

namespace {

namespace fs = std::filesystem;

struct ChessboardOptions {
    std::string project;
    std::vector<std::string> photos;
    std::string board = "9x6";
    double square = 0;
    FocalOptions focal;
    std::string poses;
    bool force = false;
};

/// The photo among `photos` that an existing project shows (its pose is the one to keep),
/// else the first.
size_t project_photo(const std::string& project, const std::vector<std::string>& photos) {
    std::error_code ec;
    if (!fs::exists(project, ec)) return 0;
    const Project p = load_project(project);
    const fs::path own = p.resolve(p.photo.path);
    for (size_t i = 0; i < photos.size(); ++i)
        if (fs::equivalent(own, photos[i], ec)) return i;
    return 0;
}

ChessboardSpec parse_board(const std::string& text, double square) {
    ChessboardSpec spec;
    const size_t x = text.find('x');
    try {
        size_t a = 0, b = 0;
        if (x == std::string::npos) throw std::invalid_argument("no x");
        spec.cols = std::stoi(text.substr(0, x), &a);
        spec.rows = std::stoi(text.substr(x + 1), &b);
        if (a != x || b != text.size() - x - 1) throw std::invalid_argument("junk");
    } catch (const std::exception&) {
        throw InputError("", "--board",
                         "expected COLSxROWS inner corners (e.g. 9x6), got '" + text + "'");
    }
    spec.square_size = square;
    return spec;
}

int run_chessboard(const ChessboardOptions& o) {
    const ChessboardSpec spec = parse_board(o.board, o.square);
    ReadSet read;
    for (const std::string& photo : o.photos) read.add(photo, "a photo being calibrated");
    std::vector<Output> extra;
    if (!o.poses.empty()) extra.push_back({o.poses, "--poses"});
    check_camera_outputs(o.project, extra, read, o.force);
    std::vector<ChessboardView> views;
    for (const std::string& photo : o.photos) views.push_back(detect_chessboard(photo, spec));
    CalibrationResult r;
    std::string method, photo = o.photos[0], poses;
    if (views.size() > 1) {
        if (o.focal.given())
            throw InputError("", "--focal",
                             "several photos calibrate the focal length themselves; give a "
                             "focal length only with a single photo");
        ChessboardCalibration c = calibrate_chessboard(views, spec);
        for (size_t i = 0; i < views.size(); ++i) {
            const glm::dvec3 pos = c.poses[i].position();
            std::printf(
                "photo %s: rms_px %.4f position %.4f %.4f %.4f ± %.2g m "
                "rotation ± %.2g°%s\n",
                views[i].source.c_str(), c.view_rms_px[i], pos.x, pos.y, pos.z,
                c.view_uncertainty[i].position_m, c.view_uncertainty[i].rotation_deg,
                c.duplicate_of[i] >= 0 ? " (duplicate, not in the lens fit)" : "");
        }
        if (!o.poses.empty()) poses = chessboard_poses_json(c, views, spec);
        const size_t keep = project_photo(o.project, o.photos);
        r = c.for_view(keep);
        method = "chessboard, " + std::to_string(views.size()) + " photos (pose of " +
                 fs::path(o.photos[keep]).filename().string() + ")";
        photo = o.photos[keep];
    } else {
        if (!o.poses.empty())
            throw InputError("", "--poses",
                             "writes the poses of several photos; with one photo the project "
                             "gets its pose");
        const ChessboardView& v = views[0];
        if (auto f = o.focal.resolve(o.photos[0], v.width, v.height)) {
            r = chessboard_pose(v, spec, Intrinsics::centred(v.width, v.height, *f));
            method = "chessboard, one photo, given focal length";
        } else {
            r = chessboard_single(v, spec);
            method = "chessboard, one photo, focal length from the board";
        }
    }
    print_result(r, method);
    write_camera(o.project, r, photo);
    if (!poses.empty()) {  // after the project: a refused camera writes nothing
        try {
            write_file_atomically(o.poses, poses + "\n");
        } catch (const std::runtime_error& e) {
            throw InputError(o.poses, "--poses", e.what());
        }
        std::printf("wrote every photo's pose to %s\n", o.poses.c_str());
    }
    return 0;
}

struct ExifOptions {
    std::string project, photo;
    std::optional<double> sensor_width;
    bool force = false;
};

/// Sets the focal length from EXIF and centres the principal point; the pose is kept (a
/// look-at camera is converted to the same pose).
int run_exif(const ExifOptions& o) {
    ReadSet read;
    read.add(o.photo, "the photo being calibrated");
    check_camera_outputs(o.project, {}, read, o.force);
    ExifFocal e = read_exif_focal(o.photo, o.sensor_width);
    CalibrationResult r;
    r.intrinsics = Intrinsics::centred(e.width, e.height, e.focal_px);
    r.rms_px = std::numeric_limits<double>::quiet_NaN();
    if (fs::exists(o.project)) {
        const Camera cam = load_project(o.project).camera.build(e.width, e.height);
        r.pose.R = glm::dmat3(cam.rotation());
        r.pose.t = glm::dvec3(cam.translation());
        r.intrinsics.distortion = cam.distortion();
    }
    std::printf("exif: %s%s%s\n", e.camera.c_str(), e.camera.empty() ? "" : ", ", e.method.c_str());
    print_result(r, "EXIF focal length (pose kept from the project)");
    write_camera(o.project, r, o.photo);
    return 0;
}

struct FspyOptions {
    std::string project, file, extract;
    bool force = false;
};

int run_fspy(const FspyOptions& o) {
    FspyImport f = read_fspy(o.file);
    if (!o.extract.empty() && f.from_json_export)
        throw InputError(o.file, "--extract-photo",
                         "fSpy's exported camera parameters hold no photo (the .fspy project does)");
    ReadSet read;
    read.add(o.file, "the fSpy file being read");
    std::vector<Output> extra;
    if (!o.extract.empty()) extra.push_back({o.extract, "--extract-photo", double(f.image.size())});
    check_camera_outputs(o.project, extra, read, o.force);
    // The embedded photo is written byte for byte: its name must say its format.
    if (!o.extract.empty()) check_extension_for_content(o.extract, "--extract-photo", f.image.data(), f.image.size());
    if (f.from_json_export)
        std::printf("fspy: exported camera parameters (no distance unit)\n");
    else
        std::printf("fspy: distance unit %s\n", f.unit.c_str());
    const char* what = f.from_json_export ? "fSpy camera parameters " : "fSpy project ";
    print_result(f.result, what + o.file);
    // The project first, as with --poses: a camera the project refuses writes nothing.
    write_camera(o.project, f.result, o.extract);
    if (!o.extract.empty()) {
        try {
            write_file_atomically(o.extract, std::string(f.image.begin(), f.image.end()));
        } catch (const std::runtime_error& e) {
            throw InputError(o.extract, "--extract-photo", e.what());
        }
        std::printf("wrote the embedded photo (%s) to %s\n",
                    f.image_extension.empty() ? "unknown format" : f.image_extension.c_str(), o.extract.c_str());
    }
    return 0;
}

}  // namespace

std::vector<Command> add_calibrate_camera_commands(CLI::App& calibrate) {
    std::vector<Command> out;
    {
        auto o = std::make_shared<ChessboardOptions>();
        CLI::App* sub = calibrate.add_subcommand(
            "chessboard", "Camera from photos of a chessboard lying on the ground");
        sub->add_option("project", o->project, "Project file to write or update")->required();
        sub->add_option("photos", o->photos,
                        "Photos of the board; the pose is the project photo's (else the "
                        "first's). One photo: give the focal length or let the board estimate it")
            ->required();
        sub->add_option("--board", o->board, "Inner corners COLSxROWS (default 9x6)");
        sub->add_option("--square", o->square, "Square size in metres")->required()->check(kFinite);
        o->focal.add_to(sub);
        sub->add_option("--poses", o->poses,
                        "Write every photo's pose (and its corners) to this JSON file");
        add_force_flag(sub, o->force);
        out.push_back({sub, [o] { return run_chessboard(*o); }});
    }
    {
        auto o = std::make_shared<ExifOptions>();
        CLI::App* sub = calibrate.add_subcommand(
            "exif", "Focal length from the photo's EXIF data (keeps the camera's pose)");
        sub->add_option("project", o->project, "Project file to write or update")->required();
        sub->add_option("photo", o->photo, "Photo with EXIF data (JPEG, TIFF, raw...)")->required();
        sub->add_option("--sensor-width", o->sensor_width,
                        "Sensor width in millimetres, across its rows (the stored image's)")
            ->check(kFinite);
        add_force_flag(sub, o->force);
        out.push_back({sub, [o] { return run_exif(*o); }});
    }
    {
        auto o = std::make_shared<FspyOptions>();
        CLI::App* sub = calibrate.add_subcommand(
            "fspy", "Camera from an fSpy project file or fSpy's exported camera parameters");
        sub->add_option("project", o->project, "Project file to write or update")->required();
        sub->add_option("file", o->file,
                        "fSpy project (.fspy) or its camera parameters exported as JSON "
                        "(told apart by content)")
            ->required();
        sub->add_option("--extract-photo", o->extract,
                        "Write the embedded photo to this file (and use it for a new project)");
        add_force_flag(sub, o->force);
        out.push_back({sub, [o] { return run_fspy(*o); }});
    }
    for (Command& c : add_calibrate_point_commands(calibrate)) out.push_back(std::move(c));
    out.push_back(add_calibrate_auto_command(calibrate));
    return out;
}

Command add_calibrate_command(CLI::App& app) {
    CLI::App* sub = app.add_subcommand(
        "calibrate", "Match the camera (and the scene) to the photograph; see docs/calibration.md");
    sub->require_subcommand(1);
    // Each group adds its subcommands to `calibrate`; a new group is one more entry here.
    using Group = std::vector<Command> (*)(CLI::App&);
    auto commands = std::make_shared<std::vector<Command>>();
    for (Group add_group : {&add_calibrate_camera_commands})
        for (Command& c : add_group(*sub)) commands->push_back(std::move(c));
    auto json = std::make_shared<bool>(false);
    for (Command& c : *commands)
        c.app->add_flag("--json", *json,
                        "Print the result as one JSON object on stdout (the other lines go to stderr)");
    // proxy, albedo and probe edit the scene and print no JSON result.
    auto scene_commands = std::make_shared<std::vector<Command>>(std::vector<Command>{
        add_calibrate_proxy_command(*sub), add_calibrate_albedo_command(*sub), add_calibrate_probe_command(*sub),
        add_calibrate_holdout_command(*sub)});
    return {sub, [commands, scene_commands, json] {
                for (const Command& c : *scene_commands)
                    if (c.app->parsed()) return c.run();
                for (const Command& c : *commands) {
                    if (!c.app->parsed()) continue;
                    if (!*json) return c.run();
                    // The human-readable lines go to stderr, so that stdout is only the JSON.
                    std::fflush(stdout);
                    const int out = dup(STDOUT_FILENO);
                    dup2(STDERR_FILENO, STDOUT_FILENO);
                    int rc;
                    try {
                        rc = c.run();
                    } catch (...) {
                        std::fflush(stdout);
                        dup2(out, STDOUT_FILENO);
                        close(out);
                        throw;
                    }
                    std::fflush(stdout);
                    dup2(out, STDOUT_FILENO);
                    close(out);
                    std::printf("%s\n", last_result_json().dump(1).c_str());
                    return rc;
                }
                return 2;  // unreachable: require_subcommand(1)
            }};
}

}  // namespace dp::cli
