#pragma once
// Whether a mesh's size once placed looks like an object in a photograph, and what unit_scale
// would make it one: a file in centimetres or millimetres read as metres is 100 or 1000 times
// too large, and the render shows nothing of it but a wall or a speck.
#include <string>

#include "base/math.h"
#include "scene/project.h"

namespace dp {

/// Above this size (metres, the largest extent once placed) a mesh is said to look too large.
inline constexpr float kMeshTooLarge = 100.0f;
/// Below this size a mesh is said to look too small.
inline constexpr float kMeshTooSmall = 0.01f;

/// The largest extent (metres) of a mesh whose file bounds are `lo`, `hi` once placed by
/// `shape` (its up axis and unit_scale) and `transform` (its scale; the rotation is left out,
/// so the figure does not change as the object turns); `file_up` is the axis the file declares.
float placed_mesh_size(const vec3& lo, const vec3& hi, const Shape& shape, const Transform& transform,
                       UpAxis file_up = UpAxis::Y);

/// The warning for a mesh `size` metres across once placed, given its `unit_scale`, or "" when
/// the size lies within kMeshTooSmall to kMeshTooLarge. It names `field` (the shape's
/// unit_scale) and `name`, and suggests a unit_scale: the present one times 1/100 or 1/1000
/// (100 or 1000 for a small mesh), whichever brings the size closest to 1 m, e.g.
/// "objects[1].shape.unit_scale: 'chair' is 215 m across once placed: its file looks like
/// centimetres: set unit_scale 0.01".
std::string mesh_size_warning(const std::string& field, const std::string& name, float size, float unit_scale);

/// Above this many times the width the camera sees at a mesh's distance, it is said to look too
/// large for its place; below 1/kViewTooSmall of it, too small (a few pixels).
inline constexpr float kViewTooLarge = 5.0f, kViewTooSmall = 100.0f;

/// The warning for a mesh `size` metres across once placed where the camera's view is
/// `view_width` metres wide (at the mesh's distance), or "" when it fits a photograph there: as
/// mesh_size_warning, with the factor (of the unit mix-ups) that brings it nearest a quarter of
/// the view, e.g. "objects[0].shape.unit_scale: 'vase' is 30 m across once placed, 11 times the
/// view's width at its distance (2.7 m): its file looks like centimetres: set unit_scale 0.01".
std::string mesh_view_warning(const std::string& field, const std::string& name, float size, float unit_scale,
                              float view_width);

}  // namespace dp
