#include "calibrate_common.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/error.h"
#include "base/input_file.h"
#include "calibrate_scene_common.h"
#include "calibration/exif.h"
#include "common.h"
#include "image/image_io.h"
#include "scene/project_io.h"
#include "scene/relink.h"

namespace dp::cli {

namespace fs = std::filesystem;

std::vector<double> parse_numbers(const std::string& text, size_t n, const std::string& option) {
    std::vector<double> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        size_t used = 0;
        double v = 0;
        try {
            v = std::stod(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        while (used < item.size() && std::isspace(static_cast<unsigned char>(item[used]))) ++used;
        if (item.empty() || used != item.size() || !std::isfinite(v))
            throw InputError("", option, "'" + text + "' is not a list of numbers");
        out.push_back(v);
    }
    if (out.size() != n)
        throw InputError("", option,
                         "expected " + std::to_string(n) + " comma-separated numbers, got '" +
                             text + "'");
    return out;
}

ImagePoint parse_point(const std::string& text, const std::string& option) {
    auto v = parse_numbers(text, 2, option);
    return ImagePoint(v[0], v[1]);
}

LineSegment parse_segment(const std::string& text, const std::string& option) {
    auto v = parse_numbers(text, 4, option);
    return LineSegment{ImagePoint(v[0], v[1]), ImagePoint(v[2], v[3])};
}

nlohmann::json read_json(const std::string& path) {
    // Clicks and segments take kilobytes; a FIFO or a device would block or feed the parser.
    check_input_file(path, "", "a JSON file of points", 16u << 20);
    std::ifstream in(path);
    if (!in) throw InputError(path, "", "cannot open the file");
    try {
        return nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw InputError(path, "", std::string("invalid JSON: ") + e.what());
    }
}

std::vector<double> json_numbers(const nlohmann::json& j, size_t n, const std::string& file,
                                 const std::string& field) {
    if (!j.is_array() || j.size() != n)
        throw InputError(file, field, "expected an array of " + std::to_string(n) + " numbers");
    std::vector<double> out;
    for (const auto& v : j) {
        if (!v.is_number() || !std::isfinite(v.get<double>()))
            throw InputError(file, field, "expected finite numbers");
        out.push_back(v.get<double>());
    }
    return out;
}

void FocalOptions::add_to(CLI::App* sub) {
    sub->add_option("--focal", focal_px, "Focal length in pixels")->check(kFinite);
    sub->add_option("--focal-mm", focal_mm, "Focal length in millimetres (with --sensor-width)")
        ->check(kFinite);
    sub->add_option("--sensor-width", sensor_width_mm,
                    "Sensor width in millimetres, across its rows (with --focal-mm or --exif)")
        ->check(kFinite);
    sub->add_flag("--exif", exif, "Focal length from the photo's EXIF data");
}

std::optional<double> FocalOptions::resolve(const std::string& photo, int width,
                                            int height) const {
    if (int(bool(focal_px)) + int(bool(focal_mm)) + int(exif) > 1)
        throw InputError("", "--focal", "give only one of --focal, --focal-mm and --exif");
    if (focal_px) {
        check_focal(*focal_px, "", "--focal");
        return focal_px;
    }
    if (focal_mm) {
        if (!sensor_width_mm)
            throw InputError("", "--focal-mm", "needs --sensor-width (millimetres)");
        if (!(*sensor_width_mm > 0))
            throw InputError("", "--sensor-width", "the sensor width must be > 0 mm");
        const bool turned = !photo.empty() && exif_orientation(photo) >= 5;
        const double f = *focal_mm * (turned ? height : width) / *sensor_width_mm;
        check_focal(f, "", "--focal-mm");
        return f;
    }
    if (exif) {
        if (photo.empty()) throw InputError("", "--exif", "needs a photo to read");
        ExifFocal e = read_exif_focal(photo, sensor_width_mm);
        // EXIF describes the stored image; scale if the photo given is another size.
        const double f = e.focal_px * double(width) / e.width;
        std::printf("exif: %s%s%s -> %.2f px\n", e.camera.c_str(), e.camera.empty() ? "" : ", ",
                    e.method.c_str(), f);
        return f;
    }
    return std::nullopt;
}

ImageSize image_size(const std::string& photo, const std::string& size_text) {
    ImageSize s;
    if (!size_text.empty()) {
        const size_t x = size_text.find('x');
        try {
            size_t a = 0, b = 0;
            if (x == std::string::npos) throw std::invalid_argument("no x");
            s.width = std::stoi(size_text.substr(0, x), &a);
            s.height = std::stoi(size_text.substr(x + 1), &b);
            if (a != x || b != size_text.size() - x - 1) throw std::invalid_argument("junk");
        } catch (const std::exception&) {
            throw InputError("", "--size", "expected WIDTHxHEIGHT in pixels, got '" + size_text + "'");
        }
        if (s.width <= 0 || s.height <= 0)
            throw InputError("", "--size", "the image size must be positive");
        return s;
    }
    if (photo.empty())
        throw InputError("", "--photo", "give the photo (--photo) or its size (--size WxH)");
    Image img = load_image(photo, "--photo");
    s.width = img.width();
    s.height = img.height();
    return s;
}

void write_camera(const std::string& project_path, const CalibrationResult& result,
                  const std::string& photo) {
    Project p;
    CalibrationResult r = result;
    if (fs::exists(project_path)) {
        p = load_project(project_path);
        const fs::path own = p.resolve(p.photo.path);
        std::error_code ec;
        if (fs::is_regular_file(own, ec) && r.intrinsics.width > 0) {
            const Image img = load_image(own.string(), "photo.path");
            if (img.width() != r.intrinsics.width || img.height() != r.intrinsics.height) {
                r = scaled_to(r, img.width(), img.height(), project_path, "photo.path");
                std::printf("note: intrinsics scaled to the project's %dx%d photo\n",
                            img.width(), img.height());
            }
        }
    } else if (photo.empty()) {
        // Matched on a size alone (--size): the photo is named later.
        p.photo.path = "photo.jpg";
        p.probe.path = "probe.exr";
        std::printf("note: created a new project; set photo.path to the %dx%d photograph the "
                    "camera was matched on and probe.path to the light probe\n",
                    r.intrinsics.width, r.intrinsics.height);
    } else {
        // Inside the project's folder: relative, so the folder can move; elsewhere: absolute.
        p.photo.path = path_for_project(fs::absolute(project_path).parent_path(), photo);
        p.probe.path = "probe.exr";
        std::printf("note: created a new project; set probe.path to the light probe\n");
    }
    p.camera = r.camera_spec();
    save_calibrated(p, project_path, r.intrinsics.width, r.intrinsics.height);
    std::printf("wrote the camera to %s\n", project_path.c_str());
}

void check_camera_outputs(const std::string& project_path, std::vector<Output> extra, ReadSet read, bool force) {
    std::error_code ec;
    if (fs::exists(project_path, ec)) read.add_project(load_project(project_path), project_path);
    Output project{project_path, "project"};
    project.updates = project_path;
    extra.insert(extra.begin(), project);
    check_outputs(extra, read, force);
}

nlohmann::json& last_result_json() {
    static nlohmann::json result;
    return result;
}

namespace {

nlohmann::json result_json(const CalibrationResult& r, const std::string& method) {
    const Intrinsics& k = r.intrinsics;
    const Distortion& d = k.distortion;
    const Uncertainty& u = r.uncertainty;
    auto v3 = [](const glm::dvec3& v) { return nlohmann::json{v.x, v.y, v.z}; };
    nlohmann::json rows = nlohmann::json::array();
    for (int i = 0; i < 3; ++i) rows.push_back({r.pose.R[0][i], r.pose.R[1][i], r.pose.R[2][i]});
    nlohmann::json doc = {
        {"method", method},
        {"image", {{"width", k.width}, {"height", k.height}}},
        {"intrinsics", {{"fx", k.fx}, {"fy", k.fy}, {"cx", k.cx}, {"cy", k.cy}, {"hfov_deg", k.hfov_deg()}}},
        {"distortion", {{"k1", d.k1}, {"k2", d.k2}, {"p1", d.p1}, {"p2", d.p2}, {"k3", d.k3}}},
        {"rotation", rows},  // world to camera, rows
        {"translation", v3(r.pose.t)},
        {"position", v3(r.pose.position())},
        {"forward", v3(glm::transpose(r.pose.R) * glm::dvec3(0, 0, 1))},
        {"rms_px", std::isnan(r.rms_px) ? nlohmann::json(nullptr) : nlohmann::json(r.rms_px)},
        {"warnings", r.warnings}};
    if (u.known)
        doc["uncertainty"] = {{"fx", u.fx}, {"fy", u.fy}, {"cx", u.cx}, {"cy", u.cy},
                              {"rotation_deg", u.rotation_deg}, {"position_m", u.position_m},
                              {"point_sigma_px", u.point_sigma_px}, {"focal_free", u.focal_free},
                              {"principal_free", u.principal_free}};
    else
        doc["uncertainty"] = nullptr;
    return doc;
}

}  // namespace

void print_result(const CalibrationResult& r, const std::string& method) {
    last_result_json() = result_json(r, method);
    const Intrinsics& k = r.intrinsics;
    const Distortion& d = k.distortion;
    // Below the printed precision, 0 (not "-0.0000" from rounding noise).
    auto tidy = [](glm::dvec3 v) {
        for (int i = 0; i < 3; ++i) v[i] = std::abs(v[i]) < 5e-5 ? 0.0 : v[i];
        return v;
    };
    const glm::dvec3 c = tidy(r.pose.position());
    const glm::dvec3 f = tidy(glm::transpose(r.pose.R) * glm::dvec3(0, 0, 1));
    std::printf("method: %s\n", method.c_str());
    std::printf("image: %dx%d\n", k.width, k.height);
    std::printf("intrinsics: fx %.3f fy %.3f cx %.3f cy %.3f hfov_deg %.3f\n", k.fx, k.fy, k.cx,
                k.cy, k.hfov_deg());
    std::printf("distortion: k1 %.6g k2 %.6g p1 %.6g p2 %.6g k3 %.6g\n", d.k1, d.k2, d.p1, d.p2,
                d.k3);
    std::printf("position: %.4f %.4f %.4f (m, world Y up)\n", c.x, c.y, c.z);
    std::printf("forward: %.4f %.4f %.4f\n", f.x, f.y, f.z);
    if (std::isnan(r.rms_px))
        std::printf("rms_px n/a\n");
    else
        std::printf("rms_px %.4f\n", r.rms_px);
    // One standard deviation; the noise it assumes for each point, where it has one.
    std::printf("uncertainty: %s", uncertainty_text(r).c_str());
    if (r.uncertainty.known)
        std::printf(" (1 sigma, points to %.2g px)", r.uncertainty.point_sigma_px);
    std::printf("\n");
    for (const std::string& w : r.warnings) warn(w);
}

}  // namespace dp::cli
