#include "image/image.h"

#include <algorithm>
#include <cmath>

namespace dp {

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

}  // namespace dp
