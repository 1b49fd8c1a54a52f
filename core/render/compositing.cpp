#include "render/compositing.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dp {

namespace {

constexpr float kFullyCovered = 0.999f;

void check_sizes(const Image& a, const Image& b, const char* what) {
    if (a.width() != b.width() || a.height() != b.height())
        throw std::invalid_argument(std::string("compositing: ") + what + " differs in size");
}

float coverage(const Image& alpha, size_t i) { return std::clamp(alpha[i].x, 0.0f, 1.0f); }

}  // namespace

Image objects_premultiplied(const Image& augmented, const Image& photo, const Image& alpha, const Image& dL) {
    check_sizes(augmented, photo, "the photo");
    check_sizes(augmented, alpha, "alpha");
    check_sizes(augmented, dL, "dL");
    Image out(augmented.width(), augmented.height());
    for (size_t i = 0; i < out.size(); ++i) {
        const float a = coverage(alpha, i);
        if (a == 0) continue;
        const vec3 v = augmented[i] - (1.0f - a) * photo[i] - dL[i];
        // The objects' light is never negative; noise in dL can make the difference so.
        out[i] = glm::max(v, vec3(0.0f));
    }
    return out;
}

Image shadow_catcher(const Image& photo, const Image& alpha, const Image& dL) {
    check_sizes(photo, alpha, "alpha");
    check_sizes(photo, dL, "dL");
    Image out(photo.width(), photo.height(), vec3(1.0f));
    for (size_t i = 0; i < out.size(); ++i) {
        const float a = coverage(alpha, i);
        if (a >= kFullyCovered) continue;
        for (int c = 0; c < 3; ++c) {
            const float p = photo[i][c];
            if (!(p > 0)) continue;
            const float r = (p + dL[i][c] / (1.0f - a)) / p;
            out[i][c] = std::isfinite(r) ? std::max(r, 0.0f) : 1.0f;
        }
    }
    return out;
}

Image recomposite(const Image& objects, const Image& alpha, const Image& photo, const Image& catcher) {
    check_sizes(objects, alpha, "alpha");
    check_sizes(objects, photo, "the photo");
    check_sizes(objects, catcher, "the catcher");
    Image out(objects.width(), objects.height());
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = objects[i] + (1.0f - coverage(alpha, i)) * photo[i] * catcher[i];
    return out;
}

}  // namespace dp
