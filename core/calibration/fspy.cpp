#include "calibration/fspy.h"
#include "base/input_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>

#include "base/error.h"
#include "calibration/cv_util.h"
#include "base/byte_order.h"

namespace dp {
namespace {

using json = nlohmann::json;

constexpr uint32_t kMagic = 0x79707366;  // "fspy" read as a little-endian uint32

/// Metres per fSpy reference distance unit; 0 when the unit is not known. "No unit" is what
/// fSpy 1.0 writes for none ("None" in earlier versions): lengths in whatever the reference
/// distance was measured in, taken as metres.
double metres_per(const std::string& unit) {
    if (unit == "Millimeters") return 0.001;
    if (unit == "Centimeters") return 0.01;
    if (unit == "Meters") return 1.0;
    if (unit == "Kilometers") return 1000.0;
    if (unit == "Inches") return 0.0254;
    if (unit == "Feet") return 0.3048;
    // Early fSpy versions offered yards; fSpy now reads them as three times as many feet.
    if (unit == "Yards") return 0.9144;
    if (unit == "Miles") return 1609.344;
    if (unit == "No unit" || unit == "None") return 1.0;
    return 0.0;
}

bool is_no_unit(const std::string& unit) { return unit == "No unit" || unit == "None"; }

std::string image_extension(const std::vector<uint8_t>& b) {
    if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return ".jpg";
    if (b.size() >= 4 && b[0] == 0x89 && b[1] == 'P' && b[2] == 'N' && b[3] == 'G') return ".png";
    return "";
}

std::vector<uint8_t> read_bytes(const std::string& path) {
    // A photo and a few kB of JSON: 512 MB is far above any real one and refuses a device.
    check_input_file(path, "", "an fSpy project file", 512u << 20);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, "", "cannot open the file");
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
}

/// Where the file's parts lie: the header, then `state_size` bytes of JSON, then the image.
struct Sections {
    uint64_t state_size = 0, image_size = 0;
    std::ptrdiff_t state_begin() const { return 16; }
    std::ptrdiff_t image_begin() const { return 16 + std::ptrdiff_t(state_size); }
    std::ptrdiff_t image_end() const { return 16 + std::ptrdiff_t(state_size + image_size); }
};

/// Checks the 16-byte header (version 1) and that the file holds what it announces.
Sections read_header(const std::vector<uint8_t>& bytes, const std::string& path) {
    if (bytes.size() < 16)
        throw InputError(path, "", "the file is truncated (shorter than the fSpy header)");
    const uint32_t version = le32(&bytes[4]);
    if (version != 1)
        throw InputError(path, "", "unsupported fSpy project version " + std::to_string(version));
    const Sections s{le32(&bytes[8]), le32(&bytes[12])};
    if (16 + s.state_size + s.image_size > bytes.size())
        throw InputError(path, "",
                         "the file is truncated (the header announces " +
                             std::to_string(16 + s.state_size + s.image_size) +
                             " bytes, the file has " + std::to_string(bytes.size()) + ")");
    return s;
}

json parse_json(std::vector<uint8_t>::const_iterator begin,
                std::vector<uint8_t>::const_iterator end, const std::string& path,
                const char* what) {
    try {
        return json::parse(begin, end);
    } catch (const json::exception& e) {
        throw InputError(path, "", std::string("invalid JSON ") + what + ": " + e.what());
    }
}

/// The exported camera parameters JSON starts, after white space, with an object.
bool looks_like_json(const std::vector<uint8_t>& bytes) {
    size_t i = 0;
    if (bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF) i = 3;
    while (i < bytes.size() && std::isspace(bytes[i])) ++i;
    return i < bytes.size() && bytes[i] == '{';
}

/// The state's camera parameters; fSpy writes null there when its calibration failed.
const json& camera_parameters(const json& state, const std::string& path) {
    const json* cam = state.contains("cameraParameters") ? &state["cameraParameters"] : nullptr;
    if (!cam || cam->is_null())
        throw InputError(path, "cameraParameters",
                         "the project has no camera parameters (the calibration in fSpy did "
                         "not succeed)");
    if (!cam->is_object()) throw InputError(path, "cameraParameters", "expected an object");
    return *cam;
}

/// Reads the camera parameters object; `prefix` names it in messages ("cameraParameters." in
/// a project, "" in the exported JSON, where it is the whole file).
class CameraReader {
public:
    CameraReader(const json& cam, const std::string& path, std::string prefix)
        : cam_(cam), path_(path), prefix_(std::move(prefix)) {}

