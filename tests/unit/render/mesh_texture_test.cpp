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
    /// the object's albedo, or (`file_materials`) with the file's materials over a green one.
    std::string write_project(const std::string& mesh, bool file_materials = false) {
        const std::string material =
            file_materials
                ? R"("material_source": "file", "material": {"type": "diffuse", "albedo": [0, 1, 0]})"
                : R"("material": {"type": "diffuse", "albedo": {"texture": "red_over_blue.png"}})";
        const std::string text = R"({"schema_version": 1, "photo": {"path": "photo.exr"},
            "probe": {"path": "probe.exr"},
            "camera": {"model": "lookat", "eye": [0, 1, 3], "target": [0, 1, 0], "vfov_deg": 60},
            "objects": [{"name": "quad", "shape": {"type": "mesh", "path": ")" +
                                 mesh + R"("}, )" + material + "}]}";
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

namespace {

bool have_blender() {
    return std::system("blender --version > /dev/null 2>&1") == 0;
}

/// Runs Blender on a script that builds a 2 m plane stood up facing Blender's -Y (the front
/// view), 1 m above the ground, with Blender's own UVs and a material whose base colour is the
/// red-over-blue image in `dir`, then runs `export_lines` (each exporter with its default axes,
/// +Y up). False, with Blender's output in `dir`/blender.log, when Blender fails.
bool blender_export(const fs::path& dir, const std::string& export_lines) {
    const std::string script =
        "import bpy\n"
        "bpy.ops.wm.read_factory_settings(use_empty=True)\n"
        "bpy.ops.mesh.primitive_plane_add(size=2, location=(0, 0, 1), rotation=(1.5707963, 0, 0))\n"
        "mat = bpy.data.materials.new('painted')\n"
        "mat.use_nodes = True\n"
        "bsdf = mat.node_tree.nodes['Principled BSDF']\n"
        "tex = mat.node_tree.nodes.new('ShaderNodeTexImage')\n"
        "tex.image = bpy.data.images.load(r'" +
        (dir / "red_over_blue.png").string() +
        "')\n"
        "mat.node_tree.links.new(tex.outputs['Color'], bsdf.inputs['Base Color'])\n"
        "bpy.context.object.data.materials.append(mat)\n" +
        export_lines;
    std::ofstream(dir / "export.py") << script;
    const std::string command = "blender -b --factory-startup --python-exit-code 1 -P '" +
                                (dir / "export.py").string() + "' > '" +
                                (dir / "blender.log").string() + "' 2>&1";
    return std::system(command.c_str()) == 0;
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

}  // namespace

TEST_F(MeshTexture, AQuadExportedByBlenderAsObjShowsTheTopOfItsTextureAtItsTop) {
    if (!have_blender()) GTEST_SKIP() << "Blender is not installed";
    ASSERT_TRUE(blender_export(
        dir_, "bpy.ops.wm.obj_export(filepath=r'" + (dir_ / "blender.obj").string() + "')\n"))
        << read_text(dir_ / "blender.log");
    expect_red_over_blue(write_project("blender.obj"));
    SCOPED_TRACE("with the file's own material and texture");
    expect_red_over_blue(write_project("blender.obj", true));
}

TEST_F(MeshTexture, AQuadExportedByBlenderAsGltfAndGlbShowsTheTopOfItsTextureAtItsTop) {
    if (!have_blender()) GTEST_SKIP() << "Blender is not installed";
    // The glTF image beside the file, and the GLB's inside it.
    const bool exported = blender_export(
        dir_, "bpy.ops.export_scene.gltf(filepath=r'" + (dir_ / "blender.gltf").string() +
                  "', export_format='GLTF_SEPARATE')\n"
                  "bpy.ops.export_scene.gltf(filepath=r'" +
                  (dir_ / "blender.glb").string() + "', export_format='GLB')\n");
    const std::string log = read_text(dir_ / "blender.log");
    // Blender's glTF add-on imports numpy, which a distribution's Blender may lack.
    if (!exported && log.find("No module named") != std::string::npos)
        GTEST_SKIP() << "Blender's glTF exporter cannot run here: "
                     << log.substr(log.find("No module named"), 40);
    ASSERT_TRUE(exported) << log;
    for (const char* mesh : {"blender.gltf", "blender.glb"}) {
        SCOPED_TRACE(mesh);
        expect_red_over_blue(write_project(mesh));
        SCOPED_TRACE("with the file's own material and texture");
        expect_red_over_blue(write_project(mesh, true));
    }
}

TEST_F(MeshTexture, AnObjsOwnMaterialAndTextureAreUsedWhereTheObjectTakesTheFilesMaterials) {
    write("quad.mtl", "newmtl painted\nKd 0.8 0.8 0.8\nmap_Kd red_over_blue.png\n");
    write("quad.obj",
          "mtllib quad.mtl\nv -1 0.2 0\nv 1 0.2 0\nv 1 1.8 0\nv -1 1.8 0\n"
          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
          "usemtl painted\nf 1/1 2/2 3/3 4/4\n");
    auto project = [&](const char* source) {
        const std::string text = R"({"schema_version": 1, "photo": {"path": "photo.exr"},
            "probe": {"path": "probe.exr"},
            "camera": {"model": "lookat", "eye": [0, 1, 3], "target": [0, 1, 0], "vfov_deg": 60},
            "objects": [{"name": "quad", "shape": {"type": "mesh", "path": "quad.obj"},
                         "material_source": ")" +
                                 std::string(source) + R"(",
                         "material": {"type": "diffuse", "albedo": [0, 1, 0]}}]})";
        write(std::string(source) + ".json", text);
        return (dir_ / (std::string(source) + ".json")).string();
    };
    expect_red_over_blue(project("file"));
    // The project's material instead: green all over.
    const std::string file = project("project");
    AssetLibrary library;
    const auto scene = build_scene(library, load_project(file), 0, 0, file);
    EXPECT_EQ(albedo_seen(*scene, 15.5f, 8.0f), vec3(0, 0.98f, 0));
    EXPECT_EQ(albedo_seen(*scene, 15.5f, 16.0f), vec3(0, 0.98f, 0));
}

