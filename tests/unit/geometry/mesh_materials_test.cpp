// A mesh file's materials as the loader reads them: which triangles use which, their colours,
// and their textures found beside the mesh file or inside it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/byte_buffers.h"
#include "geometry/mesh.h"
#include "image/image_io.h"

using namespace dp;
using namespace dp::test;
namespace fs = std::filesystem;

namespace {

/// A quad (two triangles) in the XY plane, and a second one above it, as a glTF buffer:
/// positions, UVs, then the indices of each quad.
std::string two_quads_buffer() {
    std::vector<uint8_t> buf;
    append_bytes(buf, std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 2, 0, 1, 2, 0});
    append_bytes(buf, std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0, 0, 0, 1, 0});
    append_bytes(buf, std::vector<uint16_t>{0, 1, 2, 0, 2, 3, 3, 2, 5, 3, 5, 4});
    return base64(buf);  // 72 + 48 + 24 = 144 bytes
}

class MeshMaterials : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("dp_mesh_materials_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "models");
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string write(const std::string& name, const std::string& text) {
        const fs::path p = dir_ / name;
        std::ofstream(p, std::ios::binary) << text;
        return p.string();
    }

    /// glTF of two quads with the given materials JSON, the lower quad using material
    /// `lower` and the upper `upper` (-1: none), and the given images and textures.
    std::string gltf(const std::string& materials, int lower, int upper,
                     const std::string& extra = "") {
        auto prim = [](int indices, int material) {
            return R"({"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": )" +
                   std::to_string(indices) +
                   (material >= 0 ? R"(, "material": )" + std::to_string(material)
                                  : std::string()) +
                   "}";
        };
        return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [)" +
               prim(2, lower) + ", " + prim(3, upper) + R"(]}],
            "materials": )" +
               materials + extra + R"(,
            "buffers": [{"byteLength": 144, "uri": "data:application/octet-stream;base64,)" +
               two_quads_buffer() + R"("}],
            "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 72}, {"buffer": 0, "byteOffset": 72, "byteLength": 48},
                            {"buffer": 0, "byteOffset": 120, "byteLength": 12}, {"buffer": 0, "byteOffset": 132, "byteLength": 12}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3", "min": [0, 0, 0], "max": [1, 2, 0]},
                          {"bufferView": 1, "componentType": 5126, "count": 6, "type": "VEC2"},
                          {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"},
                          {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
    }

    fs::path dir_;
};

/// The material index of the triangles whose centroid lies below (lower) or above y = 1.
uint32_t material_at(const TriangleMesh& m, bool upper) {
    uint32_t found = 12345;
    for (size_t i = 0; i < m.triangles.size(); ++i) {
        const glm::uvec3 t = m.triangles[i];
        const float y = (m.positions[t.x].y + m.positions[t.y].y + m.positions[t.z].y) / 3.0f;
        if ((y > 1.0f) != upper) continue;
        EXPECT_TRUE(found == 12345 || found == m.triangle_materials[i])
            << "a quad with two materials";
        found = m.triangle_materials[i];
    }
    return found;
}

}  // namespace

TEST_F(MeshMaterials, AnObjWithAnMtlGivesEachFaceItsMaterialAndFindsTexturesBesideTheMeshFile) {
    // Written on Windows: a backslash in the texture's relative path.
    write("models/chair.mtl",
          "newmtl wood\nKd 0.8 0.8 0.8\nmap_Kd textures\\wood.png\n"
          "newmtl paint\nKd 0.1 0.2 0.7\n");
    const std::string path = write("models/chair.obj",
                                   "mtllib chair.mtl\n"
                                   "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 2 0\nv 1 2 0\n"
                                   "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                   "usemtl wood\nf 1/1 2/2 3/3 4/4\n"
                                   "usemtl paint\nf 4/1 3/2 6/3 5/4\n");
    const LoadedMesh loaded = load_mesh(path);
    ASSERT_TRUE(loaded.has_file_materials());
    ASSERT_EQ(loaded.materials.size(), 2u);
    ASSERT_EQ(loaded.mesh.triangle_materials.size(), loaded.mesh.triangle_count());
    const FileMaterial& wood = loaded.materials[material_at(loaded.mesh, false)];
    const FileMaterial& paint = loaded.materials[material_at(loaded.mesh, true)];
    EXPECT_EQ(wood.name, "wood");
    EXPECT_EQ(wood.texture, (dir_ / "models" / "textures" / "wood.png").string());
    EXPECT_FALSE(wood.texture_times_colour);  // an MTL texture replaces Kd
    EXPECT_EQ(paint.name, "paint");
    EXPECT_EQ(paint.colour, vec3(0.1f, 0.2f, 0.7f));
    EXPECT_EQ(paint.texture, "");
    EXPECT_EQ(paint.metallic, 0.0f);
    EXPECT_EQ(paint.transmission, 0.0f);
}

