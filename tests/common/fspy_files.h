#pragma once
// fSpy files for the importer's tests: writing a project (header, state, image) as fSpy does,
// reading a project's state back, and checking an imported camera against the control points
// the fSpy user placed (its vanishing lines and origin), in the image's pixels.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calibration/calibration.h"

namespace dp::test {

using json = nlohmann::json;

/// Writes an .fspy file: header (magic, version, state size, image size), state, image.
inline void write_fspy(const std::string& path, const json& state,
                       const std::vector<uint8_t>& image, uint32_t version = 1) {
    const std::string text = state.dump();
    std::ofstream out(path, std::ios::binary);
    auto u32 = [&](uint32_t v) {
        for (int i = 0; i < 4; ++i) out.put(char((v >> (8 * i)) & 0xFF));
    };
    out.write("fspy", 4);
    u32(version);
    u32(uint32_t(text.size()));
    u32(uint32_t(image.size()));
    out.write(text.data(), std::streamsize(text.size()));
    out.write(reinterpret_cast<const char*>(image.data()), std::streamsize(image.size()));
}

/// The state JSON of an .fspy file, read on its own (not through the importer).
inline json read_fspy_state(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<uint8_t> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (b.size() < 16) return json();
    const uint32_t size = uint32_t(b[8]) | uint32_t(b[9]) << 8 | uint32_t(b[10]) << 16 |
                          uint32_t(b[11]) << 24;
    if (16 + size > b.size()) return json();
    return json::parse(b.begin() + 16, b.begin() + 16 + size);
}

/// fSpy's axis names ("xPositive", ...) as directions in Blender's world (Z up).
inline glm::dvec3 fspy_axis(const std::string& name) {
    const double s = name.find("Negative") != std::string::npos ? -1.0 : 1.0;
    const char a = name.empty() ? 'x' : name[0];
    return s * glm::dvec3(a == 'x', a == 'y', a == 'z');
}

/// How far the imported camera is from what the fSpy user placed, in pixels.
struct ControlPointErrors {
    double lines_px = 0;   ///< the worst endpoint's distance from the line through the other
                           ///< endpoint and the vanishing point of the group's axis
    double origin_px = 0;  ///< the origin control point from the projection of world (0,0,0)
    int lines = 0;         ///< how many control lines were checked
};

/// Checks `r` against the control points of an fSpy state: each vanishing-point group's lines
/// must pass through the projection of its world axis (fSpy's Blender axes turned into ours,
/// (x, y, z) -> (x, z, -y)), and the origin point must be where world (0, 0, 0) projects.
/// Control points are relative ([0, 1] over the image, y down), as fSpy stores them. The
/// second group comes from the first's endpoints in fSpy's quad mode; the third counts only
/// where it set the principal point.
inline ControlPointErrors control_point_errors(const json& state, const CalibrationResult& r) {
    const Intrinsics& k = r.intrinsics;
    const glm::dmat3 K(glm::dvec3(k.fx, 0, 0), glm::dvec3(0, k.fy, 0), glm::dvec3(k.cx, k.cy, 1));
    auto pixel = [&](const json& p) {
        return glm::dvec3(p.at("x").get<double>() * k.width - 0.5,
                          p.at("y").get<double>() * k.height - 0.5, 1.0);
    };
    auto ours = [](glm::dvec3 b) { return glm::dvec3(b.x, b.z, -b.y); };
    ControlPointErrors out;
    auto check_group = [&](const json& segments, const glm::dvec3& blender_axis) {
        const glm::dvec3 vp = K * (r.pose.R * ours(blender_axis));  // homogeneous
        for (const json& seg : segments) {
            const glm::dvec3 a = pixel(seg.at(0)), b = pixel(seg.at(1));
            for (const auto& [p, q] : {std::pair(a, b), std::pair(b, a)}) {
                const glm::dvec3 line = glm::cross(p, vp);
                const double d = std::abs(glm::dot(line, q)) / std::hypot(line.x, line.y);
                out.lines_px = std::max(out.lines_px, d);
            }
            ++out.lines;
        }
    };
    const json& settings = state.at("calibrationSettingsBase");
    const json& base = state.at("controlPointsStateBase");
    const glm::dvec3 first = fspy_axis(settings.at("firstVanishingPointAxis"));
    const json& first_lines = base.at("firstVanishingPoint").at("lineSegments");
    check_group(first_lines, first);
    const std::string mode = state.at("globalSettings").at("calibrationMode");
    if (mode == "TwoVanishingPoints") {
        const json& two = state.at("calibrationSettings2VP");
        const glm::dvec3 second = fspy_axis(settings.at("secondVanishingPointAxis"));
        json second_lines = state.at("controlPointsState2VP").at("secondVanishingPoint").at("lineSegments");
        if (two.value("quadModeEnabled", false))
            second_lines = json::array({json::array({first_lines[0][0], first_lines[1][0]}),
                                        json::array({first_lines[0][1], first_lines[1][1]})});
        check_group(second_lines, second);
        if (two.value("principalPointMode", "") == "FromThirdVanishingPoint")
            check_group(state.at("controlPointsState2VP").at("thirdVanishingPoint").at("lineSegments"),
                        glm::cross(first, second));
    }
    const glm::dvec3 o = K * r.pose.t;  // world (0, 0, 0) in the camera: t
    const glm::dvec3 origin = pixel(base.at("origin"));
    out.origin_px = std::hypot(o.x / o.z - origin.x, o.y / o.z - origin.y);
    return out;
}

}  // namespace dp::test
