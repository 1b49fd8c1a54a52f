#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "base/error.h"
#include "scene/project_diff.h"
#include "scene/project_io.h"
#include "scene_test_util.h"

using namespace dp;
using dp::test::kRichProject;

namespace {

class ProjectIo : public dp::test::TempDirTest {};

}  // namespace

TEST_F(ProjectIo, RichProjectLoadsWithEveryField) {
    Project p = load_project(write("rich.json", kRichProject));
    EXPECT_EQ(p.photo.path, "photos/kitchen.jpg");
    EXPECT_FLOAT_EQ(p.photo.exposure, -0.5f);
    EXPECT_EQ(p.probe.format, ProbeSpec::Format::MirrorBall);
    EXPECT_FLOAT_EQ(p.probe.rotation_deg.y, 90.5f);
    EXPECT_FLOAT_EQ(p.probe.intensity, 1.25f);
    EXPECT_EQ(p.probe.white_balance, vec3(1.1f, 1.0f, 0.85f));

    ASSERT_EQ(p.camera.model, CameraSpec::Model::Intrinsics);
    EXPECT_FLOAT_EQ(p.camera.fx, 1210.5f);
    EXPECT_FLOAT_EQ(p.camera.distortion.k3, 0.001f);
    // The file is row-major: row 0 is (0, 0, 1), so R maps world +Z onto camera +X.
    vec3 x_cam = p.camera.rotation * vec3(0, 0, 1);
    EXPECT_FLOAT_EQ(x_cam.x, 1.0f);
    EXPECT_FLOAT_EQ(p.camera.rotation[2][0], 1.0f);  // glm [column][row]
    EXPECT_FLOAT_EQ(p.camera.rotation[0][2], -1.0f);

    ASSERT_EQ(p.real.size(), 3u);
    EXPECT_EQ(p.real[0].shape.kind, Shape::Kind::Plane);
    EXPECT_FLOAT_EQ(p.real[0].shape.size.x, 10.0f);
    EXPECT_FLOAT_EQ(p.real[0].shape.size.z, 8.0f);
    EXPECT_EQ(p.real[0].albedo.kind, Albedo::Kind::Estimate);
    EXPECT_EQ(p.real[1].albedo.kind, Albedo::Kind::Constant);
    EXPECT_FLOAT_EQ(p.real[1].transform.scale.z, 2.0f);
    EXPECT_EQ(p.real[2].albedo.kind, Albedo::Kind::Texture);
    EXPECT_EQ(p.real[2].albedo.texture_path, "wood.png");
    EXPECT_EQ(p.real[2].shape.mesh_path, "/abs/table.obj");
    // A mesh's axes and unit: as written; left out, the up axis is the file's (else +Y) and
    // the unit metres.
    EXPECT_FALSE(p.real[2].shape.up_axis.has_value());
    EXPECT_EQ(p.real[2].shape.effective_up(UpAxis::Z), UpAxis::Z);
    EXPECT_EQ(p.real[2].shape.effective_up(), UpAxis::Y);
    EXPECT_EQ(p.real[2].shape.unit_scale, 1.0f);
    EXPECT_EQ(p.objects[2].shape.up_axis, UpAxis::Z);
    EXPECT_EQ(p.objects[2].shape.unit_scale, 0.01f);
    EXPECT_EQ(p.objects[2].material_source, MaterialSource::File);
    EXPECT_EQ(p.objects[0].material_source, MaterialSource::Project);  // the default

    ASSERT_EQ(p.objects.size(), 5u);
    EXPECT_EQ(p.objects[0].material.kind, Material::Kind::Glass);
    EXPECT_FLOAT_EQ(p.objects[0].material.ior, 1.45f);
    EXPECT_FALSE(p.objects[1].visible);
    EXPECT_EQ(p.objects[1].material.kind, Material::Kind::Mirror);
    EXPECT_EQ(p.objects[2].material.albedo.kind, Albedo::Kind::Texture);
    EXPECT_TRUE(p.objects[3].visible);
    // Defaults from project.h where fields are left out.
    EXPECT_EQ(p.objects[4].name, "");
    EXPECT_EQ(p.objects[4].material, Material{});
    EXPECT_EQ(p.objects[4].transform, Transform{});

    EXPECT_EQ(p.render.photons_per_pass, 500000);
    EXPECT_EQ(p.render.passes, 32);
    EXPECT_DOUBLE_EQ(p.render.time_budget_s, 12.5);
    ASSERT_TRUE(p.render.initial_radius.has_value());
    EXPECT_FLOAT_EQ(*p.render.initial_radius, 0.02f);
    EXPECT_EQ(p.render.seed, 18446744073709551615ull);
    EXPECT_EQ(p.render.threads, 4);
}

