#pragma once
#include <cstdint>
#include <vector>

#include "assets/render_scene.h"
#include "image/mask.h"

namespace dp {

/// A sphere around an edited virtual object, where it was or where it is now.
struct EditedBounds {
    vec3 center{0};
    float radius = 0;
};

/// How far from an edited object its change is looked for, in multiples of its radius: its
/// contact and sky shadows, ambient occlusion and colour bleeding fade within a few radii.
inline constexpr float kChangeReach = 3.0f;

/// The pixels of `scene`'s image whose render an edit of some virtual objects can change (1)
/// and those it cannot (0), row-major at the scene's resolution. `edited` holds each edited
/// object's sphere before and after the edit; `scene` is the state after it. A pixel can change
/// when its centre ray passes through an edited sphere (what it saw before, or sees now, even
/// where the new scene shows a far surface there), sees any virtual mirror or glass (which may
/// show the edited objects), or meets a surface, real or virtual, within kChangeReach radii of
/// an edited sphere or in the sun's or a virtual light's shadow (or caustic) of one. A viewer that keeps a refined
/// picture replaces only these pixels with a preview.
/// With `step` > 1 one ray is traced per step x step block (through its centre) and the mask
/// is (W + step - 1) / step by (H + step - 1) / step: a viewer needs the region, not its edge
/// to the pixel.
std::vector<uint8_t> change_region(const RenderScene& scene, const std::vector<EditedBounds>& edited,
                                   float reach = kChangeReach, int step = 1);

}  // namespace dp
