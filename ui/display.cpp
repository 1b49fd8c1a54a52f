#include "display.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "image/image_io.h"

namespace dp::ui {

namespace {

constexpr int kLutSize = 4096;

/// 8-bit sRGB code of a linear value in [0, 1], sampled finely enough that neighbouring
/// entries differ by at most one code (the curve is steepest near 0, handled by the table's
/// square-root spacing).
const std::array<uint8_t, kLutSize + 1>& srgb_lut() {
    static const std::array<uint8_t, kLutSize + 1> lut = [] {
        std::array<uint8_t, kLutSize + 1> t{};
        for (int i = 0; i <= kLutSize; ++i) {
            const float u = float(i) / kLutSize;
            t[i] = uint8_t(std::lround(linear_to_srgb(u * u) * 255.0f));
        }
        return t;
    }();
    return lut;
}

inline uint8_t encode(float v) {
    if (!(v > 0)) return 0;  // also NaN
    if (v >= 1) return 255;
    return srgb_lut()[size_t(std::sqrt(v) * kLutSize + 0.5f)];
}

/// Every how many pixels a picture at most `max_width` wide samples `image`.
int stride(const Image& image, int max_width) {
    if (max_width <= 0 || image.width() <= max_width) return 1;
    return (image.width() + max_width - 1) / max_width;
}

}  // namespace

QImage to_display(const Image& image, float exposure, int max_width, const DisplayTransform* view) {
    const int step = stride(image, max_width);
    QImage out(image.width() / step, image.height() / step, QImage::Format_RGB32);
    const float scale = std::exp2(exposure);
    if (view && !view->is_standard()) {
        std::vector<vec3> row_in(size_t(out.width())), row_out(size_t(out.width()));
        for (int y = 0; y < out.height(); ++y) {
            for (int x = 0; x < out.width(); ++x)
                row_in[size_t(x)] = image.at(x * step + step / 2, y * step + step / 2) * scale;
            view->apply(row_in.data(), row_out.data(), row_in.size());
            auto* row = reinterpret_cast<QRgb*>(out.scanLine(y));
            for (int x = 0; x < out.width(); ++x) {
                const vec3 c = row_out[size_t(x)] * 255.0f + 0.5f;
                row[x] = qRgb(int(c.x), int(c.y), int(c.z));
            }
        }
        return out;
    }
    for (int y = 0; y < out.height(); ++y) {
        auto* row = reinterpret_cast<QRgb*>(out.scanLine(y));
        for (int x = 0; x < out.width(); ++x) {
            const vec3 c = image.at(x * step + step / 2, y * step + step / 2) * scale;
            row[x] = qRgb(encode(c.x), encode(c.y), encode(c.z));
        }
    }
    return out;
}

QImage to_false_colour(const Image& delta, float exposure, int max_width) {
    const int step = stride(delta, max_width);
    QImage out(delta.width() / step, delta.height() / step, QImage::Format_RGB32);
    const float scale = std::exp2(exposure);
    for (int y = 0; y < out.height(); ++y) {
        auto* row = reinterpret_cast<QRgb*>(out.scanLine(y));
        for (int x = 0; x < out.width(); ++x) {
            const float d = luminance(delta.at(x * step + step / 2, y * step + step / 2)) * scale;
            const uint8_t m = encode(std::abs(d));
            row[x] = d >= 0 ? qRgb(m, m / 4, 0) : qRgb(0, m / 2, m);
        }
    }
    return out;
}

}  // namespace dp::ui