TEST_F(ProjectIo, LoadSaveLoadGivesAnEqualProject) {
    Project a = load_project(write("rich.json", kRichProject));
    std::string saved = (dir_ / "saved.json").string();
    save_project(a, saved);
    Project b = load_project(saved);
    EXPECT_EQ(a, b);
    // And again, so the written form is a fixed point.
    save_project(b, (dir_ / "saved2.json").string());
    EXPECT_EQ(read(saved), read((dir_ / "saved2.json").string()));
}

TEST_F(ProjectIo, LookAtProjectWithDefaultsRoundTrips) {
    const char* text = R"({"schema_version": 1, "photo": {"path": "p.png"},
        "probe": {"path": "probe.hdr"},
        "camera": {"model": "lookat", "eye": [0.1, 1.7, 4], "target": [0, 0.5, 0]}})";
    Project a = load_project(write("min.json", text));
    EXPECT_EQ(a.probe.format, ProbeSpec::Format::LatLong);
    EXPECT_EQ(a.camera.model, CameraSpec::Model::LookAt);
    EXPECT_FLOAT_EQ(a.camera.vfov_deg, 45.0f);
    EXPECT_EQ(a.render, RenderSettings{});
    EXPECT_FALSE(a.render.initial_radius.has_value());
    EXPECT_TRUE(a.real.empty());
    EXPECT_TRUE(a.objects.empty());
    std::string saved = (dir_ / "saved.json").string();
    save_project(a, saved);
    EXPECT_EQ(load_project(saved), a);
}

TEST_F(ProjectIo, TheProbesWhiteBalanceRoundTripsAndIsLeftOutWhenNeutral) {
    const char* text = R"({"schema_version": 1, "photo": {"path": "p.png"},
        "probe": {"path": "probe.hdr", "intensity": 2.04, "white_balance": [1.18, 0.98, 0.69]},
        "camera": {"model": "lookat", "eye": [0, 1, 4], "target": [0, 0.5, 0]}})";
    Project a = load_project(write("wb.json", text));
    EXPECT_EQ(a.probe.white_balance, vec3(1.18f, 0.98f, 0.69f));
    EXPECT_EQ(a.probe.gain(), 2.04f * vec3(1.18f, 0.98f, 0.69f));
    const std::string saved = (dir_ / "saved.json").string();
    save_project(a, saved);
    EXPECT_EQ(load_project(saved), a);
    EXPECT_NE(read(saved).find("\"white_balance\""), std::string::npos);
    EXPECT_EQ(parse_project(to_json(a), "memory", dir_), a);

    // Neutral, it is not written: the file stays as older builds wrote (and read) it.
    a.probe.white_balance = vec3(1.0f);
    save_project(a, saved);
    EXPECT_EQ(read(saved).find("white_balance"), std::string::npos);
    EXPECT_EQ(load_project(saved).probe.white_balance, vec3(1.0f));
    EXPECT_EQ(load_project(write("min.json", R"({"schema_version": 1, "photo": {"path": "p.png"},
        "probe": {"path": "probe.hdr"},
        "camera": {"model": "lookat", "eye": [0, 1, 4], "target": [0, 0.5, 0]}})"))
                  .probe.white_balance,
              vec3(1.0f));
}

