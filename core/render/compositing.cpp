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

/// The catcher of pixel `i`: per channel the light on the real surface with the objects over
/// the light without them; 1 where there is no ratio (a black photo channel, a pixel the objects
/// cover), never negative.
/// `held`, if given, says whether any channel had to be held (no ratio, or a negative one).
vec3 catcher_at(const Image& photo, const Image& alpha, const Image& dL, size_t i, bool* held = nullptr) {
    const float a = coverage(alpha, i);
    vec3 out(1.0f);
    if (held) *held = a >= kFullyCovered;
    if (a >= kFullyCovered) return out;
    for (int c = 0; c < 3; ++c) {
        const float p = photo[i][c];
        const float r = p > 0 ? (p + dL[i][c] / (1.0f - a)) / p : NAN;
        if (held) *held |= !(std::isfinite(r) && r >= 0) && dL[i][c] != 0;
        if (p > 0) out[c] = std::isfinite(r) ? std::max(r, 0.0f) : 1.0f;
    }
    return out;
}

}  // namespace

Image objects_premultiplied(const Image& augmented, const Image& photo, const Image& alpha, const Image& dL) {
    check_sizes(augmented, photo, "the photo");
    check_sizes(augmented, alpha, "alpha");
    check_sizes(augmented, dL, "dL");
    Image out(augmented.width(), augmented.height());
    for (size_t i = 0; i < out.size(); ++i) {
        // What the catcher's plate leaves of the beauty: the recipe gives the beauty back
        // exactly, wherever the catcher had to be held (at 0, or at 1 for lack of a ratio).
        bool held = false;
        const vec3 c = catcher_at(photo, alpha, dL, i, &held);
        const float a = coverage(alpha, i);
        if (a == 0 && !held) continue;  // nothing of the objects: exactly 0
        out[i] = augmented[i] - (1.0f - a) * photo[i] * c;
    }
    return out;
}

Image shadow_catcher(const Image& photo, const Image& alpha, const Image& dL) {
    check_sizes(photo, alpha, "alpha");
    check_sizes(photo, dL, "dL");
    Image out(photo.width(), photo.height());
    for (size_t i = 0; i < out.size(); ++i) out[i] = catcher_at(photo, alpha, dL, i);
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
