#pragma once
// Vector overlays drawn over the render: ground grid, real proxies as wireframe, virtual
// objects' bounding spheres, the lights' glyphs, and the selection's gizmo axes.
#include <QTransform>

#include "camera/camera.h"
#include "scene/project.h"

class QPainter;

namespace dp::ui {

struct OverlayOptions {
    bool grid = true;
    bool proxies = true;
    bool outlines = true;
    int selected = -1;
    int selectedLight = -1;  ///< index into project.lights
};

/// Draws the overlays (lights with the outlines: a bulb with rays at a point light, a spot's
/// cone, an area light's face with its facing, each with a dashed drop line to the surface
/// below); `toWidget` maps render pixel coordinates to widget coordinates.
void draw_overlays(QPainter& painter, const Project& project, const Camera& camera,
                   const QTransform& toWidget, const OverlayOptions& options);

}  // namespace dp::ui