TEST_F(ProjectIo, TheProbesMaxWidthRoundTripsAndIsLeftOutWhenAutomatic) {
    const char* text = R"({"schema_version": 1, "photo": {"path": "p.png"},
        "probe": {"path": "probe.exr", "max_width": 2048},
        "camera": {"model": "lookat", "eye": [0, 1, 4], "target": [0, 0.5, 0]}})";
    Project a = load_project(write("mw.json", text));
    EXPECT_EQ(a.probe.max_width, 2048);
    const std::string saved = (dir_ / "saved.json").string();
    save_project(a, saved);
    EXPECT_NE(read(saved).find("\"max_width\": 2048"), std::string::npos) << read(saved);
    EXPECT_EQ(load_project(saved), a);

    // Automatic (0) is not written: the file stays readable by builds that know no max_width.
    a.probe.max_width = 0;
    save_project(a, saved);
    EXPECT_EQ(read(saved).find("max_width"), std::string::npos);
    EXPECT_EQ(load_project(saved).probe.max_width, 0);
}

TEST_F(ProjectIo, TheProbesSunScaleRoundTripsAndIsLeftOutAtOne) {
    const char* text = R"({"schema_version": 1, "photo": {"path": "p.png"},
        "probe": {"path": "probe.exr", "sun_scale": 19.75},
        "camera": {"model": "lookat", "eye": [0, 1, 4], "target": [0, 0.5, 0]}})";
    Project a = load_project(write("ss.json", text));
    EXPECT_EQ(a.probe.sun_scale, 19.75f);
    const std::string saved = (dir_ / "saved.json").string();
    save_project(a, saved);
    EXPECT_EQ(load_project(saved), a);
    Project b = a;
    b.probe.sun_scale = 1;
    // The scale is applied to the probe's pixels as they load: a change reloads the assets.
    EXPECT_EQ(classify(a, b), Change::Assets);
    save_project(b, saved);
    EXPECT_EQ(read(saved).find("sun_scale"), std::string::npos);
}

TEST_F(ProjectIo, HoldoutsRoundTripAndAreLeftOutWhenThereAreNone) {
    const char* text = R"({"schema_version": 1, "photo": {"path": "p.png"},
        "probe": {"path": "probe.exr"},
        "camera": {"model": "lookat", "eye": [0, 1, 4], "target": [0, 0.5, 0]},
        "holdouts": [{"name": "board", "mask": "board.mask.png", "depth": 1.25}]})";
    Project a = load_project(write("h.json", text));
    ASSERT_EQ(a.holdouts.size(), 1u);
    EXPECT_EQ(a.holdouts[0].name, "board");
    EXPECT_EQ(a.holdouts[0].mask, "board.mask.png");
    EXPECT_EQ(a.holdouts[0].depth, 1.25f);
    const std::string saved = (dir_ / "saved.json").string();
    save_project(a, saved);
    EXPECT_EQ(load_project(saved), a);
    // The mask is an input file: relinking, bundling and the missing-files check see it.
    std::vector<std::string> fields;
    for_each_input(a, [&](const InputRef& ref, const std::string&) { fields.push_back(ref.field); });
    EXPECT_NE(std::find(fields.begin(), fields.end(), "holdouts[0].mask"), fields.end());

    // A new mask is loaded with the assets; a new depth only rebuilds the scene.
    Project b = a;
    b.holdouts[0].depth = 2;
    EXPECT_EQ(classify(a, b), Change::Scene);
    b = a;
    b.holdouts[0].mask = "other.png";
    EXPECT_EQ(classify(a, b), Change::Assets);
    std::vector<int> edited;
    EXPECT_FALSE(edited_objects(a, b, edited));  // the whole picture can change
    b.holdouts.clear();
    EXPECT_EQ(classify(a, b), Change::Assets);
    save_project(b, saved);
    EXPECT_EQ(read(saved).find("holdouts"), std::string::npos);
}

