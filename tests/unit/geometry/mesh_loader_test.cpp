#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "common/byte_buffers.h"
#include "base/error.h"
#include "geometry/mesh.h"
#include "mesh_checks.h"
#include "../fbx_quad.h"

using namespace dp;
using namespace dp::test;
namespace fs = std::filesystem;

namespace {

bool contains_position(const TriangleMesh& m, const vec3& p) {
    for (const vec3& q : m.positions) {
        if (glm::distance(p, q) < 1e-5f) return true;
    }
    return false;
}

/// Each test writes its files into a fresh directory of its own.
class MeshLoader : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("dp_geometry_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string write(const std::string& name, const std::string& contents) {
        const fs::path p = dir_ / name;
        std::ofstream(p, std::ios::binary) << contents;
        return p.string();
    }

    fs::path dir_;
};

}  // namespace

TEST_F(MeshLoader, LoadsAnObjQuadAsTwoTrianglesWithUvsAndGeneratedNormals) {
    // Counter-clockwise seen from +Y, no normals in the file.
    const std::string path = write("quad.obj",
                                   "v -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\n"
                                   "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                   "f 1/1 2/2 3/3 4/4\n");
    LoadedMesh loaded = load_mesh(path);
    const TriangleMesh& m = loaded.mesh;
    EXPECT_EQ(loaded.dropped_degenerate, 0u);
    ASSERT_EQ(m.triangle_count(), 2u);
    EXPECT_EQ(m.positions.size(), 4u);
    ASSERT_EQ(m.normals.size(), m.positions.size());
    ASSERT_EQ(m.uvs.size(), m.positions.size());
    for (const vec3& n : m.normals) EXPECT_NEAR(glm::dot(n, vec3(0, 1, 0)), 1.0f, 1e-5f);
    EXPECT_GT(min_winding_agreement(m), 0.999f);
    EXPECT_NEAR(surface_area(m), 4.0, 1e-5);
    for (size_t i = 0; i < m.positions.size(); ++i) {
        // The file maps u to +X and v to -Z with v = 0 at the image's bottom; the loaded mesh has
        // v = 0 at the image's top, so its v runs along +Z.
        EXPECT_NEAR(m.uvs[i].x, 0.5f * (m.positions[i].x + 1.0f), 1e-6f);
        EXPECT_NEAR(m.uvs[i].y, 0.5f * (1.0f + m.positions[i].z), 1e-6f);
    }
}

TEST_F(MeshLoader, MergesEveryObjectOfAnObjIntoOneMesh) {
    const std::string path = write("two.obj",
                                   "o first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
                                   "o second\nv 0 0 5\nv 1 0 5\nv 0 1 5\nf 4 5 6\n");
    LoadedMesh loaded = load_mesh(path);
    EXPECT_EQ(loaded.mesh.triangle_count(), 2u);
    EXPECT_TRUE(loaded.mesh.uvs.empty());
    vec3 lo, hi;
    ASSERT_TRUE(loaded.mesh.bounds(lo, hi));
    EXPECT_EQ(lo, vec3(0, 0, 0));
    EXPECT_EQ(hi, vec3(1, 1, 5));
}

TEST_F(MeshLoader, LoadsAnAsciiPlyCubeWithItsQuadsTriangulatedAndWindingKept) {
    const std::string path = write("cube.ply",
                                   "ply\nformat ascii 1.0\nelement vertex 8\n"
                                   "property float x\nproperty float y\nproperty float z\n"
                                   "element face 6\nproperty list uchar int vertex_indices\n"
                                   "end_header\n"
                                   "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                                   "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n"
                                   "4 3 7 6 2\n4 0 4 7 3\n4 1 2 6 5\n");
    LoadedMesh loaded = load_mesh(path);
    const TriangleMesh& m = loaded.mesh;
    EXPECT_EQ(m.triangle_count(), 12u);
    EXPECT_NEAR(surface_area(m), 6.0, 1e-5);
    EXPECT_NEAR(signed_volume(m), 1.0, 1e-5);  // positive: faces still wound outward
    ASSERT_EQ(m.normals.size(), m.positions.size());
    EXPECT_GT(min_winding_agreement(m), 0.0f);
    // Generated smooth normals point roughly away from the cube's centre (area weighting over
    // the triangulated quads tilts them a little off the diagonals).
    for (size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-5f);
        EXPECT_GT(glm::dot(m.normals[i], glm::normalize(m.positions[i] - vec3(0.5f))), 0.9f);
    }
}

