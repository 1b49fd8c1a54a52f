#include "photo_geometry.h"

#include "base/error.h"

namespace dp::ui {

QSize photo_size(AssetLibrary& assets, const Project& project) {
    int w = 0, h = 0;
    assets.photo_size(project, w, h);
    return QSize(w, h);
}

vec2 render_to_photo(QPointF r, QSize render, QSize photo) {
    if (!render.isValid()) throw InputError("", "", "no photo is shown in the viewport");
    const double sx = double(photo.width()) / render.width();
    const double sy = double(photo.height()) / render.height();
    return vec2(float((r.x() + 0.5) * sx - 0.5), float((r.y() + 0.5) * sy - 0.5));
}

Camera photo_camera(AssetLibrary& assets, const Project& project) {
    const QSize s = photo_size(assets, project);
    return project.camera.build(s.width(), s.height());
}

}  // namespace dp::ui
