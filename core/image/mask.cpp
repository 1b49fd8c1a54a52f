#include "image/mask.h"

namespace dp {

void dilate_mask(std::vector<uint8_t>& mask, int width, int height, int pixels) {
    if (pixels <= 0) return;
    // Separable: rows, then columns (a square structuring element).
    std::vector<uint8_t> tmp(mask.size(), 0);
    for (int y = 0; y < height; ++y) {
        int last = -1 - pixels;  // last set pixel to the left
        for (int x = 0; x < width; ++x) {
            if (mask[size_t(y) * width + x]) last = x;
            tmp[size_t(y) * width + x] = x - last <= pixels;
        }
        last = width + pixels;
        for (int x = width - 1; x >= 0; --x) {
            if (mask[size_t(y) * width + x]) last = x;
            tmp[size_t(y) * width + x] |= last - x <= pixels;
        }
    }
    for (int x = 0; x < width; ++x) {
        int last = -1 - pixels;
        for (int y = 0; y < height; ++y) {
            if (tmp[size_t(y) * width + x]) last = y;
            mask[size_t(y) * width + x] = y - last <= pixels;
        }
        last = height + pixels;
        for (int y = height - 1; y >= 0; --y) {
            if (tmp[size_t(y) * width + x]) last = y;
            mask[size_t(y) * width + x] |= last - y <= pixels;
        }
    }
}

}  // namespace dp