TEST_F(MeshLoader, KeepsNormalsGivenInTheFile) {
    // The file's normals deliberately lean away from the face normal; they must survive as given.
    const std::string path = write("normals.obj",
                                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0.6 0 0.8\n"
                                   "f 1//1 2//1 3//1\n");
    LoadedMesh loaded = load_mesh(path);
    ASSERT_EQ(loaded.mesh.normals.size(), 3u);
    for (const vec3& n : loaded.mesh.normals) {
        EXPECT_NEAR(glm::distance(n, vec3(0.6f, 0.0f, 0.8f)), 0.0f, 1e-6f);
    }
}

TEST_F(MeshLoader, AppliesTheNodeTransformsOfAGltfWithAnEmbeddedBuffer) {
    // One triangle in the XZ plane facing +Y. The child node scales x by 2 and rotates 90 degrees
    // about +X (so +Y becomes +Z); its parent translates by (1, 2, 3).
    std::vector<uint8_t> buf;
    append_bytes(buf, std::vector<float>{0, 0, 0, 0, 0, 1, 1, 0, 0});
    append_bytes(buf, std::vector<float>{0, 1, 0, 0, 1, 0, 0, 1, 0});
    append_bytes(buf, std::vector<uint16_t>{0, 1, 2});
    ASSERT_EQ(buf.size(), 78u);
    const std::string gltf = R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [
    {"translation": [1, 2, 3], "children": [1]},
    {"rotation": [0.70710678, 0, 0, 0.70710678], "scale": [2, 1, 1], "mesh": 0}
  ],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
  "buffers": [{"byteLength": 78,
               "uri": "data:application/octet-stream;base64,)" +
                             base64(buf) + R"("}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 72, "target": 34962},
    {"buffer": 0, "byteOffset": 72, "byteLength": 6, "target": 34963}
  ],
  "accessors": [
    {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 0, 1]},
    {"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}
  ]
})";
    LoadedMesh loaded = load_mesh(write("tri.gltf", gltf));
    const TriangleMesh& m = loaded.mesh;
    ASSERT_EQ(m.triangle_count(), 1u);
    EXPECT_EQ(m.positions.size(), 3u);
    EXPECT_TRUE(contains_position(m, vec3(1, 2, 3)));
    EXPECT_TRUE(contains_position(m, vec3(1, 1, 3)));
    EXPECT_TRUE(contains_position(m, vec3(3, 2, 3)));
    ASSERT_EQ(m.normals.size(), 3u);
    for (const vec3& n : m.normals) EXPECT_NEAR(glm::dot(n, vec3(0, 0, 1)), 1.0f, 1e-5f);
    EXPECT_GT(min_winding_agreement(m), 0.999f);
}

TEST_F(MeshLoader, DropsADegenerateTriangleAmongGoodOnesAndCountsIt) {
    const std::string path = write("mixed.obj",
                                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 0 0\n"
                                   "f 1 2 3\nf 2 4 3\nf 1 2 5\n");  // the last one is a line
    LoadedMesh loaded = load_mesh(path);
    EXPECT_EQ(loaded.dropped_degenerate, 1u);
    EXPECT_EQ(loaded.mesh.triangle_count(), 2u);
    EXPECT_NEAR(surface_area(loaded.mesh), 1.0, 1e-6);
    for (const vec3& n : loaded.mesh.normals) {
        EXPECT_TRUE(is_finite(n));
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
    }
}

TEST_F(MeshLoader, RejectsAMeshWhoseTrianglesAreAllDegenerate) {
    const std::string path = write("flat.obj",
                                   "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\n"
                                   "f 1 2 3\nf 2 3 4\n");
    try {
        load_mesh(path, "shapes[0].file");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(path), std::string::npos) << what;
        EXPECT_NE(what.find("degenerate"), std::string::npos) << what;
        EXPECT_NE(what.find("all 2 triangles"), std::string::npos) << what;
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(e.field(), "shapes[0].file");
    }
}

TEST_F(MeshLoader, RejectsAFileWithoutTriangles) {
    const std::string path = write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n");
    try {
        load_mesh(path);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("no triangles"), std::string::npos) << e.what();
    }
}

