#include "photo_geometry.h"

#include <map>
#include <string>

#include "base/error.h"
#include "image/image_io.h"

namespace dp::ui {

QSize photo_size(const Project& project) {
    static std::map<std::string, QSize> sizes;  // photos do not change size under one path
    const std::string path = project.resolve(project.photo.path).string();
    auto it = sizes.find(path);
    if (it != sizes.end()) return it->second;
    const Image img = load_image(path, "photo.path");
    const QSize s(img.width(), img.height());
    sizes[path] = s;
    return s;
}

vec2 render_to_photo(QPointF r, QSize render, QSize photo) {
    if (!render.isValid()) throw InputError("", "", "no photo is shown in the viewport");
    const double sx = double(photo.width()) / render.width();
    const double sy = double(photo.height()) / render.height();
    return vec2(float((r.x() + 0.5) * sx - 0.5), float((r.y() + 0.5) * sy - 0.5));
}

Camera photo_camera(const Project& project) {
    const QSize s = photo_size(project);
    return project.camera.build(s.width(), s.height());
}

}  // namespace dp::ui
