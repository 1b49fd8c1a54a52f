#include "scene/relink.h"

#include <gtest/gtest.h>

#include "scene/project_io.h"
#include "scene_test_util.h"

using namespace dp;
namespace fs = std::filesystem;

namespace {

class Relink : public dp::test::TempDirTest {
  protected:
    /// A project in dir_ naming a photo, a probe, a mesh object and a textured proxy by
    /// relative paths.
    Project project() const {
        Project p;
        p.base_dir = dir_;
        p.photo.path = "photo.exr";
        p.probe.path = "light/probe.exr";
        VirtualObject teapot;
        teapot.name = "teapot";
        teapot.shape.kind = Shape::Kind::Mesh;
        teapot.shape.mesh_path = "teapot.obj";
        p.objects.push_back(teapot);
        VirtualObject ball;  // names no file
        ball.shape.kind = Shape::Kind::Sphere;
        p.objects.push_back(ball);
        RealProxy floor;
        floor.name = "floor";
        floor.albedo.kind = Albedo::Kind::Texture;
        floor.albedo.texture_path = "wood.png";
        p.real.push_back(floor);
        return p;
    }
};

}  // namespace

TEST_F(Relink, EveryFileTheProjectReadsIsListedWithItsFieldAndWhatItIs) {
    write("photo.exr", "x");
    const std::vector<InputFile> files = input_files(project());
    ASSERT_EQ(files.size(), 4u);
    EXPECT_EQ(files[0].ref.field, "photo.path");
    EXPECT_EQ(files[0].ref.what, "photo");
    EXPECT_FALSE(files[0].missing);
    EXPECT_EQ(files[1].ref.field, "probe.path");
    EXPECT_EQ(files[1].ref.what, "light probe");
    EXPECT_EQ(files[1].stored, "light/probe.exr");
    EXPECT_EQ(files[1].resolved, dir_ / "light/probe.exr");
    EXPECT_TRUE(files[1].missing);
    EXPECT_EQ(files[2].ref.field, "real[0].albedo.texture");
    EXPECT_EQ(files[2].ref.what, "texture of proxy \"floor\"");
    EXPECT_EQ(files[3].ref.field, "objects[0].shape.path");
    EXPECT_EQ(files[3].ref.what, "mesh of \"teapot\"");
    EXPECT_EQ(missing_inputs(project()).size(), 3u);
}

TEST_F(Relink, AFolderWhereAFileWasIsStillMissing) {
    fs::create_directories(dir_ / "photo.exr");
    EXPECT_TRUE(input_files(project())[0].missing);
}

TEST_F(Relink, SettingAnInputPathChangesOnlyThatField) {
    Project p = project();
    EXPECT_TRUE(set_input_path(p, "objects[0].shape.path", "meshes/teapot.obj"));
    EXPECT_EQ(p.objects[0].shape.mesh_path, "meshes/teapot.obj");
    EXPECT_TRUE(set_input_path(p, "probe.path", "/probes/sky.exr"));
    EXPECT_EQ(p.probe.path, "/probes/sky.exr");
    Project q = project();
    q.objects[0].shape.mesh_path = "meshes/teapot.obj";
    q.probe.path = "/probes/sky.exr";
    EXPECT_TRUE(p == q);
    EXPECT_FALSE(set_input_path(p, "objects[1].shape.path", "ball.obj"));  // a sphere
    EXPECT_FALSE(set_input_path(p, "objects[7].shape.path", "x.obj"));
    EXPECT_TRUE(p == q);
}

TEST_F(Relink, PathsInsideTheProjectFolderAreStoredRelativeAndOthersAbsolute) {
    EXPECT_EQ(path_for_project(dir_, dir_ / "sub" / "photo.exr"), "sub/photo.exr");
    EXPECT_EQ(path_for_project(dir_, dir_ / "sub" / ".." / "photo.exr"), "photo.exr");
    const fs::path outside = dir_.parent_path() / "elsewhere" / "photo.exr";
    EXPECT_EQ(path_for_project(dir_, outside), outside.string());
    EXPECT_EQ(path_for_project("", "/a/b.exr"), "/a/b.exr");
}

TEST_F(Relink, AFileIsFoundByNameInTheFoldersGivenDownToTwoLevels) {
    write("a/b/photo.exr", "x");
    write("c/d/e/probe.exr", "x");
    write("f/teapot.obj", "x");
    fs::create_directories(dir_ / "g" / "wood.png");  // a folder of that name is no file
    EXPECT_EQ(find_file_named("photo.exr", {dir_}), dir_ / "a/b/photo.exr");
    EXPECT_EQ(find_file_named("probe.exr", {dir_}), std::nullopt);  // three levels down
    EXPECT_EQ(find_file_named("probe.exr", {dir_ / "c"}), dir_ / "c/d/e/probe.exr");
    EXPECT_EQ(find_file_named("wood.png", {dir_}), std::nullopt);
    EXPECT_EQ(find_file_named("teapot.obj", {dir_ / "nowhere", dir_ / "f"}), dir_ / "f/teapot.obj");
    EXPECT_EQ(find_file_named("photo.exr", {dir_}, 1), std::nullopt);
}

TEST_F(Relink, TheShallowestFileOfTheNameIsFoundFirst) {
    write("x/y/photo.exr", "deep");
    write("z/photo.exr", "shallow");
    EXPECT_EQ(find_file_named("photo.exr", {dir_}), dir_ / "z/photo.exr");
    // The folders are searched in the order given: a relinked file's folder before the project's.
    EXPECT_EQ(find_file_named("photo.exr", {dir_ / "x", dir_}), dir_ / "x/y/photo.exr");
}

TEST_F(Relink, AFolderSearchedShallowIsSearchedAgainWhenReachedWithLevelsToGo) {
    write("p/q/r/photo.exr", "x");
    // dir_ first reaches p/q at its last level; p itself then goes two levels below p.
    EXPECT_EQ(find_file_named("photo.exr", {dir_, dir_ / "p"}), dir_ / "p/q/r/photo.exr");
}

TEST_F(Relink, ASearchOfAHugeTreeStopsAtItsEntryBudget) {
    for (int i = 0; i < 30; ++i) write("many/f" + std::to_string(i), "x");
    write("z/photo.exr", "x");
    EXPECT_EQ(find_file_named("photo.exr", {dir_ / "many", dir_ / "z"}, 2, 10), std::nullopt);
    EXPECT_EQ(find_file_named("photo.exr", {dir_ / "many", dir_ / "z"}, 2, 100),
              dir_ / "z/photo.exr");
}