TEST_F(MeshLoader, ReportsAMissingFileWithItsPath) {
    const std::string path = (dir_ / "does_not_exist.obj").string();
    try {
        load_mesh(path, "mesh");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos);
    }
}

TEST_F(MeshLoader, ReportsGarbageContentAsAnInputError) {
    std::string junk;
    for (int i = 0; i < 512; ++i) junk += char((i * 73 + 11) % 256);
    for (const char* name : {"garbage.ply", "garbage.glb", "garbage.gltf", "garbage.xyz"}) {
        const std::string path = write(name, junk);
        try {
            load_mesh(path);
            ADD_FAILURE() << name << " loaded";
        } catch (const InputError& e) {
            EXPECT_EQ(e.file(), path);
            const std::string expected = std::string(name) == "garbage.ply" ? "malformed PLY header" : "cannot read mesh";
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        }
    }
}

namespace {

const char* const kTetraPlyHeader =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
const char* const kTetraPlyBody = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

std::string input_error_text(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no InputError)";
}

}  // namespace

// Assimp's PLY reader loops forever on these headers; each is refused naming the line.
TEST_F(MeshLoader, RefusesMalformedPlyHeadersNamingTheLine) {
    EXPECT_EQ(load_mesh(write("good.ply", std::string(kTetraPlyHeader) + kTetraPlyBody)).mesh.triangle_count(), 4u);
    const std::pair<std::string, std::string> cases[] = {
        {"ply\nformat ascii 1.0\nelement vertex 4\nelemenrty float x\n", "line 4: unknown keyword \"elemenrty\""},
        {"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nend_heade\n0 0 0\n", "line 5: unknown keyword"},
        {"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n", "no end_header"},
        {"ply\nformat ascii 1.0\nelement vertex four\n", "line 3: expected \"element NAME COUNT\""},
        {"ply\nformat ascii 1.0\nelement vertex 4\nproperty flaot x\nend_header\n", "line 4: expected \"property"},
        {"ply\nelement vertex 4\nproperty float x\nend_header\n", "no format line"},
    };
    for (const auto& [header, expected] : cases) {
        // clang 14 cannot capture a structured binding; a file cut before end_header has no body.
        const std::string text = expected == "no end_header" ? header : header + kTetraPlyBody;
        const std::string message = input_error_text([&] { load_mesh(write("bad.ply", text)); });
        EXPECT_NE(message.find("malformed PLY header"), std::string::npos) << message;
        EXPECT_NE(message.find(expected), std::string::npos) << "expected '" << expected << "' in: " << message;
    }
}

// Assimp's post-processing asserts (and aborts the process) on a face without vertices.
TEST_F(MeshLoader, RefusesAFaceWithoutVertices) {
    const std::string body = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n0\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    const std::string message = input_error_text([&] { load_mesh(write("empty_face.ply", kTetraPlyHeader + body)); });
    EXPECT_NE(message.find("has no vertices"), std::string::npos) << message;
}

