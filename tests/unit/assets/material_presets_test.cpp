// The principled material's presets: each a material the project format takes, as named.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "assets/material_presets.h"
#include "scene/project_io.h"

using namespace dp;

namespace {

/// A project with one sphere of material `m`, written and read back as a file would be.
Material round_trip(const Material& m) {
    Project p;
    p.photo.path = "photo.exr";
    p.probe.path = "probe.exr";
    VirtualObject o;
    o.name = "ball";
    o.shape.kind = Shape::Kind::Sphere;
    o.material = m;
    p.objects.push_back(o);
    return parse_project(to_json(p), "presets.json", ".").objects.at(0).material;
}

}  // namespace

TEST(MaterialPresets, EachIsAPrincipledMaterialTheFormatTakesAsItIs) {
    std::set<std::string> names;
    for (const MaterialPreset& preset : material_presets()) {
        Material before;
        before.albedo.rgb = vec3(0.2f, 0.4f, 0.6f);
        const Material m = with_preset(before, preset);
        EXPECT_EQ(m.kind, Material::Kind::Principled) << preset.name;
        EXPECT_EQ(round_trip(m), m) << preset.name;  // every value within the format's ranges
        EXPECT_EQ(m.albedo.rgb, preset.base_colour.value_or(before.albedo.rgb)) << preset.name;
        names.insert(preset.name);
    }
    for (const char* wanted : {"Plastic", "Rubber", "Brushed metal", "Gold", "Ceramic", "Frosted glass", "Emissive"})
        EXPECT_TRUE(names.count(wanted)) << wanted;
}

TEST(MaterialPresets, TheyAreWhatTheirNamesSay) {
    auto find = [](const std::string& name) {
        for (const MaterialPreset& p : material_presets())
            if (name == p.name) return p;
        ADD_FAILURE() << name;
        return material_presets()[0];
    };
    EXPECT_EQ(find("Gold").params.metallic, 1.0f);
    EXPECT_GT(find("Gold").base_colour->x, find("Gold").base_colour->z);  // yellow
    EXPECT_EQ(find("Frosted glass").params.transmission, 1.0f);
    EXPECT_GT(find("Frosted glass").params.roughness, 0.2f);  // frosted, not clear
    EXPECT_GT(find("Rubber").params.roughness, find("Plastic").params.roughness);
    EXPECT_LT(find("Ceramic").params.roughness, find("Plastic").params.roughness);  // glazed
    EXPECT_GT(luminance(find("Emissive").params.emission), 0.0f);
    for (const char* dielectric : {"Plastic", "Rubber", "Ceramic", "Frosted glass"})
        EXPECT_EQ(find(dielectric).params.metallic, 0.0f) << dielectric;
}

TEST(MaterialPresets, AColourPresetReplacesATexture) {
    Material textured;
    textured.albedo.kind = Albedo::Kind::Texture;
    textured.albedo.texture_path = "wood.png";
    const MaterialPreset* gold = nullptr;
    const MaterialPreset* plastic = nullptr;
    for (const MaterialPreset& p : material_presets()) {
        if (std::string(p.name) == "Gold") gold = &p;
        if (std::string(p.name) == "Plastic") plastic = &p;
    }
    ASSERT_TRUE(gold && plastic);
    EXPECT_EQ(with_preset(textured, *gold).albedo.kind, Albedo::Kind::Constant);
    EXPECT_EQ(with_preset(textured, *plastic).albedo.texture_path, "wood.png");  // a finish keeps it
}