TEST_F(MeshTexture, AGltfMeshIsDrawnWithItsPrincipledMaterialsAndTheProjectsMaterialWhereItHasNone) {
    // Three quads side by side (x -1.5 to 1.5), facing the camera: chrome, glass, none.
    write("three.gltf", R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0},
                                   {"attributes": {"POSITION": 0}, "indices": 2, "material": 1},
                                   {"attributes": {"POSITION": 0}, "indices": 3}]}],
        "materials": [{"name": "chrome", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 0.7, 1], "metallicFactor": 1}},
                      {"name": "glass", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.8, 1, 1], "metallicFactor": 0},
                       "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                                      "KHR_materials_ior": {"ior": 1.33}}}],
        "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior"],
        "buffers": [{"byteLength": 132, "uri": "data:application/octet-stream;base64,AADAvwAAAD8AAAAAAAAAvwAAAD8AAAAAAAAAPwAAAD8AAAAAAADAPwAAAD8AAAAAAADAvwAAwD8AAAAAAAAAvwAAwD8AAAAAAAAAPwAAwD8AAAAAAADAPwAAwD8AAAAAAAABAAUAAAAFAAQAAQACAAYAAQAGAAUAAgADAAcAAgAHAAYA"}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96}, {"buffer": 0, "byteOffset": 96, "byteLength": 12},
                        {"buffer": 0, "byteOffset": 108, "byteLength": 12}, {"buffer": 0, "byteOffset": 120, "byteLength": 12}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [-1.5, 0.5, 0], "max": [1.5, 1.5, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
                      {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"},
                      {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]})");
    const std::string text =
        R"({"schema_version": 1, "photo": {"path": "photo.exr"}, "probe": {"path": "probe.exr"},
        "camera": {"model": "lookat", "eye": [0, 1, 3], "target": [0, 1, 0], "vfov_deg": 60},
        "objects": [{"shape": {"type": "mesh", "path": "three.gltf"}, "material_source": "file",
                     "material": {"type": "diffuse", "albedo": [0.2, 0.3, 0.4]}}]})";
    write("three.json", text);
    const std::string file = (dir_ / "three.json").string();
    Project project = load_project(file);
    AssetLibrary library;
    const auto scene = build_scene(library, project, 0, 0, file);
    // The quads' centres, x = -1, 0 and 1 at 3 m, are seen at columns 15.5 + x fx / 3 with
    // fx = 12 / tan(30 degrees): 8.6, 15.5 and 22.4.
    auto material_in = [&](const RenderScene& sc, float x) -> Material {
        const Hit hit = sc.intersect(sc.camera_ray(x, 12.0f));
        EXPECT_TRUE(hit);
        return hit ? hit.surface->material : Material{};
    };
    auto material_at = [&](float x) { return material_in(*scene, x); };
    const Material chrome = material_at(8.5f), glass = material_at(15.5f),
                   none = material_at(22.5f);
    // glTF's metallic-roughness material, roughness 1 by glTF's default.
    EXPECT_EQ(chrome.kind, Material::Kind::Principled);
    EXPECT_EQ(chrome.albedo.rgb, vec3(0.9f, 0.8f, 0.7f));
    EXPECT_EQ(chrome.principled.metallic, 1.0f);
    EXPECT_EQ(chrome.principled.roughness, 1.0f);
    EXPECT_EQ(glass.kind, Material::Kind::Principled);
    EXPECT_FLOAT_EQ(glass.principled.ior, 1.33f);
    EXPECT_EQ(glass.principled.transmission, 1.0f);
    EXPECT_EQ(glass.albedo.rgb, vec3(0.6f, 0.8f, 1.0f));
    EXPECT_EQ(none.kind, Material::Kind::Diffuse);
    EXPECT_EQ(none.albedo.rgb, vec3(0.2f, 0.3f, 0.4f));
    EXPECT_TRUE(scene->has_transmissive());  // glass among the parts: photons carry its shadow

    // A material edit (no rebuild) is a new version of the scene that changes the project's
    // triangles only; the version it came from is left as it was.
    project.objects[0].material.albedo.rgb = vec3(0.7f, 0.1f, 0.1f);
    const std::shared_ptr<const RenderScene> edited = scene->with_materials(project);
    EXPECT_EQ(material_in(*edited, 22.5f).albedo.rgb, vec3(0.7f, 0.1f, 0.1f));
    EXPECT_EQ(material_in(*edited, 8.5f).kind, Material::Kind::Principled);
    EXPECT_EQ(material_in(*edited, 15.5f).principled.transmission, 1.0f);
    EXPECT_EQ(material_at(22.5f).albedo.rgb, vec3(0.2f, 0.3f, 0.4f));
    EXPECT_EQ(&edited->assets(), &scene->assets());  // the decoded files are shared, not copied
}