    /// A finite number; absent (nullopt) is allowed only when `optional`.
    std::optional<double> number(const char* key, bool optional = false) const {
        if (!cam_.contains(key) || cam_[key].is_null()) {
            if (optional) return std::nullopt;
            fail(key, "missing");
        }
        if (!cam_[key].is_number()) fail(key, "expected a number");
        const double v = cam_[key].get<double>();
        if (!std::isfinite(v)) fail(key, "expected a finite number");
        return v;
    }
    /// The image size: whole numbers of pixels, at most 2^20 a side.
    int pixels(const char* key) const {
        const double v = *number(key);
        if (!(v >= 1 && v <= double(1 << 20) && v == std::floor(v)))
            fail(key, "expected a whole number of pixels in [1, 1048576]");
        return int(v);
    }
    /// A point {"x": .., "y": ..}.
    glm::dvec2 point(const char* key) const {
        const json* p = cam_.contains(key) ? &cam_[key] : nullptr;
        if (!p || !p->is_object()) fail(key, "expected an object with x and y");
        glm::dvec2 out;
        int i = 0;
        for (const char* c : {"x", "y"}) {
            if (!p->contains(c) || !(*p)[c].is_number())
                fail(key, std::string("expected a number for ") + c);
            out[i++] = (*p)[c].get<double>();
        }
        return out;
    }
    /// The 4x4 row-major matrix {"rows": [[..], ..]} of `key`.
    glm::dmat4 matrix(const char* key) const {
        const json* m = cam_.contains(key) ? &cam_[key] : nullptr;
        const json* rows = m && m->is_object() && m->contains("rows") ? &(*m)["rows"] : nullptr;
        if (!rows || !rows->is_array() || rows->size() != 4)
            fail(key, "expected {\"rows\": [4 rows of 4 numbers]}");
        glm::dmat4 out(0.0);
        for (size_t r = 0; r < 4; ++r) {
            const json& row = (*rows)[r];
            if (!row.is_array() || row.size() != 4)
                fail(key, "expected {\"rows\": [4 rows of 4 numbers]}");
            for (size_t c = 0; c < 4; ++c) {
                if (!row[c].is_number()) fail(key, "expected numbers in its rows");
                out[int(c)][int(r)] = row[c].get<double>();
            }
        }
        return out;
    }
    [[noreturn]] void fail(const std::string& key, const std::string& what) const {
        throw InputError(path_, prefix_ + key, what);
    }

private:
    const json& cam_;
    const std::string& path_;
    std::string prefix_;
};

/// The image size and the focal length relative to half the longer side.
struct FspyLens {
    int width = 0, height = 0;
    double relative_focal = 0;
};

FspyLens read_lens(const CameraReader& cam, std::vector<std::string>& warnings) {
    FspyLens lens;
    lens.width = cam.pixels("imageWidth");
    lens.height = cam.pixels("imageHeight");
    const std::optional<double> rel = cam.number("relativeFocalLength", true);
    const std::optional<double> hfov = cam.number("horizontalFieldOfView", !!rel);
    if (hfov && !(*hfov > 0 && *hfov < std::numbers::pi))
        cam.fail("horizontalFieldOfView", "must be in (0, pi) radians");
    if (rel) {
        if (!(*rel > 1e-6 && *rel < 1e6)) cam.fail("relativeFocalLength", "must be in (1e-6, 1e6)");
        lens.relative_focal = *rel;
    } else {
        // fSpy 1.0 measures the "horizontal" field of view across the longer side.
        lens.relative_focal = 1.0 / std::tan(0.5 * *hfov);
    }
    if (rel && hfov) {
        // Across the longer side (fSpy 1.0), or across the width (earlier versions): both
        // agree with the relative focal length; anything else is a file edited by hand.
        const double shorter = double(std::min(lens.width, lens.height)) /
                               double(std::max(lens.width, lens.height));
        const double longer_fov = 2 * std::atan(1.0 / *rel);
        const double width_fov = 2 * std::atan((lens.width < lens.height ? shorter : 1.0) / *rel);
        if (std::abs(*hfov - longer_fov) > 1e-5 && std::abs(*hfov - width_fov) > 1e-5)
            warnings.push_back("horizontalFieldOfView (" + std::to_string(*hfov) +
                               " rad) does not match relativeFocalLength (" +
                               std::to_string(*rel) + "): the relative focal length is used");
    }
    return lens;
}

/// The camera as fSpy stores it, in Blender's axes and fSpy's length unit.
struct BlenderCamera {
    glm::dmat3 R;  ///< camera-to-world rotation
    glm::dvec3 C;  ///< camera centre
};

BlenderCamera read_camera_transform(const CameraReader& cam) {
    const glm::dmat4 M = cam.matrix("cameraTransform");
    BlenderCamera b{glm::dmat3(M), glm::dvec3(M[3])};
    const glm::dmat3 E = b.R * glm::transpose(b.R) - glm::dmat3(1.0);
    double err = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) err = std::max(err, std::abs(E[i][j]));
    if (!(err <= 1e-4) || glm::determinant(b.R) < 0)
        cam.fail("cameraTransform", "the rotation part is not a rotation matrix");
    return b;
}

