// `diffphoton calibrate rectangle | points | vanishing`: the camera from points and lines
// picked in the photo, given on the command line or in a JSON file.
#include <cstdio>
#include <memory>

#include "base/error.h"
#include "calibrate_common.h"
#include "calibration/correspondences.h"
#include "calibration/vanishing.h"
#include "commands.h"
#include "common.h"

namespace dp::cli {

namespace {

using json = nlohmann::json;

/// Options every point-based method shares.
struct PhotoOptions {
    std::string project, photo, size, file;
    FocalOptions focal;
    double click_sigma = 0.5;
    bool force = false;

    void add_to(CLI::App* sub, const char* file_help) {
        sub->add_option("project", project, "Project file to write or update")->required();
        sub->add_option("--photo", photo, "The photo (for its size, and EXIF with --exif)");
        sub->add_option("--size", size, "Image size WIDTHxHEIGHT instead of --photo");
        sub->add_option("--file", file, file_help);
        sub->add_option("--click-sigma", click_sigma,
                        "How precisely the points were clicked, pixels (default 0.5): the "
                        "uncertainty's floor")
            ->check(kFinite);
        focal.add_to(sub);
        add_force_flag(sub, force);
    }
    /// check_camera_outputs, before the work: the project is none of the files given.
    void check_project_output() const {
        ReadSet read;
        read.add(photo, "the photo being calibrated (--photo)");
        read.add(file, "the points file (--file)");
        check_camera_outputs(project, {}, read, force);
    }
    /// Throws InputError for a click precision < 0.
    double click_sigma_px() const {
        if (!(click_sigma >= 0))
            throw InputError("", "--click-sigma", "the click precision must be >= 0 pixels");
        return click_sigma;
    }
    /// The JSON file's document, or an empty object.
    json document() const { return file.empty() ? json::object() : read_json(file); }
};

const json* member(const json& doc, const char* key) {
    return doc.is_object() && doc.contains(key) ? &doc[key] : nullptr;
}

double json_number(const json& j, const std::string& file, const std::string& field) {
    return json_numbers(json::array({j}), 1, file, field)[0];
}

// ---- rectangle -------------------------------------------------------------------------

struct RectangleOptions : PhotoOptions {
    std::vector<std::string> corners;
    std::optional<double> width, height;
};

int run_rectangle(const RectangleOptions& o) {
    o.check_project_output();
    const json doc = o.document();
    std::vector<ImagePoint> corners;
    double width = o.width.value_or(0), height = o.height.value_or(0);
    if (const json* c = member(doc, "corners")) {
        if (!c->is_array()) throw InputError(o.file, "corners", "expected an array of [x, y]");
        for (size_t i = 0; i < c->size(); ++i) {
            auto v = json_numbers((*c)[i], 2, o.file, "corners[" + std::to_string(i) + "]");
            corners.emplace_back(v[0], v[1]);
        }
    }
    if (const json* w = member(doc, "width"); w && !o.width) width = json_number(*w, o.file, "width");
    if (const json* h = member(doc, "height"); h && !o.height)
        height = json_number(*h, o.file, "height");
    for (const std::string& c : o.corners) corners.push_back(parse_point(c, "--corners"));
    if (!(width > 0) || !(height > 0))
        throw InputError(o.file, "--width", "give the rectangle's --width and --height in metres (> 0)");
    const ImageSize s = image_size(o.photo, o.size);
    std::optional<Intrinsics> k;
    if (auto f = o.focal.resolve(o.photo, s.width, s.height))
        k = Intrinsics::centred(s.width, s.height, *f);
    CalibrationResult r = calibrate_rectangle(corners, width, height, s.width, s.height, k, o.file,
                                              o.click_sigma_px());
    print_result(r, k ? "rectangle, given focal length" : "rectangle, focal length from its perspective");
    write_camera(o.project, r, o.photo);
    return 0;
}

// ---- points ----------------------------------------------------------------------------

struct PointsOptions : PhotoOptions {
    std::vector<std::string> points;
};

int run_points(const PointsOptions& o) {
    o.check_project_output();
    const json doc = o.document();
    std::vector<PointCorrespondence> pts;
    if (const json* list = member(doc, "points")) {
        if (!list->is_array())
            throw InputError(o.file, "points", "expected an array of {\"world\", \"image\"}");
        for (size_t i = 0; i < list->size(); ++i) {
            const std::string f = "points[" + std::to_string(i) + "]";
            const json& p = (*list)[i];
            if (!p.is_object() || !p.contains("world") || !p.contains("image"))
                throw InputError(o.file, f, "expected {\"world\": [x, y, z], \"image\": [u, v]}");
            auto w = json_numbers(p["world"], 3, o.file, f + ".world");
            auto im = json_numbers(p["image"], 2, o.file, f + ".image");
            pts.push_back({glm::dvec3(w[0], w[1], w[2]), ImagePoint(im[0], im[1])});
        }
    }
    for (const std::string& text : o.points) {
        auto v = parse_numbers(text, 5, "--point");
        pts.push_back({glm::dvec3(v[0], v[1], v[2]), ImagePoint(v[3], v[4])});
    }
    const ImageSize s = image_size(o.photo, o.size);
    std::optional<Intrinsics> k;
    if (auto f = o.focal.resolve(o.photo, s.width, s.height))
        k = Intrinsics::centred(s.width, s.height, *f);
    CalibrationResult r = calibrate_points(pts, s.width, s.height, k, o.file, o.click_sigma_px());
    print_result(r, k ? "points, given focal length" : "points, focal length from the points");
    write_camera(o.project, r, o.photo);
    return 0;
}

// ---- vanishing -------------------------------------------------------------------------

struct VanishingOptions : PhotoOptions {
    std::vector<std::string> x, y, z;
    std::string origin, distance, vertical;
    std::optional<double> camera_height;
    bool free_principal_point = false;
};

/// A scale given as U1,V1,U2,V2,METRES (on the command line or as a JSON array).
std::optional<VanishingInput::Distance> scale_length(const json& doc, const std::string& text,
                                                     const char* key, const std::string& option,
                                                     const std::string& file) {
    std::optional<std::vector<double>> v;
    if (const json* j = member(doc, key)) v = json_numbers(*j, 5, file, key);
    if (!text.empty()) v = parse_numbers(text, 5, option);
    if (!v) return std::nullopt;
    return VanishingInput::Distance{ImagePoint((*v)[0], (*v)[1]), ImagePoint((*v)[2], (*v)[3]),
                                    (*v)[4]};
}

int run_vanishing(const VanishingOptions& o) {
    o.check_project_output();
    const json doc = o.document();
    VanishingInput in;
    const std::pair<const char*, std::vector<LineSegment>*> axes[3] = {
        {"x", &in.x}, {"y", &in.y}, {"z", &in.z}};
    for (const auto& [name, list] : axes) {
        if (const json* segs = member(doc, name)) {
            if (!segs->is_array())
                throw InputError(o.file, name, "expected an array of [x1, y1, x2, y2]");
            for (size_t i = 0; i < segs->size(); ++i) {
                auto v = json_numbers((*segs)[i], 4, o.file,
                                      std::string(name) + "[" + std::to_string(i) + "]");
                list->push_back({ImagePoint(v[0], v[1]), ImagePoint(v[2], v[3])});
            }
        }
    }
    for (const std::string& t : o.x) in.x.push_back(parse_segment(t, "--x"));
    for (const std::string& t : o.y) in.y.push_back(parse_segment(t, "--y"));
    for (const std::string& t : o.z) in.z.push_back(parse_segment(t, "--z"));
    bool has_origin = false;
    if (const json* j = member(doc, "origin")) {
        auto v = json_numbers(*j, 2, o.file, "origin");
        in.origin = ImagePoint(v[0], v[1]);
        has_origin = true;
    }
    if (!o.origin.empty()) in.origin = parse_point(o.origin, "--origin"), has_origin = true;
    if (const json* j = member(doc, "camera_height"))
        in.camera_height = json_number(*j, o.file, "camera_height");
    if (o.camera_height) in.camera_height = o.camera_height;
    in.distance = scale_length(doc, o.distance, "distance", "--distance", o.file);
    in.vertical = scale_length(doc, o.vertical, "vertical", "--vertical", o.file);
    if (int(bool(in.camera_height)) + int(bool(in.distance)) + int(bool(in.vertical)) > 1)
        throw InputError(o.file, "--camera-height",
                         "give one scale only: --camera-height, --distance or --vertical");
    if (!has_origin) {
        // The first point of a distance, or the foot of a vertical length, is on the ground.
        if (!in.distance && !in.vertical)
            throw InputError(o.file, "--origin", "give the image point of the world origin");
        in.origin = in.distance ? in.distance->a : in.vertical->a;
    }
    if (const json* j = member(doc, "free_principal_point")) {
        if (!j->is_boolean())
            throw InputError(o.file, "free_principal_point", "expected true or false");
        in.free_principal_point = j->get<bool>();
    }
    if (o.free_principal_point) in.free_principal_point = true;
    in.click_sigma_px = o.click_sigma_px();
    const ImageSize s = image_size(o.photo, o.size);
    in.focal_px = o.focal.resolve(o.photo, s.width, s.height);
    CalibrationResult r = calibrate_vanishing(in, s.width, s.height, o.file);
    print_result(r, "vanishing points");
    write_camera(o.project, r, o.photo);
    return 0;
}

}  // namespace

std::vector<Command> add_calibrate_point_commands(CLI::App& calibrate) {
    std::vector<Command> out;
    {
        auto o = std::make_shared<RectangleOptions>();
        CLI::App* sub = calibrate.add_subcommand(
            "rectangle", "Camera from the four corners of a known rectangle on the ground");
        o->add_to(sub, "JSON file with \"corners\": [[x, y], ...], \"width\", \"height\"");
        sub->add_option("--corners", o->corners,
                        "Four corners X,Y in order around the rectangle; the first edge is "
                        "--width long");
        sub->add_option("--width", o->width, "Length of the edge from corner 1 to 2, metres")
            ->check(kFinite);
        sub->add_option("--height", o->height, "Length of the edge from corner 2 to 3, metres")
            ->check(kFinite);
        out.push_back({sub, [o] { return run_rectangle(*o); }});
    }
    {
        auto o = std::make_shared<PointsOptions>();
        CLI::App* sub = calibrate.add_subcommand(
            "points", "Camera from points with known world coordinates (6+, or 4+ with a focal)");
        o->add_to(sub, "JSON file with \"points\": [{\"world\": [x, y, z], \"image\": [u, v]}]");
        sub->add_option("--point", o->points, "A correspondence X,Y,Z,U,V (world metres, pixels)");
        out.push_back({sub, [o] { return run_points(*o); }});
    }
    {
        auto o = std::make_shared<VanishingOptions>();
        CLI::App* sub = calibrate.add_subcommand(
            "vanishing", "Camera from lines along two or three orthogonal directions");
        o->add_to(sub, "JSON file with \"x\", \"y\", \"z\" (arrays of [x1, y1, x2, y2]), "
                       "\"origin\", \"distance\", \"vertical\" or \"camera_height\", "
                       "\"free_principal_point\"");
        sub->add_option("--x", o->x, "Segment X1,Y1,X2,Y2 along world X (on the ground)");
        sub->add_option("--y", o->y, "Segment X1,Y1,X2,Y2 along world Y (vertical)");
        sub->add_option("--z", o->z, "Segment X1,Y1,X2,Y2 along world Z (on the ground)");
        sub->add_option("--origin", o->origin, "Image point U,V of the world origin (on the ground)");
        sub->add_option("--distance", o->distance,
                        "Scale: two ground points and their distance U1,V1,U2,V2,METRES");
        sub->add_option("--vertical", o->vertical,
                        "Scale: a vertical length U1,V1,U2,V2,METRES, its foot on the ground "
                        "first (a box edge, a door frame, a person)");
        sub->add_option("--camera-height", o->camera_height, "Scale: camera height in metres")
            ->check(kFinite);
        sub->add_flag("--free-principal-point", o->free_principal_point,
                      "Estimate the principal point too (needs three directions that pin it "
                      "down; otherwise it stays at the image centre)");
        out.push_back({sub, [o] { return run_vanishing(*o); }});
    }
    return out;
}

}  // namespace dp::cli
