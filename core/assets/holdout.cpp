#include "assets/holdout.h"

#include <algorithm>
#include <cmath>

#include "base/math.h"

namespace dp {

HoldoutMask HoldoutMask::from_image(const Image& mask, float depth) {
    HoldoutMask h;
    h.width = mask.width();
    h.height = mask.height();
    h.depth = depth;
    h.covered.resize(mask.size());
    for (size_t i = 0; i < mask.size(); ++i) h.covered[i] = luminance(mask[i]) >= 0.5f;
    return h;
}

bool HoldoutMask::covers(float u, float v) const {
    if (!(u >= 0 && u < 1 && v >= 0 && v < 1) || covered.empty()) return false;
    const int x = std::min(int(u * float(width)), width - 1), y = std::min(int(v * float(height)), height - 1);
    return covered[size_t(y) * size_t(width) + size_t(x)] != 0;
}

double HoldoutMask::coverage() const {
    if (covered.empty()) return 0;
    return double(std::count(covered.begin(), covered.end(), uint8_t(1))) / double(covered.size());
}

}  // namespace dp
