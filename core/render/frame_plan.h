#pragma once
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <vector>

#include "base/math.h"
#include "assets/render_scene.h"

namespace dp {

/// Where a pass can have work, computed once per camera and geometry: what each pixel's centre
/// ray sees, and how likely a real pixel's direct-light change needs a ray. Work is organised
/// in tiles so that a pass touches only the tiles the change can reach.
struct FramePlan {
    static constexpr int kTile = 8;  ///< tile edge in pixels
    enum class PixelKind : uint8_t { Nothing, Real, NearVirtual };

    int width = 0, height = 0, tiles_x = 0, tiles_y = 0;
    /// Pixel values below this (a tenth of the photo's mean luminance) count as this much when
    /// a change is judged against a pixel's value: a black pixel's change is measured against
    /// the image, not against zero.
    float value_floor = 0;
    std::vector<PixelKind> kind;  ///< per pixel
    /// Per real pixel: probability that a pass estimates its direct-light change (Russian
    /// roulette on a bound of that change against the pixel's value; 1 near the objects and
    /// wherever a virtual light can reach).
    std::vector<float> direct_probability;
    /// Per real pixel: the radius of a disk as large as the pixel's footprint on the surface its
    /// centre sees. While a pass's gather radius is below it, the pass's photons are splatted
    /// into the pixel (unbiased for the pixel's box filter, and less noisy than a gather over a
    /// smaller disk) instead of gathered by a camera ray.
    std::vector<float> splat_radius;
    std::vector<float> tile_splat_min;       ///< per tile: its real pixels' smallest splat radius
    std::vector<float> tile_direct_max;      ///< per tile: its pixels' largest probability
    std::vector<uint8_t> tile_has_object;    ///< per tile: some pixel is NearVirtual
    std::vector<uint32_t> direct_tiles;      ///< tiles with a probability above 0

    size_t tiles() const { return tile_has_object.size(); }
    int tile_of(int x, int y) const { return (y / kTile) * tiles_x + x / kTile; }
    /// Pixels in the plan with a direct-light probability above 0 and their mean probability:
    /// the expected next-event work of a pass.
    double expected_direct_pixels() const;
};

/// Relative change below which a pixel's direct-light estimate is left to Russian roulette:
/// a pixel whose bound is this fraction of its value is estimated every pass, one whose bound
/// is a tenth of it every tenth pass (with ten times the weight).
inline constexpr float kDirectRouletteLevel = 0.02f;

/// Image area (pixels^2, lens distortion included) per unit of surface area at p with unit
/// normal n, as the camera sees it; 0 where p is behind the camera or seen edge-on.
double pixels_per_area(const Camera& camera, const vec3& p, const vec3& n);

/// A rectangle of pixels, [x0, x1) x [y0, y1): where a viewer needs the render (an edit's
/// region while a slider is dragged), the rest left as the photo.
struct PixelWindow {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
    bool meets_tile(int tile_x, int tile_y, int tile) const {
        return tile_x * tile < x1 && (tile_x + 1) * tile > x0 && tile_y * tile < y1 && (tile_y + 1) * tile > y0;
    }
    size_t area() const { return size_t(std::max(0, x1 - x0)) * size_t(std::max(0, y1 - y0)); }
};

/// Traces one ray through every pixel centre (of `window` only, when given: the pixels outside
/// it are planned as seeing nothing that changes). With `direct_by_rays`, bounds each real pixel's
/// direct-light change (DirectChange::bound) for the roulette; otherwise the probabilities
/// stay 0 (the all-photon estimator has no direct term) but where a virtual light reaches.
/// `cancel` becoming true stops it early: the plan returned is then incomplete (width 0).
FramePlan build_frame_plan(const RenderScene& scene, bool direct_by_rays,
                           const std::atomic<bool>* cancel = nullptr, const PixelWindow* window = nullptr);

}  // namespace dp