TEST_F(MeshMaterials, FilesWithoutMaterialsHaveNone) {
    // Assimp's own default material (an OBJ without MTL, every PLY and STL) is no file material.
    const LoadedMesh none = load_mesh(write("none.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    EXPECT_FALSE(none.has_file_materials());
    EXPECT_TRUE(none.mesh.triangle_materials.empty());
    const LoadedMesh ply =
        load_mesh(write("t.ply",
                        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                        "property float y\nproperty float z\nelement face 1\n"
                        "property list uchar int vertex_indices\nend_header\n"
                        "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
    EXPECT_FALSE(ply.has_file_materials());
    const LoadedMesh stl =
        load_mesh(write("t.stl",
                        "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                        "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n"));
    EXPECT_FALSE(stl.has_file_materials());
}

TEST_F(MeshMaterials, AnMtlRoughnessIsReadAndItsAbsenceIsMinusOne) {
    write("m.mtl", "newmtl pbr\nKd 0.8 0.2 0.1\nPr 0.3\nPm 1\nnewmtl plain\nKd 0 0 1\n");
    const LoadedMesh m = load_mesh(write("m.obj",
                                         "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 0 2 0\n"
                                         "usemtl pbr\nf 1 2 3\nusemtl plain\nf 2 4 5\n"));
    ASSERT_EQ(m.materials.size(), 2u);
    const FileMaterial& pbr = m.materials[0].name == "pbr" ? m.materials[0] : m.materials[1];
    const FileMaterial& plain = m.materials[0].name == "pbr" ? m.materials[1] : m.materials[0];
    EXPECT_FLOAT_EQ(pbr.roughness, 0.3f);
    EXPECT_FLOAT_EQ(pbr.metallic, 1.0f);
    EXPECT_EQ(plain.roughness, -1.0f);
}

TEST_F(MeshMaterials, ADroppedDegenerateTriangleTakesItsMaterialWithIt) {
    write("m.mtl", "newmtl a\nKd 1 0 0\nnewmtl b\nKd 0 0 1\n");
    const LoadedMesh m =
        load_mesh(write("m.obj",
                        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 0 2 0\n"
                        "usemtl a\nf 1 2 4\nusemtl b\nf 1 2 3\nf 2 5 3\n"));
    EXPECT_EQ(m.dropped_degenerate, 1u);  // the first face is a line
    ASSERT_EQ(m.mesh.triangle_materials.size(), 2u);
    ASSERT_EQ(m.materials.size(), 1u);  // only b is used
    EXPECT_EQ(m.materials[0].name, "b");
    EXPECT_EQ(m.mesh.triangle_materials[0], 0u);
    EXPECT_EQ(m.mesh.triangle_materials[1], 0u);
}

TEST_F(MeshMaterials, GltfMaterialsKeepTheirBaseColourMetallicTransmissionAndIor) {
    const std::string materials = R"([
        {"name": "chrome", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.8, 1], "metallicFactor": 1,
         "roughnessFactor": 0.25}},
        {"name": "glass", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 1, 0.95, 1], "metallicFactor": 0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 1.33}}}])";
    const LoadedMesh m = load_mesh(
        write("m.gltf",
              gltf(materials, 0, 1,
                   R"(, "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior"])")));
    ASSERT_EQ(m.materials.size(), 2u);
    const FileMaterial& chrome = m.materials[material_at(m.mesh, false)];
    const FileMaterial& glass = m.materials[material_at(m.mesh, true)];
    EXPECT_EQ(chrome.name, "chrome");
    EXPECT_EQ(chrome.metallic, 1.0f);
    EXPECT_EQ(chrome.colour, vec3(0.9f, 0.9f, 0.8f));
    EXPECT_EQ(chrome.transmission, 0.0f);
    EXPECT_EQ(chrome.roughness, 0.25f);
    EXPECT_EQ(glass.roughness, 1.0f);  // glTF's default
    EXPECT_EQ(glass.transmission, 1.0f);
    EXPECT_FLOAT_EQ(glass.ior, 1.33f);
    EXPECT_EQ(glass.colour, vec3(0.9f, 1.0f, 0.95f));
    EXPECT_TRUE(glass.texture_times_colour);
}

TEST_F(MeshMaterials, AGltfPrimitiveWithoutAMaterialHasNoneAndATextureInsideTheFileIsKept) {
    // A 2 x 2 PNG stored in the file as a data URI, as "glTF Embedded" exports hold it.
    save_ldr((dir_ / "t.png").string(), Image(2, 2, vec3(1, 0, 0)));
    std::ifstream png(dir_ / "t.png", std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(png)), {});
    const std::string materials =
        R"([{"name": "painted", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
        "baseColorFactor": [1, 0.5, 0.5, 1], "metallicFactor": 0}}])";
    const std::string extra =
        R"(, "textures": [{"source": 0}], "images": [{"uri": "data:image/png;base64,)" +
        base64(bytes) + R"("}])";
    const LoadedMesh m = load_mesh(write("m.gltf", gltf(materials, 0, -1, extra)));
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_EQ(material_at(m.mesh, true), kNoFileMaterial);
    const FileMaterial& painted = m.materials[material_at(m.mesh, false)];
    EXPECT_EQ(painted.texture, "");
    ASSERT_EQ(painted.embedded_texture, 0);
    ASSERT_EQ(m.embedded_textures.size(), 1u);
    EXPECT_EQ(m.embedded_textures[0].bytes, bytes);
    EXPECT_TRUE(painted.texture_times_colour);
    EXPECT_EQ(painted.colour, vec3(1, 0.5f, 0.5f));
}
