#pragma once
// Vector overlays drawn over the render: ground grid, real proxies as wireframe, virtual
// objects' bounding spheres, and the selected object's gizmo axes.
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
};

/// Draws the overlays; `toWidget` maps render pixel coordinates to widget coordinates.
void draw_overlays(QPainter& painter, const Project& project, const Camera& camera,
                   const QTransform& toWidget, const OverlayOptions& options);

}  // namespace dp::ui
