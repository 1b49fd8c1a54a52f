// `diffphoton calibrate auto`: the camera from the photo's own lines (docs/calibration.md,
// "From the photo's lines"). The proposed lines can be written as a `calibrate vanishing`
// file, edited (lines dropped or added) and solved again, and drawn over the photo.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include "base/atomic_file.h"
#include "base/error.h"
#include "calibrate_common.h"
#include "calibration/auto_lines.h"
#include "commands.h"
#include "common.h"
#include "image/image_io.h"

namespace dp::cli {

namespace {

using json = nlohmann::json;

struct AutoOptions {
    std::string project, photo, lines_out, picture;
    FocalOptions focal;
    double camera_height = 1.5;
    bool dry_run = false, force = false;
};

/// The proposal as a `calibrate vanishing --file` document: what the user edits.
json lines_document(const LineProposal& p, const std::optional<CalibrationResult>& camera, ImagePoint origin,
                    double camera_height) {
    json doc = json::object();
    static const char* const kKeys[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
        json list = json::array();
        for (const LineSegment& s : p.axis[a]) list.push_back({s.a.x, s.a.y, s.b.x, s.b.y});
        doc[kKeys[a]] = list;
    }
    doc["origin"] = {origin.x, origin.y};
    doc["camera_height"] = camera_height;
    json other = json::array();
    for (const LineSegment& s : p.other) other.push_back({s.a.x, s.a.y, s.b.x, s.b.y});
    doc["unused"] = other;  // detected in no chosen direction: move any into x, y or z
    if (camera) doc["focal_px_found"] = camera->intrinsics.fx;  // for reading: the solve estimates it again
    return doc;
}

/// A line `width` pixels wide from a to b in `img`.
void draw_line(Image& img, ImagePoint a, ImagePoint b, vec3 colour, int width) {
    const int steps = int(std::ceil(std::max(std::abs(b.x - a.x), std::abs(b.y - a.y)))) + 1;
    for (int i = 0; i <= steps; ++i) {
        const ImagePoint p = a + (b - a) * (double(i) / steps);
        for (int dy = -width / 2; dy <= width / 2; ++dy)
            for (int dx = -width / 2; dx <= width / 2; ++dx) {
                const int x = int(std::lround(p.x)) + dx, y = int(std::lround(p.y)) + dy;
                if (x >= 0 && y >= 0 && x < img.width() && y < img.height()) img.at(x, y) = colour;
            }
    }
}

/// The photo, dimmed, with the proposed lines over it: X red, Y green, Z blue, the rest grey.
Image lines_picture(const Image& photo, const LineProposal& p) {
    Image out = photo;
    for (size_t i = 0; i < out.size(); ++i) out[i] *= 0.5f;
    const int width = std::max(1, std::max(photo.width(), photo.height()) / 500);
    for (const LineSegment& s : p.other) draw_line(out, s.a, s.b, vec3(0.4f), std::max(1, width / 2));
    const vec3 colours[3] = {vec3(1, 0.05f, 0.05f), vec3(0.05f, 1, 0.05f), vec3(0.1f, 0.3f, 1)};
    for (int a = 0; a < 3; ++a)
        for (const LineSegment& s : p.axis[a]) draw_line(out, s.a, s.b, colours[a], width);
    return out;
}

int run_auto(const AutoOptions& o) {
    if (!(o.camera_height > 0)) throw InputError("", "--camera-height", "the camera height must be > 0 metres");
    ReadSet read;
    read.add(o.photo, "the photo being calibrated (--photo)");
    std::vector<Output> extra;
    if (!o.lines_out.empty()) extra.push_back({o.lines_out, "--lines-out"});
    if (!o.picture.empty()) extra.push_back({o.picture, "--picture"});
    check_camera_outputs(o.project, extra, read, o.force);
    const Image photo = load_image(o.photo, "--photo");
    AutoLinesOptions options;
    options.focal_px = o.focal.resolve(o.photo, photo.width(), photo.height());
    options.camera_height = o.camera_height;
    const AutoLinesResult r = calibrate_from_lines(photo, options, o.photo);
    for (const std::string& note : r.proposal.notes) std::fprintf(stderr, "%s\n", note.c_str());
    if (!o.lines_out.empty()) {
        try {
            write_file_atomically(o.lines_out, lines_document(r.proposal, r.camera, r.origin, o.camera_height).dump(1) + "\n");
        } catch (const std::runtime_error& e) {
            throw InputError(o.lines_out, "--lines-out", e.what());
        }
        std::fprintf(stderr, "wrote %s: edit it and solve with `diffphoton calibrate vanishing %s --photo %s --file %s`\n",
                     o.lines_out.c_str(), o.project.c_str(), o.photo.c_str(), o.lines_out.c_str());
    }
    if (!o.picture.empty()) {
        save_display_image(o.picture, lines_picture(photo, r.proposal), DisplayTransform());
        std::fprintf(stderr, "wrote %s (X red, Y green, Z blue, unused grey)\n", o.picture.c_str());
    }
    if (!r.camera) throw InputError(o.photo, "--photo", r.failure);
    print_result(*r.camera, "the photo's lines");
    if (!o.dry_run) write_camera(o.project, *r.camera, o.photo);
    return 0;
}

}  // namespace

Command add_calibrate_auto_command(CLI::App& calibrate) {
    auto o = std::make_shared<AutoOptions>();
    CLI::App* sub = calibrate.add_subcommand(
        "auto", "Camera from the photo's own lines: detected, grouped by vanishing point, solved");
    sub->add_option("project", o->project, "Project file to write or update")->required();
    sub->add_option("--photo", o->photo, "The photo")->required();
    o->focal.add_to(sub);
    sub->add_option("--camera-height", o->camera_height,
                    "Scale: the camera's height above the ground in metres (default 1.5)")
        ->check(kFinite);
    sub->add_option("--lines-out", o->lines_out,
                    "Write the proposed lines as a `calibrate vanishing --file` JSON file to edit");
    sub->add_option("--picture", o->picture, "Draw the proposed lines over the photo into this image");
    sub->add_flag("--dry-run", o->dry_run, "Print the camera but leave the project as it is");
    add_force_flag(sub, o->force);
    return {sub, [o] { return run_auto(*o); }};
}

}  // namespace dp::cli
