// A mesh file's materials mapped onto ours, and their textures decoded, from beside the mesh
// file or from inside it.
#include "assets/file_materials.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "assets/asset_library.h"
#include "base/error.h"
#include "image/image_io.h"

using namespace dp;
namespace fs = std::filesystem;

TEST(FileMaterials, AMaterialWithARoughnessIsPrincipledWithEveryFactor) {
    FileMaterial f;
    f.colour = vec3(0.9f, 1.2f, 0.5f);  // out of range: clamped
    f.metallic = 0.7f;
    f.roughness = 0.35f;
    f.transmission = 0.25f;
    f.ior = 1.33f;
    Material m = material_from_file(f);
    EXPECT_EQ(m.kind, Material::Kind::Principled);
    EXPECT_EQ(m.albedo.kind, Albedo::Kind::Constant);
    EXPECT_EQ(m.albedo.rgb, vec3(0.9f, 1.0f, 0.5f));
    EXPECT_EQ(m.principled.metallic, 0.7f);
    EXPECT_EQ(m.principled.roughness, 0.35f);
    EXPECT_EQ(m.principled.transmission, 0.25f);
    EXPECT_EQ(m.principled.ior, 1.33f);
    EXPECT_EQ(m.principled.specular, 1.0f);
    f.ior = 0;  // no KHR_materials_ior
    EXPECT_EQ(material_from_file(f).principled.ior, 1.5f);
    f.ior = 1.0f;  // below the principled range: clamped
    EXPECT_EQ(material_from_file(f).principled.ior, kMinPrincipledIor);
    f.metallic = 2;
    f.roughness = 3;
    m = material_from_file(f, "rust.png");
    EXPECT_EQ(m.principled.metallic, 1.0f);
    EXPECT_EQ(m.principled.roughness, 1.0f);
    EXPECT_EQ(m.albedo.kind, Albedo::Kind::Texture);
    EXPECT_EQ(m.albedo.texture_path, "rust.png");
}

TEST(FileMaterials, WithoutARoughnessTransmissionMakesGlassMetallicAMirrorAndTheRestIsDiffuse) {
    FileMaterial f;
    f.colour = vec3(0.9f, 1.0f, 0.5f);
    f.transmission = 1;
    f.ior = 1.33f;
    Material m = material_from_file(f);
    EXPECT_EQ(m.kind, Material::Kind::Glass);
    EXPECT_EQ(m.ior, 1.33f);
    EXPECT_EQ(m.tint, f.colour);
    f.ior = 0;  // no KHR_materials_ior
    EXPECT_EQ(material_from_file(f).ior, 1.5f);

    f.transmission = 0;
    f.metallic = 0.5f;
    m = material_from_file(f);
    EXPECT_EQ(m.kind, Material::Kind::Mirror);
    EXPECT_EQ(m.reflectance, f.colour);

    f.metallic = 0.49f;
    f.colour = vec3(1.5f, -0.1f, 0.3f);  // out of range: clamped
    m = material_from_file(f);
    EXPECT_EQ(m.kind, Material::Kind::Diffuse);
    EXPECT_EQ(m.albedo.kind, Albedo::Kind::Constant);
    EXPECT_EQ(m.albedo.rgb, vec3(1.0f, 0.0f, 0.3f));
    m = material_from_file(f, "wood.png");
    EXPECT_EQ(m.albedo.kind, Albedo::Kind::Texture);
    EXPECT_EQ(m.albedo.texture_path, "wood.png");
}

namespace {

class FileMaterialAssets : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("dp_file_materials_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        const Image photo(16, 12, vec3(0.5f)), probe(32, 16, vec3(1.0f));
        save_exr((dir_ / "photo.exr").string(), {{"", &photo}});
        save_exr((dir_ / "probe.exr").string(), {{"", &probe}});
        project_.base_dir = dir_;
        project_.photo.path = "photo.exr";
        project_.probe.path = "probe.exr";
    }
    void TearDown() override { fs::remove_all(dir_); }