// Assimp's MTL reader writes a texture or an anisotropy statement that comes before the file's
// first material through a null pointer; the file is refused, however its lines end or are
// encoded, and a material library that starts with its material still loads.
TEST_F(MeshLoader, RefusesAMaterialLibraryThatSetsAMaterialBeforeNamingOne) {
    const std::string obj = "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
    write("tri.mtl", "# colours\n\nnewmtl red\nKd 1 0 0\nmap_Kd missing.png\n");
    EXPECT_EQ(load_mesh(write("tri.obj", obj)).materials.size(), 1u);
    const std::string padding = "\n# a comment, the reader wants 8 bytes\n";
    const std::string refused[] = {
        "map_Kd red.png", "bump red.png", "disp red.png", "norm red.png", "a 0.5", "# x\rmap_Kd red.png",
        std::string("# x\0norm red.png", 16),                         // NUL ends a line
        "\xEF\xBB\xBFmap_Kd red.png",                                   // a UTF-8 mark is dropped
        std::string("\xFF\xFEn\0e\0w\0m\0t\0l\0 \0a\0\n\0", 20),  // UTF-16: the 'a' is a line
    };
    for (const std::string& mtl : refused) {
        write("tri.mtl", mtl + padding);
        const std::string message = input_error_text([&] { load_mesh(write("tri.obj", obj)); });
        EXPECT_NE(message.find("sets a material before the file's first one"), std::string::npos) << message;
    }
    // An OBJ that names itself as its material library is read as one too.
    const std::string self = "mtllib self.obj\nmap_Kd red.png\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    EXPECT_NE(input_error_text([&] { load_mesh(write("self.obj", self)); }).find("line 2 ('map_"), std::string::npos);
}

// A failed allocation is reported as out of memory; a file whose text merely says so is not.
TEST_F(MeshLoader, AFileQuotingBadAllocIsAnInputErrorNotOutOfMemory) {
    const std::string quote = write("quote.obj", std::string("\0\nvn bad_alloc", 14));
    const std::string message = input_error_text([&] { load_mesh(quote); });
    EXPECT_NE(message.find("cannot read mesh"), std::string::npos) << message;
}

// A glTF buffer is allocated at its declared size: 4 GB declared by a few hundred bytes is refused.
TEST_F(MeshLoader, RefusesGltfBuffersThatDeclareMoreBytesThanTheyHold) {
    const std::string gltf = R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 4294967295,
        "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAA"}]})";
    std::string message = input_error_text([&] { load_mesh(write("huge.gltf", gltf)); });
    EXPECT_NE(message.find("buffers[0] declares 4294967295 bytes but holds"), std::string::npos) << message;

    std::string glb = "glTF";
    auto u32 = [&](uint32_t v) { for (int i = 0; i < 4; ++i) glb += char((v >> (8 * i)) & 255); };
    const std::string json = R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":1000000}]} )";
    u32(2), u32(uint32_t(12 + 8 + json.size() + 8 + 16)), u32(uint32_t(json.size())), u32(0x4E4F534A);
    glb += json;
    u32(16), u32(0x004E4942);
    glb += std::string(16, '\0');
    message = input_error_text([&] { load_mesh(write("huge.glb", glb)); });
    EXPECT_NE(message.find("declares 1000000 bytes but holds 16"), std::string::npos) << message;

    glb.resize(glb.size() - 8);  // the binary chunk now runs past the end
    message = input_error_text([&] { load_mesh(write("cut.glb", glb)); });
    EXPECT_NE(message.find("malformed glTF"), std::string::npos) << message;
}


TEST_F(MeshLoader, AnFbxFileIsBroughtToMetresFromTheUnitItDeclaresAndItsUpAxisIsReported) {
    const std::string metres = test::fbx_quad(dir_, "100", "2");  // 100 cm per unit, Z up
    if (metres.empty()) GTEST_SKIP() << "this Assimp has no FBX exporter";
    LoadedMesh m = load_mesh(write("metres.fbx", metres));
    EXPECT_FLOAT_EQ(m.declared_unit_m, 1.0f);
    EXPECT_EQ(m.declared_up, "z");
    EXPECT_NEAR(m.bounds_hi.x - m.bounds_lo.x, 2.0f, 1e-5f);

    // The same numbers in centimetres: a quad 2 cm wide.
    m = load_mesh(write("centimetres.fbx", test::fbx_quad(dir_, "1", "1")));
    EXPECT_FLOAT_EQ(m.declared_unit_m, 0.01f);
    EXPECT_EQ(m.declared_up, "y");
    EXPECT_NEAR(m.bounds_hi.x - m.bounds_lo.x, 0.02f, 1e-7f);
    EXPECT_NEAR(m.bounds_hi.y - m.bounds_lo.y, 0.01f, 1e-7f);

    const std::string message =
        input_error_text([&] { load_mesh(write("zero.fbx", test::fbx_quad(dir_, "0", "1")), "objects[0].shape.path"); });
    EXPECT_NE(message.find("objects[0].shape.path"), std::string::npos) << message;
    EXPECT_NE(message.find("UnitScaleFactor"), std::string::npos) << message;
}

TEST_F(MeshLoader, GltfIsInMetresAndObjDeclaresNoUnit) {
    EXPECT_EQ(load_mesh(write("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).declared_unit_m, 0.0f);
    EXPECT_EQ(load_mesh(write("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).declared_up, "");
    std::vector<uint8_t> buf;
    append_bytes(buf, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    const std::string gltf = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)" + base64(buf) + R"("}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}]})";
    EXPECT_EQ(load_mesh(write("t.gltf", gltf)).declared_unit_m, 1.0f);
}
