#include "assets/material_presets.h"

namespace dp {

namespace {

PrincipledMaterial params(float metallic, float roughness, float specular, float transmission = 0.0f,
                          vec3 emission = vec3(0.0f)) {
    PrincipledMaterial p;
    p.metallic = metallic;
    p.roughness = roughness;
    p.specular = specular;
    p.transmission = transmission;
    p.emission = emission;
    return p;
}

// Metals' colours are their reflectance at normal incidence (linear sRGB), as glTF's metallic
// base colour is: gold (1.00, 0.77, 0.34), steel about 0.56.
const MaterialPreset kPresets[] = {
    {"Plastic", params(0.0f, 0.35f, 1.0f), std::nullopt},
    {"Rubber", params(0.0f, 0.85f, 0.3f), std::nullopt},
    {"Brushed metal", params(1.0f, 0.45f, 1.0f), vec3(0.56f, 0.57f, 0.58f)},
    {"Gold", params(1.0f, 0.25f, 1.0f), vec3(1.0f, 0.766f, 0.336f)},
    {"Ceramic", params(0.0f, 0.12f, 1.0f), std::nullopt},
    {"Frosted glass", params(0.0f, 0.35f, 1.0f, 1.0f), vec3(0.97f)},
    {"Emissive", params(0.0f, 0.5f, 0.5f, 0.0f, vec3(4.0f)), vec3(0.05f)},
};

}  // namespace

std::span<const MaterialPreset> material_presets() { return kPresets; }

Material with_preset(Material m, const MaterialPreset& preset) {
    m.kind = Material::Kind::Principled;
    m.principled = preset.params;
    if (preset.base_colour) {
        m.albedo = Albedo{};
        m.albedo.kind = Albedo::Kind::Constant;
        m.albedo.rgb = *preset.base_colour;
    }
    return m;
}

}  // namespace dp
