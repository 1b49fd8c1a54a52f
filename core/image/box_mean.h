#pragma once
// Sums and means of a per-pixel value over square boxes, from one integral image.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace dp {

/// The (2 r + 1)^2 box around a pixel, clipped at the image's borders, of a w x h row-major value.
class BoxSums {
public:
    BoxSums(int w, int h, const std::vector<double>& v) : w_(w), h_(h), sum_(size_t(w + 1) * (h + 1), 0.0) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t o = size_t(y + 1) * (w + 1) + x + 1;
                sum_[o] = v[size_t(y) * w + x] + sum_[o - 1] + sum_[o - size_t(w + 1)] - sum_[o - size_t(w + 1) - 1];
            }
    }
    double sum(int x, int y, int r) const {
        const int x0 = std::max(0, x - r), y0 = std::max(0, y - r);
        const int x1 = std::min(w_, x + r + 1), y1 = std::min(h_, y + r + 1);
        return at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
    }
    double mean(int x, int y, int r) const {
        const int x0 = std::max(0, x - r), y0 = std::max(0, y - r);
        const int x1 = std::min(w_, x + r + 1), y1 = std::min(h_, y + r + 1);
        return sum(x, y, r) / double((x1 - x0) * (y1 - y0));
    }

private:
    double at(int x, int y) const { return sum_[size_t(y) * (w_ + 1) + x]; }
    int w_, h_;
    std::vector<double> sum_;
};

}  // namespace dp
