// Textures on meshes from files read the way the artist painted them: a quad whose UVs put
// v = 1 at its top (as Blender exports them) shows the top of its image at its top, through the
// whole pipeline (project file, asset library, scene, renderer).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "assets/asset_library.h"
#include "common/test_scenes.h"
#include "image/image_io.h"
#include "render/progressive.h"
#include "scene/project_io.h"

using namespace dp;
using namespace dp::test;
namespace fs = std::filesystem;

namespace {

const vec3 kRed(1, 0, 0), kBlue(0, 0, 1);

/// Each test writes its files into a fresh folder of its own.
class MeshTexture : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("dp_mesh_texture_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        const Image photo(32, 24, vec3(0.2f)), probe(64, 32, vec3(1.0f));
        save_exr((dir_ / "photo.exr").string(), {{"", &photo}});
        save_exr((dir_ / "probe.exr").string(), {{"", &probe}});
        // 4 x 4 texels: the top half red, the bottom half blue.
        Image texture(4, 4);
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) texture.at(x, y) = y < 2 ? kRed : kBlue;
        save_ldr((dir_ / "red_over_blue.png").string(), texture);
    }
    void TearDown() override { fs::remove_all(dir_); }

    void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }

    /// A project seeing the mesh file `mesh` from +Z, 3 m away, with the red-over-blue texture as
    /// the object's albedo.
    std::string write_project(const std::string& mesh) {
        const std::string text = R"({"schema_version": 1, "photo": {"path": "photo.exr"},
            "probe": {"path": "probe.exr"},
            "camera": {"model": "lookat", "eye": [0, 1, 3], "target": [0, 1, 0], "vfov_deg": 60},
            "objects": [{"name": "quad", "shape": {"type": "mesh", "path": ")" + mesh + R"("},
                         "material": {"type": "diffuse", "albedo": {"texture": "red_over_blue.png"}}}]})";
        write("project.json", text);
        return (dir_ / "project.json").string();
    }

    fs::path dir_;
};

/// The albedo the camera sees through pixel (x, y): the hit surface's texture lookup.
vec3 albedo_seen(const RenderScene& scene, float x, float y) {
    const Hit hit = scene.intersect(scene.camera_ray(x, y));
    EXPECT_TRUE(hit) << "pixel (" << x << ", " << y << ") misses the quad";
    return hit ? hit.surface->reflectance_at(hit.uv) : vec3(-1);
}

bool reddish(const vec3& c) { return c.x > 2.0f * c.z; }
bool bluish(const vec3& c) { return c.z > 2.0f * c.x; }

/// The quad spans y 0.2 to 1.8 m; seen from 3 m with a 60 degree field of view on 24 rows its
/// top lies near row 6.5 and its bottom near row 17.5.
void expect_red_over_blue(const std::string& project_file) {
    const Project project = load_project(project_file);
    AssetLibrary library;
    const auto scene = build_scene(library, project, 0, 0, project_file);
    EXPECT_EQ(albedo_seen(*scene, 15.5f, 8.0f), vec3(0.98f, 0, 0));
    EXPECT_EQ(albedo_seen(*scene, 15.5f, 16.0f), vec3(0, 0, 0.98f));

    // And the render: under a uniform white sky the quad's pixels take its albedo's colour.
    ProgressiveRenderer r(scene, settings(20000, 1));
    for (int i = 0; i < 2; ++i) ASSERT_TRUE(r.render_pass());
    const Image out = r.image();
    for (int x = 12; x <= 19; ++x) {
        EXPECT_TRUE(reddish(out.at(x, 8))) << "pixel (" << x << ", 8): " << out.at(x, 8).x << " " << out.at(x, 8).z;
        EXPECT_TRUE(bluish(out.at(x, 16))) << "pixel (" << x << ", 16): " << out.at(x, 16).x << " " << out.at(x, 16).z;
    }
}

}  // namespace