TEST_F(ProjectIo, ProgrammaticProjectRoundTripsBitExactly) {
    Project a;
    a.photo.path = "photo.exr";
    a.photo.exposure = 0.1f;
    a.probe.path = "probe.exr";
    a.probe.rotation_deg = vec3(1.0f / 3.0f, 0.7f, -12.3456789f);
    a.camera.model = CameraSpec::Model::Intrinsics;
    a.camera.fx = 1000.1f;
    a.camera.fy = 999.9f;
    a.camera.cx = 640.3f;
    a.camera.cy = 360.7f;
    a.camera.distortion = Distortion{-0.123456f, 0.0789f, 1e-4f, -2e-4f, 0.0003f};
    a.camera.rotation = glm::mat3(Transform{vec3(0), vec3(10.1f, -20.2f, 30.3f), vec3(1)}.matrix());
    a.camera.translation = vec3(0.3f, -0.1f, 2.9f);
    RealProxy floor;
    floor.shape.size = vec3(5.5f, 1.0f, 3.3f);
    floor.albedo.rgb = vec3(0.3f, 0.31f, 0.32f);
    a.real.push_back(floor);
    VirtualObject ball;
    ball.name = "ball \"quoted\" ünïcode";
    ball.shape.kind = Shape::Kind::Sphere;
    ball.shape.radius = 0.123f;
    ball.material.kind = Material::Kind::Glass;
    ball.material.ior = 1.333f;
    a.objects.push_back(ball);
    a.render.initial_radius = 0.0314f;
    a.render.alpha = 2.0f / 3.0f;
    a.render.time_budget_s = 0.1;

    std::string saved = (dir_ / "saved.json").string();
    save_project(a, saved);
    EXPECT_EQ(load_project(saved), a);
    // to_json / parse_project round-trip without a file too.
    EXPECT_EQ(parse_project(to_json(a), "memory", dir_), a);
}

TEST_F(ProjectIo, APrincipledMaterialRoundTripsWithEveryFieldAndItsDefaults) {
    Project a = load_project(write("rich.json", kRichProject));
    Material& m = a.objects[0].material;
    m = Material{};
    m.kind = Material::Kind::Principled;
    m.albedo.rgb = vec3(0.9f, 0.6f, 0.2f);
    m.principled = {1.0f / 3.0f, 0.27f, 1.75f, 0.5f, 0.125f, vec3(0.0f, 2.5f, 10.0f)};
    const nlohmann::json doc = to_json(a);
    EXPECT_EQ(doc["objects"][0]["material"]["type"], "principled");
    EXPECT_EQ(doc["objects"][0]["material"]["ior"], 1.75);
    EXPECT_EQ(parse_project(doc, "memory", dir_), a);
    // A textured base colour, as a diffuse albedo is written.
    m.albedo = Albedo{};  // a texture's colour is not written
    m.albedo.kind = Albedo::Kind::Texture;
    m.albedo.texture_path = "textures/rust.png";
    EXPECT_EQ(to_json(a)["objects"][0]["material"]["base_colour"]["texture"], "textures/rust.png");
    EXPECT_EQ(parse_project(to_json(a), "memory", dir_), a);
    // Only the type: the defaults (glTF's, but roughness 0.5 and a grey base).
    nlohmann::json bare = doc;
    bare["objects"][0]["material"] = {{"type", "principled"}};
    const Material d = parse_project(bare, "memory", dir_).objects[0].material;
    EXPECT_EQ(d.kind, Material::Kind::Principled);
    EXPECT_EQ(d.principled, PrincipledMaterial{});
    EXPECT_EQ(d.principled.ior, 1.5f);
    EXPECT_EQ(d.principled.specular, 1.0f);
    EXPECT_EQ(d.principled.emission, vec3(0.0f));
    EXPECT_FALSE(to_json(a)["objects"][0]["material"].contains("normal_texture"));  // none: not written
    // The metallic-roughness texture and the normal map with its scale.
    m.principled.metallic_roughness_texture = "textures/rust_mr.png";
    m.principled.normal_texture = "textures/rust_n.png";
    m.principled.normal_scale = 0.5f;
    const nlohmann::json textured = to_json(a)["objects"][0]["material"];
    EXPECT_EQ(textured["metallic_roughness_texture"], "textures/rust_mr.png");
    EXPECT_EQ(textured["normal_texture"], "textures/rust_n.png");
    EXPECT_EQ(textured["normal_scale"], 0.5);
    EXPECT_EQ(parse_project(to_json(a), "memory", dir_), a);
    // Both are inputs of the project, under their fields.
    std::vector<std::string> fields;
    for_each_input(a, [&](const InputRef& in, const std::string&) { fields.push_back(in.field); });
    EXPECT_NE(std::find(fields.begin(), fields.end(), "objects[0].material.metallic_roughness_texture"), fields.end());
    EXPECT_NE(std::find(fields.begin(), fields.end(), "objects[0].material.normal_texture"), fields.end());
}

