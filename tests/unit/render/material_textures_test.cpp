// A glTF material's metallic-roughness texture and normal map, through the whole pipeline
// (mesh file, asset library, scene): the roughness and metallic a hit gets, and the shading
// normal a normal map bends, in the directions glTF defines (+X along u, +Y to the top of the
// image), whichever way the triangles wind.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "assets/asset_library.h"
#include "assets/principled_scatter.h"
#include "base/error.h"
#include "common/byte_buffers.h"
#include "image/image_io.h"
#include "scene/project_io.h"

using namespace dp;
using namespace dp::test;
namespace fs = std::filesystem;

namespace {

/// The linear value that save_ldr's sRGB encoding writes as 8-bit `code`.
float linear_for_code(int code) {
    const double c = code / 255.0;
    return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

/// A texel whose stored codes are `c` (0..255 each), for data textures read as linear.
vec3 codes(int r, int g, int b) { return vec3(linear_for_code(r), linear_for_code(g), linear_for_code(b)); }

/// A quad facing +Z (x -1..1, y 0.2..1.8), glTF UVs (v = 0 along its top edge), wound
/// counter-clockwise seen from +Z, or clockwise when `reversed`; with normals along +Z.
std::string quad_buffer(bool reversed) {
    std::vector<uint8_t> buf;
    append_bytes(buf, std::vector<float>{-1, 0.2f, 0, 1, 0.2f, 0, 1, 1.8f, 0, -1, 1.8f, 0});
    append_bytes(buf, std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});
    append_bytes(buf, std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0});
    append_bytes(buf, reversed ? std::vector<uint16_t>{0, 2, 1, 0, 3, 2} : std::vector<uint16_t>{0, 1, 2, 0, 2, 3});
    return base64(buf);  // 48 + 48 + 32 + 12 = 140 bytes
}

class MaterialTextures : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("dp_material_textures_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        const Image photo(32, 24, vec3(0.2f)), probe(64, 32, vec3(1.0f));
        save_exr((dir_ / "photo.exr").string(), {{"", &photo}});
        save_exr((dir_ / "probe.exr").string(), {{"", &probe}});
    }
    void TearDown() override { fs::remove_all(dir_); }

    /// Writes a 4 x 4 PNG whose left half holds codes `left` and right half `right`.
    void write_png(const std::string& name, const vec3& left, const vec3& right) {
        Image t(4, 4);
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) t.at(x, y) = x < 2 ? left : right;
        save_ldr((dir_ / name).string(), t);
    }

    /// The scene of a project seeing the quad, with a principled material (metallic 1, roughness
    /// 0.8) using metallic-roughness texture `mr` and normal map `normal` ("" for none).
    std::shared_ptr<RenderScene> scene(const std::string& mr, const std::string& normal, bool reversed = false,
                                       float normal_scale = 1) {
        // Texture k shows image k; the metallic-roughness texture comes first.
        std::string textures, images, pbr_slot, normal_slot;
        int n = 0;
        auto add = [&](const std::string& file) {
            textures += std::string(n ? ", " : "") + R"({"source": )" + std::to_string(n) + "}";
            images += std::string(n ? ", " : "") + R"({"uri": ")" + file + R"("})";
            return std::to_string(n++);
        };
        if (!mr.empty()) pbr_slot = R"(, "metallicRoughnessTexture": {"index": )" + add(mr) + "}";
        if (!normal.empty())
            normal_slot = R"(, "normalTexture": {"index": )" + add(normal) + R"(, "scale": )" +
                          std::to_string(normal_scale) + "}";
        const std::string material =
            R"({"name": "painted", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1],
            "metallicFactor": 1, "roughnessFactor": 0.8)" + pbr_slot + "}" + normal_slot + "}";
        std::ofstream(dir_ / "quad.gltf") << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
            "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
            "materials": [)" << material << "]"
                                         << (n ? R"(, "textures": [)" + textures + R"(], "images": [)" + images + "]"
                                               : std::string())
                                         << R"(,
            "buffers": [{"byteLength": 140, "uri": "data:application/octet-stream;base64,)"
                                         << quad_buffer(reversed) << R"("}],
            "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                            {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0.2, 0], "max": [1, 1.8, 0]},
                          {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                          {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
                          {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
        std::ofstream(dir_ / "project.json") << R"({"schema_version": 1, "photo": {"path": "photo.exr"},
            "probe": {"path": "probe.exr"},
            "camera": {"model": "lookat", "eye": [0, 1, 3], "target": [0, 1, 0], "vfov_deg": 60},
            "objects": [{"name": "quad", "shape": {"type": "mesh", "path": "quad.gltf"}, "material_source": "file",
                         "material": {"type": "diffuse", "albedo": [0, 1, 0]}}]})";
        const std::string file = (dir_ / "project.json").string();
        return build_scene(library_, load_project(file), 0, 0, file);
    }

    fs::path dir_;
    AssetLibrary library_;
};