TEST_F(MeshTexture, AnObjQuadWithBlenderUvsShowsTheTopOfItsTextureAtItsTop) {
    // Counter-clockwise seen from +Z; v = 1 along the top edge, as Blender writes a plane's UVs.
    write("quad.obj",
          "v -1 0.2 0\nv 1 0.2 0\nv 1 1.8 0\nv -1 1.8 0\n"
          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
          "f 1/1 2/2 3/3 4/4\n");
    expect_red_over_blue(write_project("quad.obj"));
}

TEST_F(MeshTexture, AGltfQuadShowsTheTopOfItsTextureAtItsTop) {
    // glTF puts v = 0 at the image's top: the top edge has v = 0 in the file.
    write("quad.gltf", R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2}]}],
        "buffers": [{"byteLength": 92, "uri": "data:application/octet-stream;base64,AACAv83MTD4AAAAAAACAP83MTD4AAAAAAACAP2Zm5j8AAAAAAACAv2Zm5j8AAAAAAAAAAAAAgD8AAIA/AACAPwAAgD8AAAAAAAAAAAAAAAAAAAEAAgAAAAIAAwA="}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                        {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [-1, 0.2, 0], "max": [1, 1.8, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                      {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]})");
    expect_red_over_blue(write_project("quad.gltf"));
}

TEST_F(MeshTexture, ABuiltInPlaneKeepsTheTopOfItsTextureOnItsPlusZEdge) {
    // The layout estimated albedo textures are written in (docs/reconstruction.md): row 0 at
    // v = 0, which make_plane puts on the +Z edge. Stood up by 90 degrees about X, +Z becomes -Y:
    // the image's top row is at the bottom of the card. Loading mesh files must not change this.
    std::string text = R"({"schema_version": 1, "photo": {"path": "photo.exr"},
        "probe": {"path": "probe.exr"},
        "camera": {"model": "lookat", "eye": [0, 1, 3], "target": [0, 1, 0], "vfov_deg": 60},
        "objects": [{"shape": {"type": "plane", "size": [2, 1.6]},
                     "transform": {"translation": [0, 1, 0], "rotation_deg": [90, 0, 0]},
                     "material": {"type": "diffuse", "albedo": {"texture": "red_over_blue.png"}}}]})";
    write("plane.json", text);
    const std::string file = (dir_ / "plane.json").string();
    AssetLibrary library;
    const auto scene = build_scene(library, load_project(file), 0, 0, file);
    EXPECT_EQ(albedo_seen(*scene, 15.5f, 8.0f), vec3(0, 0, 0.98f));
    EXPECT_EQ(albedo_seen(*scene, 15.5f, 16.0f), vec3(0.98f, 0, 0));
}

TEST_F(MeshTexture, AQuadExportedByBlenderShowsTheTopOfItsTextureAtItsTop) {
    if (std::system("blender --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "Blender is not installed";
    // A 2 m plane stood up facing Blender's -Y (the front view), 1 m above the ground, with
    // Blender's own UVs, exported as OBJ and glTF with each exporter's default axes (+Y up).
    const std::string script =
        "import bpy\n"
        "bpy.ops.wm.read_factory_settings(use_empty=True)\n"
        "bpy.ops.mesh.primitive_plane_add(size=2, location=(0, 0, 1), rotation=(1.5707963, 0, 0))\n"
        "bpy.ops.wm.obj_export(filepath=r'" + (dir_ / "blender.obj").string() + "', export_materials=False)\n"
        "bpy.ops.export_scene.gltf(filepath=r'" + (dir_ / "blender.gltf").string() +
        "', export_format='GLTF_SEPARATE')\n";
    write("export.py", script);
    const std::string command =
        "blender -b --factory-startup --python-exit-code 1 -P '" + (dir_ / "export.py").string() + "' > '" +
        (dir_ / "blender.log").string() + "' 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << "see " << (dir_ / "blender.log").string();
    for (const char* mesh : {"blender.obj", "blender.gltf"}) {
        SCOPED_TRACE(mesh);
        expect_red_over_blue(write_project(mesh));
    }
}
