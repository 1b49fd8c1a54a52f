// A mesh whose size once placed looks off by a unit mix-up is said, with the unit_scale that
// fixes it; sizes an object in a photograph can have are not.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "assets/asset_library.h"
#include "assets/mesh_units.h"
#include "image/image_io.h"
#include "../fbx_quad.h"

using namespace dp;
namespace fs = std::filesystem;

namespace {

Shape mesh_shape(UpAxis up = UpAxis::Y, float unit_scale = 1.0f) {
    Shape s;
    s.kind = Shape::Kind::Mesh;
    s.mesh_path = "m.obj";
    s.up_axis = up;
    s.unit_scale = unit_scale;
    return s;
}

/// A fresh folder `dir` holding a flat photo and probe, and a project in it naming them.
Project project_in(const fs::path& dir) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    const Image photo(16, 12, vec3(0.5f)), probe(32, 16, vec3(1.0f));
    save_exr((dir / "photo.exr").string(), {{"", &photo}});
    save_exr((dir / "probe.exr").string(), {{"", &probe}});
    Project p;
    p.base_dir = dir;
    p.photo.path = "photo.exr";
    p.probe.path = "probe.exr";
    return p;
}

}  // namespace

TEST(MeshUnits, ThePlacedSizeTakesTheUnitTheAxesAndTheTransformsScaleButNotItsRotation) {
    const vec3 lo(0, 0, 0), hi(2, 1, 30);  // 30 units along the file's z
    Transform t;
    EXPECT_FLOAT_EQ(placed_mesh_size(lo, hi, mesh_shape(), t), 30.0f);
    EXPECT_FLOAT_EQ(placed_mesh_size(lo, hi, mesh_shape(UpAxis::Z, 0.01f), t), 0.3f);
    t.scale = vec3(1, 50, 1);  // the file's z is the shape's y once turned: 0.3 * 50
    EXPECT_FLOAT_EQ(placed_mesh_size(lo, hi, mesh_shape(UpAxis::Z, 0.01f), t), 15.0f);
    t.rotation_deg = vec3(0, 0, 90);
    EXPECT_FLOAT_EQ(placed_mesh_size(lo, hi, mesh_shape(UpAxis::Z, 0.01f), t), 15.0f);
}

TEST(MeshUnits, SizesOfThingsInPhotographsAreNotSaid) {
    for (float size : {0.01f, 0.05f, 1.0f, 12.0f, 100.0f})
        EXPECT_EQ(mesh_size_warning("objects[0].shape.unit_scale", "chair", size, 1.0f), "") << size;
}

TEST(MeshUnits, ALargeMeshIsSaidToBeInCentimetresOrMillimetresWhicheverGivesAboutAMetre) {
    EXPECT_EQ(mesh_size_warning("objects[1].shape.unit_scale", "chair", 215.0f, 1.0f),
              "objects[1].shape.unit_scale: 'chair' is 215 m across once placed: its file looks like "
              "centimetres: set unit_scale 0.01");
    EXPECT_EQ(mesh_size_warning("objects[1].shape.unit_scale", "", 900.0f, 1.0f),
              "objects[1].shape.unit_scale: the mesh is 900 m across once placed: its file looks like "
              "millimetres: set unit_scale 0.001");
    // With a unit already set, the factor applies to it.
    EXPECT_EQ(mesh_size_warning("real[0].shape.unit_scale", "table", 150.0f, 0.1f),
              "real[0].shape.unit_scale: 'table' is 150 m across once placed: it looks 100 times too large: "
              "set unit_scale 0.001");
}

TEST(MeshUnits, ASmallMeshIsSaidToBe100Or1000TimesTooSmall) {
    EXPECT_EQ(mesh_size_warning("objects[0].shape.unit_scale", "cup", 0.0012f, 0.001f),
              "objects[0].shape.unit_scale: 'cup' is 0.0012 m across once placed: it looks 1000 times too small: "
              "set unit_scale 1");
    EXPECT_EQ(mesh_size_warning("objects[0].shape.unit_scale", "cup", 0.005f, 0.01f),
              "objects[0].shape.unit_scale: 'cup' is 0.005 m across once placed: it looks 100 times too small: "
              "set unit_scale 1");
}

TEST(MeshUnits, TheAssetLibrarySaysItForObjectsAndProxiesOnEveryLoad) {
    const fs::path dir = fs::temp_directory_path() / ("dp_mesh_units_" + std::to_string(::getpid()));
    Project p = project_in(dir);
    // A triangle 180 units across: a 1.8 m thing modelled in centimetres.
    std::ofstream(dir / "m.obj") << "v 0 0 0\nv 180 0 0\nv 0 90 0\nf 1 2 3\n";
    VirtualObject o;
    o.name = "statue";
    o.shape = mesh_shape();
    p.objects.push_back(o);
    RealProxy r;
    r.shape = mesh_shape(UpAxis::Y, 0.01f);
    p.real.push_back(r);

    AssetLibrary library;
    auto said = [&](const std::string& text) {
        for (const std::string& w : library.warnings(p))
            if (w.find(text) != std::string::npos) return true;
        return false;
    };
    EXPECT_TRUE(said("objects[0].shape.unit_scale: 'statue' is 180 m across once placed: its file looks like "
                     "centimetres: set unit_scale 0.01"));
    EXPECT_FALSE(said("real[0]"));  // 1.8 m
    // The same mesh file, cached, scaled down by its transform: no longer said.
    p.objects[0].transform.scale = vec3(0.01f);
    EXPECT_FALSE(said("statue"));
    p.real[0].shape.unit_scale = 0.00001f;
    EXPECT_TRUE(said("real[0].shape.unit_scale: the mesh is 0.0018 m across once placed: it looks 1000 times "
                     "too small: set unit_scale 0.01"));
    fs::remove_all(dir);
}

