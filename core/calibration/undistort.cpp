#include "calibration/undistort.h"

#include <string>

#include "base/error.h"

namespace dp {

Image undistort_image(const Image& photo, const Camera& camera) {
    if (photo.width() != camera.width() || photo.height() != camera.height())
        throw InputError("", "camera",
                         "the camera is for a " + std::to_string(camera.width()) + "x" +
                             std::to_string(camera.height()) + " image, the photo is " +
                             std::to_string(photo.width()) + "x" + std::to_string(photo.height()));
    Image out(photo.width(), photo.height());
    const float w = float(photo.width()), h = float(photo.height());
    for (int y = 0; y < photo.height(); ++y)
        for (int x = 0; x < photo.width(); ++x) {
            const vec2 ideal((float(x) - camera.cx()) / camera.fx(),
                             (float(y) - camera.cy()) / camera.fy());
            const vec2 d = camera.distort(ideal);
            const float sx = camera.fx() * d.x + camera.cx(), sy = camera.fy() * d.y + camera.cy();
            // Inside the photo's pixel edges; bilinear clamps the last half pixel to the border.
            if (sx >= -0.5f && sy >= -0.5f && sx <= w - 0.5f && sy <= h - 0.5f)
                out.at(x, y) = photo.bilinear(sx, sy);
        }
    return out;
}

}  // namespace dp
