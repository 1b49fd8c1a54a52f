#pragma once
// Named starting points for the principled material (docs/materials.md, "Presets"): what an
// artist picks first, then adjusts.
#include <optional>
#include <span>
#include <string>

#include "scene/project.h"

namespace dp {

/// A principled material by name. Presets that describe a finish, not a substance (plastic,
/// rubber, ceramic), keep the object's colour; the others set it (gold's colour is gold's).
struct MaterialPreset {
    const char* name;
    PrincipledMaterial params;
    std::optional<vec3> base_colour;  ///< linear; none: the object's colour is kept
};

/// Plastic, rubber, brushed metal, gold, ceramic, frosted glass, emissive.
std::span<const MaterialPreset> material_presets();

/// `m` as the principled material `preset` describes; the base colour (albedo) set where the
/// preset has one, a texture then dropped.
Material with_preset(Material m, const MaterialPreset& preset);

}  // namespace dp