    void add_mesh(const std::string& path, MaterialSource source) {
        VirtualObject o;
        o.shape.kind = Shape::Kind::Mesh;
        o.shape.mesh_path = path;
        o.material_source = source;
        project_.objects.push_back(o);
    }
    static bool has(const std::vector<std::string>& warnings, const std::string& text) {
        for (const std::string& w : warnings)
            if (w.find(text) != std::string::npos) return true;
        return false;
    }

    fs::path dir_;
    Project project_;
};

}  // namespace

TEST_F(FileMaterialAssets, AnEmbeddedTextureDecodesLikeAFileAndACorruptOneNamesTheMeshFile) {
    save_ldr((dir_ / "t.png").string(), Image(3, 2, vec3(0, 1, 0)));
    std::ifstream png(dir_ / "t.png", std::ios::binary);
    EmbeddedTexture t{"png", std::vector<unsigned char>((std::istreambuf_iterator<char>(png)), {})};
    const Image image = decode_embedded_texture(t, 0, "chair.glb", "objects[0].shape.path");
    ASSERT_EQ(image.width(), 3);
    EXPECT_EQ(image.at(2, 1), vec3(0, 1, 0));

    t.bytes.resize(20);  // cut short
    try {
        decode_embedded_texture(t, 4, "chair.glb", "objects[0].shape.path");
        FAIL() << "a corrupt embedded texture decoded";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind("chair.glb: field 'objects[0].shape.path': embedded texture 4: ", 0),
                  0u)
            << what;
        EXPECT_EQ(what.find("dp_embedded_texture"), std::string::npos)
            << what;  // not the temporary file
    }
    for (const auto& entry : fs::directory_iterator(fs::temp_directory_path()))
        EXPECT_EQ(entry.path().filename().string().rfind(
                      "dp_embedded_texture_" + std::to_string(::getpid()) + "_", 0),
                  std::string::npos)
            << "left behind: " << entry.path();
}

TEST_F(FileMaterialAssets, AnObjectDrawnWithItsFilesMaterialsGetsThemTexturesIncluded) {
    save_ldr((dir_ / "wood.png").string(), Image(2, 2, vec3(1, 0, 0)));
    std::ofstream(dir_ / "m.mtl")
        << "newmtl wood\nKd 0.8 0.8 0.8\nmap_Kd wood.png\nnewmtl lost\nKd 0 0 1\n"
           "map_Kd C:\\Users\\someone\\lost.png\n";
    std::ofstream(dir_ / "m.obj") << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\n"
                                     "usemtl wood\nf 1/1 2/1 3/1\nusemtl lost\nf 2/1 4/1 3/1\n";
    add_mesh("m.obj", MaterialSource::File);
    add_mesh("m.obj", MaterialSource::Project);
    AssetLibrary library;
    const SceneAssets a = library.load(project_);
    ASSERT_EQ(a.object_file_materials.size(), 2u);
    EXPECT_TRUE(a.object_file_materials[1].empty());  // the project's material: nothing loaded
    const auto& parts = a.object_file_materials[0];
    ASSERT_EQ(parts.size(), 2u);
    const FileMaterialAsset& wood = parts[0].name == "wood" ? parts[0] : parts[1];
    const FileMaterialAsset& lost = parts[0].name == "wood" ? parts[1] : parts[0];
    EXPECT_EQ(wood.material.albedo.kind, Albedo::Kind::Texture);
    ASSERT_EQ(wood.texture.width(), 2);
    EXPECT_EQ(wood.texture.at(0, 0), vec3(1, 0, 0));  // the texture replaces Kd in an MTL
    // A texture path from another machine: the colour stands in, and the warning says so.
    EXPECT_EQ(lost.material.albedo.kind, Albedo::Kind::Constant);
    EXPECT_EQ(lost.material.albedo.rgb, vec3(0, 0, 1));
    EXPECT_TRUE(lost.texture.empty());
    EXPECT_TRUE(
        has(a.warnings, "objects[0].shape.path: material 'lost': its texture cannot be read ("));
    EXPECT_TRUE(has(a.warnings, "lost.png"));
    EXPECT_TRUE(has(a.warnings, "); its colour is used"));
}
