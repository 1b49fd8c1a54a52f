#pragma once
// Picking and dragging math for the viewport's transform gizmo, in full-render pixel space.
#include "camera/camera.h"
#include "scene/project.h"

namespace dp::ui {

enum class GizmoMode { Translate, Rotate, Scale };

/// The visible object whose bounding sphere the ray through pixel (px, py) meets first; -1 if
/// none.
int pick_object(const Project& project, const Camera& camera, float px, float py);

/// The light whose glyph is nearest pixel (px, py): its position projects within `radius`
/// pixels of it, or (an area light) the ray through the pixel meets its face. -1 if none.
int pick_light(const Project& project, const Camera& camera, float px, float py, float radius);

/// The area light's face corners (a rectangle; a disk's bounding square) in world space.
void light_face(const VirtualLight& light, vec3 corners[4]);

/// drag_transform for a light: translate as an object's but with no snapping (a lamp hangs
/// where it is put), and where the line of sight to it is within 10 degrees of level (its
/// horizontal plane seen edge on) across the view instead, in the upright plane facing the
/// camera, at its height; rotate without an axis tilts it, 0.5 degree per pixel (across the
/// screen about the level line of sight, so that its beam swings the way the mouse goes; up
/// and down about the view's level right axis), with an axis as an object's; scale as an
/// object's.
Transform light_drag_transform(GizmoMode mode, const Transform& start, const Camera& camera,
                               vec2 from, vec2 to, int axis);

/// Where the ray through pixel (px, py) meets the horizontal plane y = `height`; false if it
/// misses (parallel, or the plane is behind the camera).
bool ground_point(const Camera& camera, float px, float py, float height, vec3& out);

/// Height of the highest real surface facing up at (x, z): the tops of box proxies and plane
/// proxies lying flat (turned about the vertical axis only); 0 (the ground) where there is none.
float support_height(const Project& project, float x, float z);

/// The transform after dragging from pixel `from` to pixel `to` in `mode`, starting from
/// `start`: translate moves on the horizontal plane through the object (grab point kept under
/// the cursor) and, given a project, snaps onto real surfaces (keeping the object's height
/// above whatever supports it); rotate turns about the vertical axis (0.5 degree per pixel
/// across); scale multiplies uniformly by the ratio of the cursor's distances to the object's
/// centre on screen.
Transform drag_transform(GizmoMode mode, const Transform& start, const Camera& camera, vec2 from,
                         vec2 to, const Project* snap = nullptr);

/// Euler angles (degrees, X then Y then Z as in Transform) of the rotation matrix `r`.
vec3 euler_deg(const glm::mat3& r);

/// Euler angles (degrees, X then Y then Z as in Transform) of the rotation `euler_deg` followed
/// by a turn of `degrees` about the world axis `axis` (0 X, 1 Y, 2 Z). A turn about Z, or
/// about an axis the rotation has not left yet, just adds to that angle.
vec3 rotate_about_world_axis(const vec3& euler_deg, int axis, float degrees);

/// The keyed transform's typed value applied to `start`: Translate moves `value` metres along
/// `axis` (X when -1), Rotate turns `value` degrees about the world `axis` (the vertical when
/// -1), Scale multiplies the scale by `value` (all three components when -1, else only
/// `axis`'s).
Transform typed_transform(GizmoMode mode, const Transform& start, int axis, float value);

/// drag_transform constrained to the world axis `axis` (0 X, 1 Y, 2 Z; -1: unconstrained,
/// drag_transform itself): Translate moves along the axis by the cursor's travel along the
/// axis's image on screen, Rotate turns about it (0.5 degree per pixel across), Scale scales
/// only that component.
Transform axis_drag_transform(GizmoMode mode, const Transform& start, const Camera& camera,
                              vec2 from, vec2 to, int axis, const Project* snap = nullptr);

/// The camera the viewport draws with: the project's camera for the render size.
Camera view_camera(const Project& project, int photo_w, int photo_h, int width, int height);

}  // namespace dp::ui
