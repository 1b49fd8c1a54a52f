#pragma once
// Picking and dragging math for the viewport's transform gizmo, in full-render pixel space.
#include "camera/camera.h"
#include "scene/project.h"

namespace dp::ui {

enum class GizmoMode { Translate, Rotate, Scale };

/// The visible object whose bounding sphere the ray through pixel (px, py) meets first; -1 if
/// none.
int pick_object(const Project& project, const Camera& camera, float px, float py);

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

/// The camera the viewport draws with: the project's camera for the render size.
Camera view_camera(const Project& project, int photo_w, int photo_h, int width, int height);

}  // namespace dp::ui
