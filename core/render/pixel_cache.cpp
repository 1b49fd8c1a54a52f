#include "render/pixel_cache.h"

#include <tbb/parallel_for.h>

namespace dp {

PixelCache build_pixel_cache(const RenderScene& s) {
    const int W = s.photo().width(), H = s.photo().height();
    const size_t n = size_t(W) * H;
    PixelCache c;
    c.near_virtual.assign(n, 0);
    c.has_real.assign(n, 0);
    c.real_point.assign(n, vec3(0));
    if (!s.has_virtual()) return c;
    std::vector<uint8_t> sees_virtual(n, 0);
    tbb::parallel_for(0, H, [&](int y) {
        for (int x = 0; x < W; ++x) {
            size_t i = size_t(y) * W + x;
            Hit hit = s.intersect(s.camera_ray(float(x), float(y)));
            if (!hit) continue;
            if (hit.surface->is_virtual) {
                sees_virtual[i] = 1;
            } else {
                c.has_real[i] = 1;
                c.real_point[i] = hit.p;
            }
        }
    });
    // Jittered samples may cross an object's edge within one pixel of a centre that sees it.
    tbb::parallel_for(0, H, [&](int y) {
        for (int x = 0; x < W; ++x) {
            uint8_t v = 0;
            for (int dy = -1; dy <= 1 && !v; ++dy)
                for (int dx = -1; dx <= 1 && !v; ++dx) {
                    int xx = x + dx, yy = y + dy;
                    if (xx >= 0 && yy >= 0 && xx < W && yy < H) v = sees_virtual[size_t(yy) * W + xx];
                }
            c.near_virtual[size_t(y) * W + x] = v;
        }
    });
    return c;
}

}  // namespace dp