TEST(MeshUnits, AMeshTooLargeOrSmallForItsPlaceInTheViewIsSaid) {
    // A 30 cm vase modelled in centimetres: 30 m, within what things can be, but on a desk 1.2 m
    // from the camera, where the view is about 1 m wide.
    EXPECT_EQ(mesh_view_warning("f", "vase", 0.3f, 1.0f, 1.0f), "");
    EXPECT_EQ(mesh_view_warning("objects[0].shape.unit_scale", "vase", 30.0f, 1.0f, 1.04f),
              "objects[0].shape.unit_scale: 'vase' is 30 m across once placed, 29 times the view's width at its "
              "distance (1.04 m): its file looks like centimetres: set unit_scale 0.01");
    EXPECT_EQ(mesh_view_warning("f", "pin", 0.0003f, 1.0f, 1.0f),
              "f: 'pin' is 0.0003 m across once placed, 1/3333 of the view's width at its distance (1 m): set "
              "unit_scale 1000");

    const fs::path dir = fs::temp_directory_path() / ("dp_mesh_view_" + std::to_string(::getpid()));
    Project p = project_in(dir);
    std::ofstream(dir / "m.obj") << "v 0 0 0\nv 30 0 0\nv 0 30 0\nf 1 2 3\n";
    p.camera.eye = vec3(0, 0.8f, 1.2f);
    p.camera.target = vec3(0, 0.7f, 0);
    p.camera.vfov_deg = 40;
    VirtualObject o;
    o.name = "vase";
    o.shape = mesh_shape();
    o.transform.translation = vec3(0, 0.7f, 0);
    p.objects.push_back(o);
    AssetLibrary library;
    auto said = [&](const std::string& text) {
        for (const std::string& w : library.warnings(p))
            if (w.find(text) != std::string::npos) return true;
        return false;
    };
    EXPECT_TRUE(said("objects[0].shape.unit_scale: 'vase' is 30 m across once placed, "));
    EXPECT_TRUE(said("set unit_scale 0.01"));
    // Its unit given: nothing said.
    p.objects[0].shape.unit_scale = 0.01f;
    EXPECT_FALSE(said("vase"));
    // Behind the camera, nothing to judge by.
    p.objects[0].shape.unit_scale = 1.0f;
    p.objects[0].transform.translation = vec3(0, 0.7f, 5);
    EXPECT_FALSE(said("vase"));
    fs::remove_all(dir);
}

TEST(MeshUnits, AFilesDeclaredUpAxisTurnsItWhereTheProjectSaysNoneAndTheProjectsWordWins) {
    const fs::path dir = fs::temp_directory_path() / ("dp_mesh_up_" + std::to_string(::getpid()));
    Project p = project_in(dir);
    // A 2 x 1 quad in the file's xy plane, the file saying Z is up: a rug lying on the floor.
    const std::string fbx = test::fbx_quad(dir, "100", "2");
    if (fbx.empty()) GTEST_SKIP() << "this Assimp has no FBX exporter";
    std::ofstream(dir / "rug.fbx") << fbx;
    p.camera.eye = vec3(0, 1.5f, 4);
    p.camera.target = vec3(0, 0, 0);
    VirtualObject o;
    o.name = "rug";
    o.shape.kind = Shape::Kind::Mesh;
    o.shape.mesh_path = "rug.fbx";
    p.objects.push_back(o);

    AssetLibrary library;
    auto extent = [&] {
        const auto scene = build_scene(library, p);
        vec3 lo, hi;
        EXPECT_TRUE(scene->virtual_surfaces()[0].mesh->bounds(lo, hi));
        return hi - lo;
    };
    vec3 e = extent();  // the file's word: flat, 1 m deep
    EXPECT_NEAR(e.y, 0.0f, 1e-5f);
    EXPECT_NEAR(e.x, 2.0f, 1e-5f);
    EXPECT_NEAR(e.z, 1.0f, 1e-5f);
    p.objects[0].shape.up_axis = UpAxis::Y;  // the project's word: standing, 1 m tall
    e = extent();
    EXPECT_NEAR(e.y, 1.0f, 1e-5f);
    EXPECT_NEAR(e.z, 0.0f, 1e-5f);
    fs::remove_all(dir);
}
