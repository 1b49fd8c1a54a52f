// The files a mesh file names besides itself, found from its text: what no output may replace.
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geometry/mesh.h"
#include "geometry/mesh_side_files.h"

using namespace dp;
namespace fs = std::filesystem;

namespace {

class MeshSideFiles : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("dp_mesh_side_files_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "maps");
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string write(const std::string& name, const std::string& text) {
        const fs::path p = dir_ / name;
        std::ofstream(p, std::ios::binary) << text;
        return p.string();
    }

    /// The side files of `mesh`, as names relative to the test folder, sorted.
    std::vector<std::string> names(const std::string& mesh) {
        std::vector<std::string> out;
        for (const MeshSideFile& f : mesh_side_files(mesh))
            out.push_back(f.path.lexically_normal().lexically_relative(dir_).string());
        std::sort(out.begin(), out.end());
        return out;
    }

    fs::path dir_;
};

using Names = std::vector<std::string>;

}  // namespace

TEST_F(MeshSideFiles, AnObjNamesItsMaterialFilesAndTheirTextures) {
    write("wood.png", "x");
    write("maps/bump map.png", "x");
    write("maps/rough.png", "x");
    write("a.mtl",
          "newmtl wood\nmap_Kd -s 1 1 1 -o 0.5 wood.png\nbump -bm 0.3 maps/bump map.png\n"
          "map_Ns maps\\rough.png\nmap_Ka missing.png\n");
    write("b.mtl", "newmtl plain\nKd 1 1 1\n");
    const std::string obj = write("m.obj", "mtllib a.mtl\n  mtllib b.mtl\nv 0 0 0\n");
    EXPECT_EQ(names(obj), (Names{"a.mtl", "b.mtl", "maps/bump map.png", "maps/rough.png", "wood.png"}));
    // What each is, for the messages.
    for (const MeshSideFile& f : mesh_side_files(obj)) {
        if (f.path.filename() == "wood.png") {
            EXPECT_EQ(f.kind, MeshSideFile::Kind::Texture);
            EXPECT_EQ(f.material_file.filename(), "a.mtl");
        }
        if (f.path.extension() == ".mtl") {
            EXPECT_EQ(f.kind, MeshSideFile::Kind::MaterialFile);
        }
    }
}

TEST_F(MeshSideFiles, AMissingMaterialFileFallsBackToTheMeshsName) {
    // Assimp reads "<mesh>.mtl" when the library it is told of cannot be opened.
    write("m.mtl", "newmtl x\nmap_Kd t.png\n");
    write("t.png", "x");
    EXPECT_EQ(names(write("m.obj", "mtllib gone.mtl\nv 0 0 0\n")), (Names{"m.mtl", "t.png"}));
    EXPECT_EQ(names(write("n.obj", "v 0 0 0\n")), Names{}) << "no mtllib, no material file";
}

TEST_F(MeshSideFiles, AGltfNamesItsBuffersAndImagesButNotItsDataUris) {
    write("mesh data.bin", "0123");
    write("maps/albedo.png", "x");
    const std::string gltf = write("m.gltf", R"({"asset": {"version": "2.0"},
        "buffers": [{"uri": "mesh%20data.bin", "byteLength": 4}, {"uri": "data:application/octet-stream;base64,AAAA", "byteLength": 3}],
        "images": [{"uri": "maps/albedo.png"}, {"bufferView": 0, "mimeType": "image/png"}, {"uri": "absent.png"}]})");
    EXPECT_EQ(names(gltf), (Names{"maps/albedo.png", "mesh data.bin"}));
}

// Assimp's JSON reader takes bytes that are not UTF-8 as they are, in a key or in a file name
// written in Latin-1 (Windows); the files such a document names are found all the same.
TEST_F(MeshSideFiles, AGltfThatIsNotUtf8NamesItsFilesByTheirBytes) {
    write("d\xE9" "cor.png", "x");
    write("mesh.bin", "0123");
    const std::string gltf = write("m.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"na\xCBme\": 1,"
                                             " \"buffers\": [{\"uri\": \"mesh.bin\", \"byteLength\": 4}],"
                                             " \"images\": [{\"uri\": \"d\xE9" "cor.png\"}]}");
    EXPECT_EQ(names(gltf), (Names{"d\xE9" "cor.png", "mesh.bin"}));
}

TEST_F(MeshSideFiles, AGlbNamesTheFilesOfItsJsonChunk) {
    write("ext.png", "x");
    std::string json = R"({"asset": {"version": "2.0"}, "images": [{"uri": "ext.png"}]})";
    while (json.size() % 4) json += ' ';
    auto u32 = [](uint32_t v) { return std::string{char(v), char(v >> 8), char(v >> 16), char(v >> 24)}; };
    const std::string glb = "glTF" + u32(2) + u32(uint32_t(20 + json.size())) + u32(uint32_t(json.size())) + "JSON" + json;
    // By content, whatever the extension: Assimp picks the glTF reader for it.
    EXPECT_EQ(names(write("m.bin3d", glb)), Names{"ext.png"});
}

/// A textured OBJ exported by Assimp as binary and ASCII FBX: the texture is listed, and it is
/// the file the mesh loader resolves from the (ASCII) FBX.
TEST_F(MeshSideFiles, AnFbxNamesItsTexturesBinaryOrAscii) {
    write("maps/wood.png", "not decoded here");
    write("t.mtl", "newmtl wood\nKd 1 1 1\nmap_Kd maps/wood.png\n");
    const std::string obj = write("t.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                           "usemtl wood\nf 1/1 2/2 3/3\n");
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(obj, 0);
    ASSERT_TRUE(scene);
    Assimp::Exporter exporter;
    for (const std::string format : {"fbx", "fbxa"}) {
        const fs::path fbx = dir_ / (format + ".fbx");
        if (exporter.Export(scene, format, fbx.string()) != aiReturn_SUCCESS) GTEST_SKIP() << "no FBX exporter";
        EXPECT_EQ(names(fbx.string()), Names{"maps/wood.png"}) << format;
        if (format == "fbx") continue;  // Assimp does not read back the binary FBX it writes
        const LoadedMesh m = load_mesh(fbx.string());
        ASSERT_FALSE(m.materials.empty()) << format;
        EXPECT_EQ(fs::path(m.materials[0].texture).lexically_normal(), (dir_ / "maps/wood.png").lexically_normal()) << format;
    }
}

TEST_F(MeshSideFiles, OtherFormatsAndUnreadableFilesNameNone) {
    EXPECT_TRUE(mesh_side_files(write("m.ply", "ply\nformat ascii 1.0\nend_header\n")).empty());
    EXPECT_TRUE(mesh_side_files(write("broken.gltf", "{not json")).empty());
    EXPECT_TRUE(mesh_side_files((dir_ / "absent.obj").string()).empty());
    EXPECT_TRUE(mesh_side_files(dir_.string()).empty()) << "a folder";
}
