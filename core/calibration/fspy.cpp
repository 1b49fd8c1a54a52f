#include "calibration/fspy.h"
#include "base/input_file.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>

#include "base/error.h"
#include "calibration/cv_util.h"

namespace dp {
namespace {

using json = nlohmann::json;

constexpr uint32_t kMagic = 0x79707366;  // "fspy" read as a little-endian uint32

uint32_t le32(const uint8_t* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

/// Metres per fSpy reference distance unit; 0 when the unit is not known.
double metres_per(const std::string& unit) {
    if (unit == "Millimeters") return 0.001;
    if (unit == "Centimeters") return 0.01;
    if (unit == "Meters") return 1.0;
    if (unit == "Kilometers") return 1000.0;
    if (unit == "Inches") return 0.0254;
    if (unit == "Feet") return 0.3048;
    if (unit == "Miles") return 1609.344;
    if (unit == "None") return 1.0;
    return 0.0;
}

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

/// Checks the 16-byte header (magic, version 1) and that the file holds what it announces.
Sections read_header(const std::vector<uint8_t>& bytes, const std::string& path) {
    if (bytes.size() < 16 || le32(bytes.data()) != kMagic)
        throw InputError(path, "", "not an fSpy project file (no 'fspy' header)");
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

json parse_state(const std::vector<uint8_t>& bytes, const Sections& s, const std::string& path) {
    try {
        return json::parse(bytes.begin() + s.state_begin(), bytes.begin() + s.image_begin());
    } catch (const json::exception& e) {
        throw InputError(path, "", std::string("invalid JSON state: ") + e.what());
    }
}

/// The state's camera parameters; fSpy writes null there when its calibration failed.
const json& camera_parameters(const json& state, const std::string& path) {
    const json* cam = state.contains("cameraParameters") ? &state["cameraParameters"] : nullptr;
    if (!cam || cam->is_null())
        throw InputError(path, "cameraParameters",
                         "the project has no camera parameters (the calibration in fSpy did "
                         "not succeed)");
    return *cam;
}

/// The image size and the horizontal field of view (radians).
struct FspyLens {
    int width = 0, height = 0;
    double hfov = 0;
};

FspyLens read_lens(const json& cam, const std::string& path) {
    FspyLens lens;
    lens.width = cam.at("imageWidth").get<int>();
    lens.height = cam.at("imageHeight").get<int>();
    if (lens.width <= 0 || lens.height <= 0)
        throw InputError(path, "cameraParameters.imageWidth", "must be > 0");
    lens.hfov = cam.at("horizontalFieldOfView").get<double>();
    if (!(lens.hfov > 0 && lens.hfov < std::numbers::pi))
        throw InputError(path, "cameraParameters.horizontalFieldOfView",
                         "must be in (0, pi) radians");
    return lens;
}

/// The camera as fSpy stores it, in Blender's axes and fSpy's length unit.
struct BlenderCamera {
    glm::dmat3 R;  ///< camera-to-world rotation
    glm::dvec3 C;  ///< camera centre
};

/// The rotation and centre of the camera transform's rows (a 4x4 matrix, row-major).
BlenderCamera read_camera_transform(const json& cam, const std::string& path) {
    const json& rows = cam.at("cameraTransform").at("rows");
    BlenderCamera b;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) b.R[c][r] = rows.at(size_t(r)).at(size_t(c)).get<double>();
        b.C[r] = rows.at(size_t(r)).at(3).get<double>();
    }
    const glm::dmat3 E = b.R * glm::transpose(b.R) - glm::dmat3(1.0);
    double err = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) err = std::max(err, std::abs(E[i][j]));
    if (err > 1e-4 || glm::determinant(b.R) < 0)
        throw InputError(path, "cameraParameters.cameraTransform",
                         "the rotation part is not a rotation matrix");
    return b;
}

/// The reference distance unit of the calibration settings ("None" where there is none).
std::string distance_unit(const json& state) {
    if (state.contains("calibrationSettingsBase") &&
        state["calibrationSettingsBase"].contains("referenceDistanceUnit"))
        return state["calibrationSettingsBase"]["referenceDistanceUnit"].get<std::string>();
    return "None";
}

/// Metres per `unit`; an unknown unit is taken as metres, with a warning.
double metres_per_unit(const std::string& unit, std::vector<std::string>& warnings) {
    const double metres = metres_per(unit);
    if (metres != 0) return metres;
    warnings.push_back("unknown distance unit '" + unit + "': lengths are taken as metres");
    return 1.0;
}

/// Without a reference distance fSpy fixes no scale, so the lengths it gives mean nothing.
bool has_reference_distance(const json& state) {
    return state.contains("calibrationSettingsBase") &&
           state["calibrationSettingsBase"].contains("referenceDistanceAxis") &&
           !state["calibrationSettingsBase"]["referenceDistanceAxis"].is_null();
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

/// Pixel intrinsics from the field of view and fSpy's principal point.
Intrinsics intrinsics_from_fspy(const json& cam, const FspyLens& lens) {
    const int W = lens.width, H = lens.height;
    // Principal point in fSpy's image plane: the longer side spans [-1, 1], +y up.
    const json& pp = cam.at("principalPoint");
    const double px = pp.at("x").get<double>(), py = pp.at("y").get<double>();
    const double aspect = double(W) / H;
    const double u = aspect >= 1 ? 0.5 * (px + 1) : 0.5 * (px / aspect + 1);
    const double v = aspect >= 1 ? 0.5 * (1 - py * aspect) : 0.5 * (1 - py);
    Intrinsics k;
    k.width = W, k.height = H;
    k.fx = k.fy = 0.5 * W / std::tan(0.5 * lens.hfov);
    k.cx = u * W - 0.5;  // OpenCV pixel centres: the image spans [-0.5, W - 0.5]
    k.cy = v * H - 0.5;
    return k;
}

}  // namespace

FspyImport read_fspy(const std::string& path) {
    const std::vector<uint8_t> bytes = read_bytes(path);
    const Sections sections = read_header(bytes, path);
    const json state = parse_state(bytes, sections, path);
    FspyImport out;
    out.image.assign(bytes.begin() + sections.image_begin(), bytes.begin() + sections.image_end());
    out.image_extension = image_extension(out.image);

    const json& cam = camera_parameters(state, path);
    try {  // a missing or mistyped field surfaces as nlohmann's exception
        const FspyLens lens = read_lens(cam, path);
        const BlenderCamera blender = read_camera_transform(cam, path);
        out.unit = distance_unit(state);
        const double metres = metres_per_unit(out.unit, out.result.warnings);
        if (!has_reference_distance(state) || out.unit == "None")
            out.result.warnings.push_back(
                "the fSpy project sets no reference distance: the scene's scale is arbitrary");
        out.result.pose = pose_from_blender(blender, metres);
        out.result.intrinsics = intrinsics_from_fspy(cam, lens);
    } catch (const json::exception& e) {
        throw InputError(path, "cameraParameters", std::string("malformed: ") + e.what());
    }
    out.result.rms_px = std::numeric_limits<double>::quiet_NaN();
    return out;
}

}  // namespace dp