/// Metres per length unit of the file, with the warnings its unit and reference call for.
double project_metres(const json& state, const std::string& path, std::string& unit,
                      std::vector<std::string>& warnings) {
    const json* base = state.contains("calibrationSettingsBase") &&
                               state["calibrationSettingsBase"].is_object()
                           ? &state["calibrationSettingsBase"]
                           : nullptr;
    unit = "No unit";
    if (base && base->contains("referenceDistanceUnit")) {
        const json& u = (*base)["referenceDistanceUnit"];
        if (!u.is_string())
            throw InputError(path, "calibrationSettingsBase.referenceDistanceUnit",
                             "expected a string");
        unit = u.get<std::string>();
    }
    // Without a reference distance fSpy fixes no scale, so the lengths it gives mean nothing.
    const bool reference = base && base->contains("referenceDistanceAxis") &&
                           !(*base)["referenceDistanceAxis"].is_null();
    double metres = metres_per(unit);
    if (metres == 0) {
        warnings.push_back("unknown distance unit '" + unit + "': lengths are taken as metres");
        metres = 1.0;
    }
    if (!reference)
        warnings.push_back(
            "the fSpy project sets no reference distance: the scene's scale is arbitrary");
    else if (is_no_unit(unit))
        warnings.push_back(
            "the fSpy project's reference distance has no unit: lengths are taken as metres");
    return metres;
}

/// The world-to-camera pose in our world (Y up, metres) and OpenCV's camera axes.
Pose pose_from_blender(const BlenderCamera& b, double metres) {
    // Blender world (Z up) -> ours (Y up); Blender camera (-Z forward, +Y up) -> OpenCV
    // (+Z forward, +Y down).
    const glm::dmat3 A = calib::from_rows({1, 0, 0}, {0, 0, 1}, {0, -1, 0});
    const glm::dmat3 F = calib::from_rows({1, 0, 0}, {0, -1, 0}, {0, 0, -1});
    Pose pose;
    pose.R = F * glm::transpose(b.R) * glm::transpose(A);
    const glm::dvec3 C = metres * (A * b.C);
    pose.t = -(pose.R * C);
    return pose;
}