/// The hit through pixel (x, 12) (the quad spans columns ~9 to ~22 at row 12).
Hit hit_at(const RenderScene& scene, float x) {
    const Hit hit = scene.intersect(scene.camera_ray(x, 12.0f));
    EXPECT_TRUE(hit && hit.surface->is_virtual) << "column " << x << " misses the quad";
    return hit;
}

}  // namespace

TEST_F(MaterialTextures, GreenScalesRoughnessAndBlueScalesMetallicPerTexel) {
    // Left half: roughness 0.8 x 0.25, metallic 1 x 1; right half: roughness 0.8 x 1, metallic 0.
    write_png("mr.png", codes(0, 64, 255), codes(0, 255, 0));
    const auto s = scene("mr.png", "");
    ASSERT_TRUE(s->assets().warnings.empty()) << s->assets().warnings.front();
    const Hit left = hit_at(*s, 11.0f), right = hit_at(*s, 20.0f);
    const PrincipledParams l = principled_at(*left.surface, left).params();
    const PrincipledParams r = principled_at(*right.surface, right).params();
    EXPECT_NEAR(l.roughness, 0.8f * 64 / 255, 0.01f);
    EXPECT_NEAR(l.metallic, 1.0f, 0.01f);
    EXPECT_NEAR(r.roughness, 0.8f, 0.01f);
    EXPECT_NEAR(r.metallic, 0.0f, 0.01f);
    // Without the texture, the factors alone.
    const auto plain = scene("", "");
    const Hit p = hit_at(*plain, 11.0f);
    EXPECT_NEAR(principled_at(*p.surface, p).params().roughness, 0.8f, 1e-6f);
    EXPECT_NEAR(principled_at(*p.surface, p).params().metallic, 1.0f, 1e-6f);
}

TEST_F(MaterialTextures, ANormalMapTiltsTheShadingNormalTowardsPlusUAndTheTopOfTheImage) {
    // Left half tilted towards +X of the map (+u: world +x), right half towards +Y (the top of
    // the image, which glTF's v = 0 puts at the quad's top: world +y). sin 30 = 0.5 -> code 191.
    const int tilt = 191, flat = 128, up = int(std::lround((0.5 + 0.5 * std::cos(M_PI / 6)) * 255));
    write_png("n.png", codes(tilt, flat, up), codes(flat, tilt, up));
    for (bool reversed : {false, true}) {
        SCOPED_TRACE(reversed ? "triangles wound clockwise" : "triangles wound counter-clockwise");
        const auto s = scene("", "n.png", reversed);
        ASSERT_TRUE(s->assets().warnings.empty()) << s->assets().warnings.front();
        const Hit left = hit_at(*s, 11.0f), right = hit_at(*s, 20.0f);
        // ns stays on ng's side, as every hit's does; its tilt is what the map says.
        for (const Hit* h : {&left, &right}) EXPECT_GT(glm::dot(h->ns, h->ng), 0.0f);
        const vec3 l = glm::dot(left.ng, vec3(0, 0, 1)) > 0 ? left.ns : -left.ns;
        const vec3 r = glm::dot(right.ng, vec3(0, 0, 1)) > 0 ? right.ns : -right.ns;
        EXPECT_NEAR(l.x, 0.5f, 0.02f);
        EXPECT_NEAR(l.y, 0.0f, 0.02f);
        EXPECT_NEAR(r.x, 0.0f, 0.02f);
        EXPECT_NEAR(r.y, 0.5f, 0.02f);
        EXPECT_NEAR(glm::length(l), 1.0f, 1e-4f);
    }
    // The scale multiplies X and Y: at 0 the map is flat.
    const auto flat_scene = scene("", "n.png", false, 0.0f);
    const Hit f = hit_at(*flat_scene, 11.0f);
    EXPECT_NEAR(std::abs(f.ns.z), 1.0f, 1e-5f);
}