TEST_F(ProjectIo, EditingAPrincipledParameterIsAMaterialChange) {
    Project a = load_project(write("rich.json", kRichProject));
    a.objects[0].material = Material{};
    a.objects[0].material.kind = Material::Kind::Principled;
    Project b = a;
    b.objects[0].material.principled.roughness = 0.8f;
    EXPECT_EQ(classify(a, b), Change::Material);
    b = a;
    b.objects[0].material.principled.emission = vec3(1.0f);
    EXPECT_EQ(classify(a, b), Change::Material);
    EXPECT_EQ(classify(a, a), Change::None);
    // A texture is an image to load: a rebuild; the normal map's strength is not.
    b = a;
    b.objects[0].material.principled.normal_texture = "n.png";
    EXPECT_EQ(classify(a, b), Change::Scene);
    Project c = b;
    c.objects[0].material.principled.normal_scale = 2.0f;
    EXPECT_EQ(classify(b, c), Change::Material);
    // Textures are loaded only for a principled material: turning one with them into another
    // kind, or back, is a rebuild too.
    c = b;
    c.objects[0].material.kind = Material::Kind::Diffuse;
    EXPECT_EQ(classify(b, c), Change::Scene);
}

TEST_F(ProjectIo, EveryLightKindRoundTripsWithItsOwnFieldsOnly) {
    Project a = load_project(write("rich.json", kRichProject));
    EXPECT_FALSE(to_json(a).contains("lights"));  // none: the key is left out
    VirtualLight point, spot, rect, disk;
    point.name = "bulb";
    point.transform.translation = vec3(0.5f, 2.25f, -1);
    point.colour = vec3(1, 0.8f, 0.6f);
    point.power_w = 60;
    spot = point;
    spot.kind = VirtualLight::Kind::Spot;
    spot.transform.rotation_deg = vec3(-30, 10, 0);
    spot.spot_angle_deg = 35;
    spot.spot_blend = 0.4f;
    rect.kind = VirtualLight::Kind::Rect;
    rect.size = vec2(1.2f, 0.3f);
    rect.visible = false;
    disk.kind = VirtualLight::Kind::Disk;
    disk.size = vec2(0.25f);
    a.lights = {point, spot, rect, disk};
    const nlohmann::json doc = to_json(a);
    EXPECT_EQ(doc["lights"][0]["type"], "point");
    EXPECT_FALSE(doc["lights"][0].contains("spot_angle_deg"));
    EXPECT_FALSE(doc["lights"][0].contains("size"));
    EXPECT_EQ(doc["lights"][1]["spot_angle_deg"], 35.0);
    EXPECT_EQ(doc["lights"][2]["size"], nlohmann::json::array({1.2, 0.3}));
    EXPECT_EQ(doc["lights"][3]["size"], nlohmann::json::array({0.25}));
    EXPECT_EQ(parse_project(doc, "memory", dir_), a);
    const std::string path = (dir_ / "saved.json").string();
    save_project(a, path);
    EXPECT_EQ(load_project(path), a);
    // Only the type: a 100 W white point light at the origin.
    nlohmann::json bare = doc;
    bare["lights"][0] = {{"type", "point"}};
    EXPECT_EQ(parse_project(bare, "memory", dir_).lights[0], VirtualLight{});
    // A light edit is taken like a material edit (no geometry rebuilt); nothing else changes.
    Project b = a;
    b.lights[1].power_w = 120;
    EXPECT_EQ(classify(a, b), Change::Material);
    std::vector<int> edited;
    EXPECT_FALSE(edited_objects(a, b, edited));  // the whole picture can change
}