/// Pixel intrinsics from fSpy's image plane, where the longer side spans [-1, 1] (+y up) and
/// the shorter one keeps the aspect: one unit there is half the longer side in pixels.
Intrinsics intrinsics_from_fspy(const CameraReader& cam, const FspyLens& lens) {
    const int W = lens.width, H = lens.height;
    const double half_longer = 0.5 * std::max(W, H);
    const glm::dvec2 pp = cam.point("principalPoint");
    Intrinsics k;
    k.width = W, k.height = H;
    k.fx = k.fy = lens.relative_focal * half_longer;
    // From the image plane to pixels: the centre, then one unit per half longer side; OpenCV
    // pixel centres put the image's edges at -0.5 and W - 0.5.
    k.cx = 0.5 * W + pp.x * half_longer - 0.5;
    k.cy = 0.5 * H - pp.y * half_longer - 0.5;
    if (!std::isfinite(k.cx) || !std::isfinite(k.cy) || std::abs(pp.x) > 1e6 ||
        std::abs(pp.y) > 1e6)
        cam.fail("principalPoint", "is not a finite point near the image");
    return k;
}

/// The camera of a camera parameters object (a project's, or the exported JSON).
CalibrationResult read_camera(const CameraReader& cam, double metres,
                              std::vector<std::string> warnings) {
    CalibrationResult r;
    const FspyLens lens = read_lens(cam, warnings);
    const BlenderCamera blender = read_camera_transform(cam);
    r.pose = pose_from_blender(blender, metres);
    const glm::dvec3 c = r.pose.position();
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
        cam.fail("cameraTransform", "the camera position is not finite in metres");
    r.intrinsics = intrinsics_from_fspy(cam, lens);
    r.warnings = std::move(warnings);
    r.rms_px = std::numeric_limits<double>::quiet_NaN();
    return r;
}

FspyImport read_project(const std::vector<uint8_t>& bytes, const std::string& path) {
    const Sections sections = read_header(bytes, path);
    const json state = parse_json(bytes.begin() + sections.state_begin(),
                                  bytes.begin() + sections.image_begin(), path, "state");
    if (!state.is_object()) throw InputError(path, "", "the state is not a JSON object");
    FspyImport out;
    out.image.assign(bytes.begin() + sections.image_begin(), bytes.begin() + sections.image_end());
    out.image_extension = image_extension(out.image);
    const json& cam = camera_parameters(state, path);
    std::vector<std::string> warnings;
    const double metres = project_metres(state, path, out.unit, warnings);
    out.result = read_camera(CameraReader(cam, path, "cameraParameters."), metres, warnings);
    return out;
}

FspyImport read_json_export(const std::vector<uint8_t>& bytes, const std::string& path) {
    const json cam = parse_json(bytes.begin(), bytes.end(), path, "camera parameters");
    if (!cam.is_object() || !cam.contains("cameraTransform"))
        throw InputError(path, "",
                         "not an fSpy project file (no 'fspy' header) nor fSpy's exported "
                         "camera parameters (no cameraTransform)");
    FspyImport out;
    out.from_json_export = true;
    out.result = read_camera(
        CameraReader(cam, path, ""), 1.0,
        {"fSpy's exported camera parameters carry no distance unit: lengths are taken as "
         "metres (the .fspy project has the reference distance's unit)"});
    return out;
}

}  // namespace

FspyImport read_fspy(const std::string& path) {
    const std::vector<uint8_t> bytes = read_bytes(path);
    if (bytes.size() >= 4 && le32(bytes.data()) == kMagic) return read_project(bytes, path);
    if (looks_like_json(bytes)) return read_json_export(bytes, path);
    throw InputError(path, "",
                     "not an fSpy project file (no 'fspy' header) nor fSpy's exported camera "
                     "parameters JSON");
}

}  // namespace dp
