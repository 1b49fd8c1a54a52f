#include "assets/mesh_units.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace dp {

float placed_mesh_size(const vec3& lo, const vec3& hi, const Shape& shape, const Transform& transform,
                       UpAxis file_up) {
    // The file frame is a rotation by quarter turns and a uniform scale: it permutes the extents.
    const vec3 extent = glm::abs(glm::mat3(shape.file_frame(file_up)) * (hi - lo)) * glm::abs(transform.scale);
    return std::max({extent.x, extent.y, extent.z});
}

std::string mesh_size_warning(const std::string& field, const std::string& name, float size, float unit_scale) {
    if (!std::isfinite(size) || (size >= kMeshTooSmall && size <= kMeshTooLarge)) return "";
    // Of the factors a unit mix-up gives (centimetres or millimetres read as metres, or the other
    // way round), the one that brings the size closest to a metre, on a log scale: things put
    // into photographs are mostly a few decimetres to a few metres.
    const bool large = size > kMeshTooLarge;
    const float candidates[2] = {large ? 0.01f : 100.0f, large ? 0.001f : 1000.0f};
    const float factor = std::abs(std::log(size * candidates[0])) <= std::abs(std::log(size * candidates[1]))
                             ? candidates[0]
                             : candidates[1];
    char size_text[64];
    std::snprintf(size_text, sizeof(size_text), "%.3g m", double(size));
    std::string text = field + ": " + (name.empty() ? std::string("the mesh") : "'" + name + "'") + " is " +
                       size_text + " across once placed";
    if (large && unit_scale == 1.0f) {
        text += std::string(": its file looks like ") + (factor == 0.01f ? "centimetres" : "millimetres");
    } else {
        text += std::string(": it looks ") + (large ? std::to_string(int(std::lround(1 / factor))) : std::to_string(int(factor))) +
                " times too " + (large ? "large" : "small");
    }
    // In double and to six figures: 1e-5 * 1000 reads "0.01", not the float product's digits.
    char suggestion[32];
    std::snprintf(suggestion, sizeof(suggestion), "%.6g", double(unit_scale) * double(factor));
    return text + ": set unit_scale " + suggestion;
}

std::string mesh_view_warning(const std::string& field, const std::string& name, float size, float unit_scale,
                              float view_width) {
    if (!std::isfinite(size) || !(view_width > 0) || (size <= kViewTooLarge * view_width && size >= view_width / kViewTooSmall))
        return "";
    const bool large = size > kViewTooLarge * view_width;
    const float candidates[2] = {large ? 0.01f : 100.0f, large ? 0.001f : 1000.0f};
    const float aim = 0.25f * view_width;
    const float factor = std::abs(std::log(size * candidates[0] / aim)) <= std::abs(std::log(size * candidates[1] / aim))
                             ? candidates[0]
                             : candidates[1];
    char figures[160];
    const double ratio = double(size) / double(view_width);
    if (large)
        std::snprintf(figures, sizeof figures, "%.3g m across once placed, %.0f times the view's width at its distance (%.3g m)",
                      double(size), ratio, double(view_width));
    else
        std::snprintf(figures, sizeof figures, "%.3g m across once placed, 1/%.0f of the view's width at its distance (%.3g m)",
                      double(size), 1.0 / ratio, double(view_width));
    std::string text = field + ": " + (name.empty() ? std::string("the mesh") : "'" + name + "'") + " is " + figures;
    if (large && unit_scale == 1.0f)
        text += std::string(": its file looks like ") + (factor == 0.01f ? "centimetres" : "millimetres");
    char suggestion[32];
    std::snprintf(suggestion, sizeof(suggestion), "%.6g", double(unit_scale) * double(factor));
    return text + ": set unit_scale " + suggestion;
}

}  // namespace dp