TEST_F(ProjectIo, AProxysGlossRoundTripsAndIsLeftOutWhenMatte) {
    Project a = load_project(write("rich.json", kRichProject));
    EXPECT_FALSE(to_json(a)["real"][0].contains("gloss"));
    a.real[0].gloss = Gloss{0.04f, 0.15f};
    const nlohmann::json doc = to_json(a);
    EXPECT_EQ(doc["real"][0]["gloss"]["specular"], 0.04);
    EXPECT_EQ(doc["real"][0]["gloss"]["roughness"], 0.15);
    EXPECT_EQ(parse_project(doc, "memory", dir_), a);
    nlohmann::json bare = doc;
    bare["real"][0]["gloss"] = {{"specular", 0.5}};
    EXPECT_EQ(parse_project(bare, "memory", dir_).real[0].gloss.roughness, Gloss{}.roughness);
}

TEST_F(ProjectIo, EveryUpAxisAndAUnitScaleRoundTripAndAreWrittenForMeshesOnly) {
    Project a = load_project(write("rich.json", kRichProject));
    for (const auto& [name, axis] : kUpAxes) {
        SCOPED_TRACE(name);
        a.objects[2].shape.up_axis = axis;
        a.objects[2].shape.unit_scale = 0.0254f;  // inches
        const nlohmann::json doc = to_json(a);
        EXPECT_EQ(doc["objects"][2]["shape"]["up_axis"], name);
        EXPECT_EQ(doc["objects"][2]["shape"]["unit_scale"], 0.0254);
        EXPECT_FALSE(doc["objects"][0]["shape"].contains("up_axis"));  // a sphere has no file
        EXPECT_FALSE(doc["objects"][0]["shape"].contains("unit_scale"));
        EXPECT_EQ(parse_project(doc, "memory", dir_), a);
    }
    // Absent stays absent, so that the file's own up axis keeps applying after a save.
    a.objects[2].shape.up_axis.reset();
    const nlohmann::json doc = to_json(a);
    EXPECT_FALSE(doc["objects"][2]["shape"].contains("up_axis"));
    EXPECT_EQ(parse_project(doc, "memory", dir_), a);
    EXPECT_EQ(a.objects[2].shape.effective_up(UpAxis::NegZ), UpAxis::NegZ);
}

TEST_F(ProjectIo, TheMaterialSourceRoundTripsAndIsWrittenForMeshesOnly) {
    Project a = load_project(write("rich.json", kRichProject));
    for (const MaterialSource source : {MaterialSource::Project, MaterialSource::File}) {
        a.objects[2].material_source = source;
        const nlohmann::json doc = to_json(a);
        EXPECT_EQ(doc["objects"][2]["material_source"], material_source_name(source));
        EXPECT_FALSE(doc["objects"][0].contains("material_source"));  // a sphere has no file
        EXPECT_EQ(parse_project(doc, "memory", dir_), a);
    }
    // An object written before the key existed takes the project's material.
    nlohmann::json doc = to_json(a);
    doc["objects"][2].erase("material_source");
    EXPECT_EQ(parse_project(doc, "memory", dir_).objects[2].material_source,
              MaterialSource::Project);
}

