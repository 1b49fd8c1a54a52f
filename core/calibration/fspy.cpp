#include "calibration/fspy.h"

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

}  // namespace

FspyImport read_fspy(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, "", "cannot open the file");
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                               std::istreambuf_iterator<char>());
    if (bytes.size() < 16 || le32(bytes.data()) != kMagic)
        throw InputError(path, "", "not an fSpy project file (no 'fspy' header)");
    const uint32_t version = le32(&bytes[4]);
    if (version != 1)
        throw InputError(path, "", "unsupported fSpy project version " + std::to_string(version));
    const uint64_t state_size = le32(&bytes[8]), image_size = le32(&bytes[12]);
    if (16 + state_size + image_size > bytes.size())
        throw InputError(path, "",
                         "the file is truncated (the header announces " +
                             std::to_string(16 + state_size + image_size) +
                             " bytes, the file has " + std::to_string(bytes.size()) + ")");
    json state;
    try {
        state = json::parse(bytes.begin() + 16, bytes.begin() + 16 + std::ptrdiff_t(state_size));
    } catch (const json::exception& e) {
        throw InputError(path, "", std::string("invalid JSON state: ") + e.what());
    }
    FspyImport out;
    out.image.assign(bytes.begin() + 16 + std::ptrdiff_t(state_size),
                     bytes.begin() + 16 + std::ptrdiff_t(state_size + image_size));
    out.image_extension = image_extension(out.image);

    const json* cam = state.contains("cameraParameters") ? &state["cameraParameters"] : nullptr;
    if (!cam || cam->is_null())
        throw InputError(path, "cameraParameters",
                         "the project has no camera parameters (the calibration in fSpy did "
                         "not succeed)");
    try {
        const int W = (*cam).at("imageWidth").get<int>(), H = (*cam).at("imageHeight").get<int>();
        if (W <= 0 || H <= 0) throw InputError(path, "cameraParameters.imageWidth", "must be > 0");
        const double hfov = (*cam).at("horizontalFieldOfView").get<double>();
        if (!(hfov > 0 && hfov < std::numbers::pi))
            throw InputError(path, "cameraParameters.horizontalFieldOfView",
                             "must be in (0, pi) radians");
        const json& rows = (*cam).at("cameraTransform").at("rows");
        glm::dmat3 Rb;  // camera-to-world rotation, Blender axes
        glm::dvec3 Cb;  // camera centre, Blender axes
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) Rb[c][r] = rows.at(size_t(r)).at(size_t(c)).get<double>();
            Cb[r] = rows.at(size_t(r)).at(3).get<double>();
        }
        const glm::dmat3 E = Rb * glm::transpose(Rb) - glm::dmat3(1.0);
        double err = 0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) err = std::max(err, std::abs(E[i][j]));
        if (err > 1e-4 || glm::determinant(Rb) < 0)
            throw InputError(path, "cameraParameters.cameraTransform",
                             "the rotation part is not a rotation matrix");

        out.unit = "None";
        if (state.contains("calibrationSettingsBase") &&
            state["calibrationSettingsBase"].contains("referenceDistanceUnit"))
            out.unit = state["calibrationSettingsBase"]["referenceDistanceUnit"].get<std::string>();
        double unit = metres_per(out.unit);
        if (unit == 0) {
            out.result.warnings.push_back("unknown distance unit '" + out.unit +
                                          "': lengths are taken as metres");
            unit = 1.0;
        }
        const bool has_reference =
            state.contains("calibrationSettingsBase") &&
            state["calibrationSettingsBase"].contains("referenceDistanceAxis") &&
            !state["calibrationSettingsBase"]["referenceDistanceAxis"].is_null();
        if (!has_reference || out.unit == "None")
            out.result.warnings.push_back(
                "the fSpy project sets no reference distance: the scene's scale is arbitrary");

        // Blender world (Z up) -> ours (Y up); Blender camera (-Z forward, +Y up) -> OpenCV
        // (+Z forward, +Y down).
        const glm::dmat3 A = calib::from_rows({1, 0, 0}, {0, 0, 1}, {0, -1, 0});
        const glm::dmat3 F = calib::from_rows({1, 0, 0}, {0, -1, 0}, {0, 0, -1});
        Pose& pose = out.result.pose;
        pose.R = F * glm::transpose(Rb) * glm::transpose(A);
        const glm::dvec3 C = unit * (A * Cb);
        pose.t = -(pose.R * C);

        // Principal point in fSpy's image plane: the longer side spans [-1, 1], +y up.
        const json& pp = (*cam).at("principalPoint");
        const double px = pp.at("x").get<double>(), py = pp.at("y").get<double>();
        const double aspect = double(W) / H;
        const double u = aspect >= 1 ? 0.5 * (px + 1) : 0.5 * (px / aspect + 1);
        const double v = aspect >= 1 ? 0.5 * (1 - py * aspect) : 0.5 * (1 - py);
        Intrinsics& k = out.result.intrinsics;
        k.width = W, k.height = H;
        k.fx = k.fy = 0.5 * W / std::tan(0.5 * hfov);
        k.cx = u * W - 0.5;  // OpenCV pixel centres: the image spans [-0.5, W - 0.5]
        k.cy = v * H - 0.5;
    } catch (const json::exception& e) {
        throw InputError(path, "cameraParameters", std::string("malformed: ") + e.what());
    }
    out.result.rms_px = std::numeric_limits<double>::quiet_NaN();
    return out;
}

}  // namespace dp