TEST_F(MaterialTextures, AMissingTextureIsIgnoredWithAWarningNamingTheMaterialAndTheSlot) {
    const auto s = scene("gone.png", "");
    const auto& w = s->assets().warnings;
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("material 'painted': its metallic-roughness texture cannot be read"), std::string::npos)
        << w[0];
    const Hit h = hit_at(*s, 11.0f);
    EXPECT_NEAR(principled_at(*h.surface, h).params().roughness, 0.8f, 1e-6f);
}

TEST_F(MaterialTextures, AProjectsPrincipledMaterialTakesBothTexturesOnASphereAndAMesh) {
    // Uniform maps: roughness 0.8 x 0.25 and metallic 0; a tilt of 30 degrees towards +Y.
    write_png("mr.png", codes(0, 64, 0), codes(0, 64, 0));
    const int tilt = 191, flat = 128, up = int(std::lround((0.5 + 0.5 * std::cos(M_PI / 6)) * 255));
    write_png("n.png", codes(flat, tilt, up), codes(flat, tilt, up));
    scene("", "");  // writes quad.gltf
    auto project = [&](const std::string& shape, const char* y) {
        std::ofstream(dir_ / "own.json") << R"({"schema_version": 1, "photo": {"path": "photo.exr"},
            "probe": {"path": "probe.exr"},
            "camera": {"model": "lookat", "eye": [0, 1, 3], "target": [0, 1, 0], "vfov_deg": 60},
            "objects": [{"name": "thing", "shape": )" + shape + R"(, "transform": {"translation": [0, )" + y + R"(, 0]},
                         "material": {"type": "principled", "metallic": 1, "roughness": 0.8,
                                      "metallic_roughness_texture": "mr.png", "normal_texture": "n.png"}}]})";
        const std::string file = (dir_ / "own.json").string();
        return build_scene(library_, load_project(file), 0, 0, file);
    };
    for (const auto& [shape, y] : {std::pair{R"({"type": "sphere", "radius": 0.6})", "1"},
                                   std::pair{R"({"type": "mesh", "path": "quad.gltf"})", "0"}}) {
        SCOPED_TRACE(shape);
        const auto s = project(shape, y);
        // The middle of the view: the sphere's point facing the camera, or the quad's middle.
        const Hit h = s->intersect(s->camera_ray(15.5f, 12.0f));
        ASSERT_TRUE(h && h.surface->is_virtual);
        const PrincipledParams p = principled_at(*h.surface, h).params();
        EXPECT_NEAR(p.roughness, 0.8f * 64 / 255, 0.01f);
        EXPECT_NEAR(p.metallic, 0.0f, 0.01f);
        // 30 degrees off the surface's normal, towards the top of the texture: up the sphere's
        // meridian, up the quad.
        const vec3 ng = glm::dot(h.ng, vec3(0, 0, 1)) > 0 ? h.ng : -h.ng;
        const vec3 n = glm::dot(h.ng, vec3(0, 0, 1)) > 0 ? h.ns : -h.ns;
        EXPECT_NEAR(glm::dot(n, ng), std::cos(M_PI / 6), 0.01);
        const vec3 tilt = n - ng * glm::dot(n, ng);
        EXPECT_NEAR(glm::length(tilt), 0.5f, 0.01f);
        EXPECT_GT(tilt.y, 0.49f);
        EXPECT_NEAR(tilt.x, 0.0f, 0.02f);
    }
}

TEST_F(MaterialTextures, AProjectTextureThatCannotBeReadIsAnErrorNamingItsField) {
    std::ofstream(dir_ / "bad.json") << R"({"schema_version": 1, "photo": {"path": "photo.exr"},
        "probe": {"path": "probe.exr"},
        "camera": {"model": "lookat", "eye": [0, 1, 3], "target": [0, 1, 0], "vfov_deg": 60},
        "objects": [{"shape": {"type": "sphere", "radius": 0.5},
                     "material": {"type": "principled", "normal_texture": "gone.png"}}]})";
    const std::string file = (dir_ / "bad.json").string();
    try {
        build_scene(library_, load_project(file), 0, 0, file);
        FAIL() << "a missing normal map was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("objects[0].material.normal_texture"), std::string::npos) << e.what();
    }
}