TEST_F(ProjectIo, SavedFileIsPrettyWithPathsAsStored) {
    Project a = load_project(write("rich.json", kRichProject));
    std::string saved = (dir_ / "out" / "saved.json").string();
    std::filesystem::create_directories(dir_ / "out");
    save_project(a, saved);
    std::string text = read(saved);
    EXPECT_EQ(text.rfind("{\n  \"schema_version\": 1,\n  \"photo\": {\n    \"path\": ", 0), 0u)
        << text.substr(0, 200);
    EXPECT_NE(text.find("\"path\": \"../probes/kitchen_ball.exr\""), std::string::npos);
    EXPECT_NE(text.find("\"path\": \"/abs/table.obj\""), std::string::npos);
    EXPECT_NE(text.find("\"albedo\": \"estimate\""), std::string::npos);
    EXPECT_NE(text.find("0.032,"), std::string::npos) << "floats are written in shortest form";
    EXPECT_EQ(text.back(), '\n');
}

TEST_F(ProjectIo, PathsResolveRelativeToTheProjectFilesFolder) {
    std::string path = write("scenes/kitchen/project.json", kRichProject);
    Project p = load_project(path);
    std::filesystem::path folder = (dir_ / "scenes" / "kitchen").lexically_normal();
    EXPECT_TRUE(p.base_dir.is_absolute());
    EXPECT_EQ(p.resolve(p.photo.path), folder / "photos" / "kitchen.jpg");
    EXPECT_EQ(p.resolve(p.probe.path).lexically_normal(),
              (dir_ / "scenes" / "probes" / "kitchen_ball.exr").lexically_normal());
    EXPECT_EQ(p.resolve(p.real[2].shape.mesh_path), std::filesystem::path("/abs/table.obj"));
    EXPECT_EQ(p.resolve(p.objects[2].shape.mesh_path), folder / "meshes" / "bunny.obj");
}

TEST_F(ProjectIo, RelativeProjectPathStillGivesTheFilesFolder) {
    write("scenes/project.json", kRichProject);
    std::filesystem::path old = std::filesystem::current_path();
    std::filesystem::current_path(dir_);
    std::filesystem::path cwd = std::filesystem::current_path();
    Project p;
    EXPECT_NO_THROW(p = load_project("scenes/project.json"));
    std::filesystem::current_path(old);  // before any assertion can return early
    EXPECT_TRUE(p.base_dir.is_absolute());
    EXPECT_EQ(p.resolve("photo.exr"), cwd / "scenes" / "photo.exr");
}

TEST_F(ProjectIo, SaveToAnUnwritablePathThrowsInputError) {
    Project p = load_project(write("rich.json", kRichProject));
    std::string bad = (dir_ / "missing_folder" / "x.json").string();
    try {
        save_project(p, bad);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
}

TEST_F(ProjectIo, ANonFiniteValueIsNotSavedAndTheOldFileStaysWhole) {
    Project a = load_project(write("rich.json", kRichProject));
    const std::string saved = (dir_ / "saved.json").string();
    save_project(a, saved);
    const std::string before = read(saved);
    Project bad = a;
    bad.camera.model = CameraSpec::Model::Intrinsics;
    bad.camera.fx = std::numeric_limits<float>::infinity();  // e.g. a calibration with --focal 1e300
    try {
        save_project(bad, saved);
        FAIL() << "a project with fx = inf was saved";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "camera.fx") << e.what();
    }
    EXPECT_EQ(read(saved), before);
    EXPECT_EQ(load_project(saved), a);
}
