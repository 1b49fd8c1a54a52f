#include "image/image.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <string>

#include "base/error.h"
#include "base/text.h"

namespace dp {

Image::Image(int width, int height, vec3 fill) : width_(width), height_(height) {
    const size_t count = size_t(width) * size_t(height);
    try {
        pixels_.assign(count, fill);
    } catch (const std::bad_alloc&) {
        throw OutOfMemory("an image of " + std::to_string(width) + " x " + std::to_string(height) + " pixels (" +
                          format_bytes(double(count) * sizeof(vec3)) + ")");
    }
}

vec3 Image::bilinear(float x, float y) const {
    x = std::clamp(x, 0.0f, float(width_ - 1));
    y = std::clamp(y, 0.0f, float(height_ - 1));
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    int x1 = std::min(x0 + 1, width_ - 1), y1 = std::min(y0 + 1, height_ - 1);
    float fx = x - x0, fy = y - y0;
    vec3 top = glm::mix(at(x0, y0), at(x1, y0), fx);
    vec3 bottom = glm::mix(at(x0, y1), at(x1, y1), fx);
    return glm::mix(top, bottom, fy);
}

Image resample(const Image& image, int width, int height) {
    if (width == image.width() && height == image.height()) return image;
    Image out(width, height);
    const float sx = float(image.width()) / float(width), sy = float(image.height()) / float(height);
    const int taps = std::max(1, int(std::ceil(std::max(sx, sy))));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            vec3 sum(0);
            for (int j = 0; j < taps; ++j)
                for (int i = 0; i < taps; ++i) {
                    const float fx = (x + (i + 0.5f) / taps) * sx - 0.5f;
                    const float fy = (y + (j + 0.5f) / taps) * sy - 0.5f;
                    sum += image.bilinear(fx, fy);
                }
            out.at(x, y) = sum / float(taps * taps);
        }
    return out;
}

size_t replace_non_finite(Image& image) {
    size_t replaced = 0;
    for (size_t i = 0; i < image.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(image[i][c])) {
                image[i][c] = 0.0f;
                ++replaced;
            }
    return replaced;
}

}  // namespace dp
