#pragma once
// Photo pixels for the studio's picking tools: the viewport works in render pixels, the
// calibration and reconstruction calls in pixels of the photograph as stored.
#include <QPointF>
#include <QSize>

#include "assets/asset_library.h"
#include "camera/camera.h"
#include "scene/project.h"

namespace dp::ui {

/// Size of the project's photo (from its header unless decoded). Throws InputError for an
/// unreadable one.
QSize photo_size(AssetLibrary& assets, const Project& project);

/// Render pixel -> photo pixel, pixel centres at integers (pixel edges scale).
vec2 render_to_photo(QPointF renderPx, QSize render, QSize photo);

/// The project's camera for its photo.
Camera photo_camera(AssetLibrary& assets, const Project& project);

}  // namespace dp::ui
