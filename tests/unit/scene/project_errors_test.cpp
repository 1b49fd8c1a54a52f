#include <gtest/gtest.h>

#include <functional>

#include "base/error.h"
#include "scene/project_io.h"
#include "scene_test_util.h"

using namespace dp;
using json = nlohmann::json;

namespace {

/// One broken input: how to break the rich project, and what the error must name.
struct BadCase {
    std::string name;
    std::function<void(json&)> mutate;
    std::string field;    ///< JSON path the error must name
    std::string message;  ///< text the message must contain
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

const json kLookAt = {{"model", "lookat"}, {"eye", {0, 1.6, 3}}, {"target", {0, 0.5, 0}}};

std::vector<BadCase> bad_cases() {
    return {
        {"VersionTooNew", [](json& j) { j["schema_version"] = 2; }, "schema_version",
         "unsupported schema version 2; this build reads version 1"},
        {"VersionMissing", [](json& j) { j.erase("schema_version"); }, "schema_version",
         "required field is missing"},
        {"VersionNotANumber", [](json& j) { j["schema_version"] = "1"; }, "schema_version",
         "expected an integer, got string"},
        {"PhotoMissing", [](json& j) { j.erase("photo"); }, "photo", "required field is missing"},
        {"PhotoPathMissing", [](json& j) { j["photo"].erase("path"); }, "photo.path",
         "required field is missing"},
        {"PhotoPathEmpty", [](json& j) { j["photo"]["path"] = ""; }, "photo.path",
         "must not be empty"},
        {"ExposureWrongType", [](json& j) { j["photo"]["exposure"] = "+1"; }, "photo.exposure",
         "expected a number, got string"},
        {"CameraMissing", [](json& j) { j.erase("camera"); }, "camera",
         "required field is missing"},
        {"UnknownTopLevelKey", [](json& j) { j["objcts"] = json::array(); }, "objcts",
         "unknown key 'objcts'; did you mean 'objects'?"},
        {"UnknownNestedKey",
         [](json& j) { j["objects"][0]["materail"] = j["objects"][0]["material"]; },
         "objects[0].materail", "unknown key 'materail'; did you mean 'material'?"},
        {"KeyOfAnotherShapeType", [](json& j) { j["objects"][0]["shape"]["size"] = {1, 1, 1}; },
         "objects[0].shape.size", "unknown key 'size' for shape type 'sphere'"},
        {"KeyOfAnotherMaterialType", [](json& j) { j["objects"][1]["material"]["ior"] = 1.5; },
         "objects[1].material.ior", "unknown key 'ior' for material type 'mirror'"},
        {"UnknownMaterial", [](json& j) { j["objects"][2]["material"]["type"] = "velvet"; },
         "objects[2].material.type",
         "unknown material type 'velvet' (valid: diffuse, mirror, glass, principled)"},
        {"MaterialTypeMissing", [](json& j) { j["objects"][2]["material"].erase("type"); },
         "objects[2].material.type", "required field is missing"},
        {"UnknownShape", [](json& j) { j["real"][1]["shape"]["type"] = "cone"; },
         "real[1].shape.type", "unknown shape type 'cone' (valid: plane, box, sphere, mesh)"},
        {"UnknownProbeFormat", [](json& j) { j["probe"]["format"] = "cubemap"; }, "probe.format",
         "unknown probe format 'cubemap' (valid: latlong, mirrorball)"},
        {"UnknownCameraModel", [](json& j) { j["camera"]["model"] = "fisheye"; }, "camera.model",
         "unknown camera model 'fisheye' (valid: lookat, opencv)"},
        {"NegativeRadius", [](json& j) { j["objects"][0]["shape"]["radius"] = -0.3; },
         "objects[0].shape.radius", "must be > 0 (got -0.3)"},
        {"ZeroPlaneSize", [](json& j) { j["real"][0]["shape"]["size"] = {10, 0}; },
         "real[0].shape.size[1]", "must be > 0 (got 0)"},
        {"PlaneSizeWithThreeNumbers", [](json& j) { j["real"][0]["shape"]["size"] = {1, 2, 3}; },
         "real[0].shape.size", "expected 2 numbers, got 3"},
        {"ZeroBoxSize", [](json& j) { j["objects"][1]["shape"]["size"] = {1, 0, 1}; },
         "objects[1].shape.size[1]", "must be > 0"},
        {"ZeroScale", [](json& j) { j["real"][1]["transform"]["scale"] = {1, 1, 0}; },
         "real[1].transform.scale[2]", "must be > 0"},
        {"MeshPathWrongType", [](json& j) { j["objects"][2]["shape"]["path"] = 3; },
         "objects[2].shape.path", "expected a string, got number"},
        {"UnknownUpAxis", [](json& j) { j["objects"][2]["shape"]["up_axis"] = "up"; },
         "objects[2].shape.up_axis", "unknown up axis 'up' (valid: y, z, -y, -z)"},
        {"UpAxisNotAString", [](json& j) { j["real"][2]["shape"]["up_axis"] = 2; },
         "real[2].shape.up_axis", "expected a string, got number"},
        {"UpAxisOnABox", [](json& j) { j["real"][1]["shape"]["up_axis"] = "z"; },
         "real[1].shape.up_axis", "unknown key 'up_axis' for shape type 'box'"},
        {"ZeroUnitScale", [](json& j) { j["objects"][2]["shape"]["unit_scale"] = 0; },
         "objects[2].shape.unit_scale", "must be > 0 metres per file unit (got 0)"},
        {"NegativeUnitScale", [](json& j) { j["real"][2]["shape"]["unit_scale"] = -0.01; },
         "real[2].shape.unit_scale", "must be > 0 metres per file unit (got -0.01)"},
        {"UnknownMaterialSource", [](json& j) { j["objects"][2]["material_source"] = "mesh"; },
         "objects[2].material_source", "unknown material source 'mesh' (valid: project, file)"},
        {"FileMaterialsOnASphere", [](json& j) { j["objects"][0]["material_source"] = "file"; },
         "objects[0].material_source", "\"file\" takes the materials of a mesh file, and this shape is a sphere"},
        {"MaterialSourceOnARealProxy", [](json& j) { j["real"][2]["material_source"] = "file"; },
         "real[2].material_source", "unknown key 'material_source'"},
        {"ZeroIor", [](json& j) { j["objects"][0]["material"]["ior"] = 0; },
         "objects[0].material.ior", "must be > 0 (got 0)"},
        {"NegativeIor", [](json& j) { j["objects"][0]["material"]["ior"] = -1.5; },
         "objects[0].material.ior", "must be > 0"},
        {"PrincipledMetallicAboveOne",
         [](json& j) { j["objects"][1]["material"] = {{"type", "principled"}, {"metallic", 1.5}}; },
         "objects[1].material.metallic", "must be in [0, 1] (got 1.5)"},
        {"PrincipledNegativeRoughness",
         [](json& j) { j["objects"][1]["material"] = {{"type", "principled"}, {"roughness", -0.1}}; },
         "objects[1].material.roughness", "must be in [0, 1] (got -0.1)"},
        {"PrincipledIorBelowRange",
         [](json& j) { j["objects"][1]["material"] = {{"type", "principled"}, {"ior", 1.0}}; },
         "objects[1].material.ior", "must be in [1.01, 5] (got 1)"},
        {"PrincipledTransmissionAboveOne",
         [](json& j) { j["objects"][1]["material"] = {{"type", "principled"}, {"transmission", 2}}; },
         "objects[1].material.transmission", "must be in [0, 1] (got 2)"},
        {"PrincipledNegativeEmission",
         [](json& j) { j["objects"][1]["material"] = {{"type", "principled"}, {"emission", {0, -1, 0}}}; },
         "objects[1].material.emission[1]", "must be >= 0 (got -1)"},
        {"PrincipledBaseColourAboveOne",
         [](json& j) { j["objects"][1]["material"] = {{"type", "principled"}, {"base_colour", {0, 1.2, 0}}}; },
         "objects[1].material.base_colour[1]", "must be in [0, 1] (got 1.2)"},
        {"PrincipledNormalScaleAboveRange",
         [](json& j) { j["objects"][1]["material"] = {{"type", "principled"}, {"normal_scale", 12}}; },
         "objects[1].material.normal_scale", "must be in [0, 10] (got 12)"},
        {"PrincipledNormalTextureNotAPath",
         [](json& j) { j["objects"][1]["material"] = {{"type", "principled"}, {"normal_texture", 3}}; },
         "objects[1].material.normal_texture", "expected a string"},
        {"PrincipledUnknownKey",
         [](json& j) { j["objects"][1]["material"] = {{"type", "principled"}, {"tint", {1, 1, 1}}}; },
         "objects[1].material.tint", "unknown key 'tint' for material type 'principled'"},
        {"TintAboveOne", [](json& j) { j["objects"][0]["material"]["tint"] = {1, 1.5, 1}; },
         "objects[0].material.tint[1]", "must be in [0, 1] (got 1.5)"},
        {"AlbedoNegative", [](json& j) { j["real"][1]["albedo"] = {0.5, -0.1, 0.5}; },
         "real[1].albedo[1]", "must be in [0, 1]"},
        {"AlbedoUnknownWord", [](json& j) { j["real"][0]["albedo"] = "estimated"; },
         "real[0].albedo", "unknown albedo 'estimated'"},
        {"AlbedoEstimateOnVirtualObject",
         [](json& j) { j["objects"][3]["material"]["albedo"] = "estimate"; },
         "objects[3].material.albedo", "\"estimate\" is only valid for real proxies"},
        {"AlbedoWrongType", [](json& j) { j["real"][1]["albedo"] = 0.5; }, "real[1].albedo",
         "expected [r, g, b], {\"texture\": path} or \"estimate\", got number"},
        {"VisibleNotBoolean", [](json& j) { j["objects"][1]["visible"] = "no"; },
         "objects[1].visible", "expected true or false, got string"},
        {"ObjectsNotArray", [](json& j) { j["objects"] = json::object(); }, "objects",
         "expected an array, got object"},
        {"ObjectNotObject", [](json& j) { j["objects"][1] = 5; }, "objects[1]",
         "expected an object, got number"},
        {"ShapeMissing", [](json& j) { j["real"][2].erase("shape"); }, "real[2].shape",
         "required field is missing"},
        {"PhotonsPerPassZero", [](json& j) { j["render"]["photons_per_pass"] = 0; },
         "render.photons_per_pass", "must be an integer in [1, inf) (got 0)"},
        {"PhotonsPerPassNegative", [](json& j) { j["render"]["photons_per_pass"] = -5; },
         "render.photons_per_pass", "(got -5)"},
        {"PassesFractional", [](json& j) { j["render"]["passes"] = 2.5; }, "render.passes",
         "must be an integer (got 2.5)"},
        {"MaxDepthZero", [](json& j) { j["render"]["max_depth"] = 0; }, "render.max_depth",
         "must be an integer in [1, "},
        {"ThreadsNegative", [](json& j) { j["render"]["threads"] = -1; }, "render.threads",
         "must be an integer in [0, "},
        {"SeedNegative", [](json& j) { j["render"]["seed"] = -1; }, "render.seed",
         "must be an integer in [0, "},
        {"AlphaZero", [](json& j) { j["render"]["alpha"] = 0; }, "render.alpha",
         "must be in (0, 1) exclusive (got 0)"},
        {"AlphaOne", [](json& j) { j["render"]["alpha"] = 1; }, "render.alpha",
         "must be in (0, 1) exclusive (got 1)"},
        {"AlphaAboveOne", [](json& j) { j["render"]["alpha"] = 1.5; }, "render.alpha",
         "must be in (0, 1)"},
        {"NegativeInitialRadius", [](json& j) { j["render"]["initial_radius"] = -0.01; },
         "render.initial_radius", "must be > 0"},
        {"NegativeTimeBudget", [](json& j) { j["render"]["time_budget_s"] = -1; },
         "render.time_budget_s", "must be >= 0 seconds"},
        {"UnknownRenderKey", [](json& j) { j["render"]["photons"] = 5; }, "render.photons",
         "unknown key 'photons'"},
        {"NegativeIntensity", [](json& j) { j["probe"]["intensity"] = -1; }, "probe.intensity",
         "must be >= 0"},
        {"ZeroWhiteBalance", [](json& j) { j["probe"]["white_balance"] = {1.2, 1, 0}; },
         "probe.white_balance[2]", "must be > 0 (got 0)"},
        {"NegativeWhiteBalance", [](json& j) { j["probe"]["white_balance"] = {-1, 1, 1}; },
         "probe.white_balance[0]", "must be > 0 (got -1)"},
        {"WhiteBalanceOverflow", [](json& j) { j["probe"]["white_balance"] = {1, 1e39, 1}; },
         "probe.white_balance[1]", "must be a finite number"},
        {"WhiteBalanceOfTwo", [](json& j) { j["probe"]["white_balance"] = {1, 1}; },
         "probe.white_balance", "expected 3 numbers, got 2"},
        {"WhiteBalanceNotAnArray", [](json& j) { j["probe"]["white_balance"] = 1.1; },
         "probe.white_balance", "an array of 3 numbers"},
        {"ProbeMaxWidthTooSmall", [](json& j) { j["probe"]["max_width"] = 63; }, "probe.max_width",
         "must be an integer in [64, 32768] (got 63)"},
        {"ProbeMaxWidthTooLarge", [](json& j) { j["probe"]["max_width"] = 65536; }, "probe.max_width",
         "must be an integer in [64, 32768] (got 65536)"},
        {"ProbeMaxWidthFractional", [](json& j) { j["probe"]["max_width"] = 2048.5; }, "probe.max_width",
         "must be an integer (got 2048.5)"},
        {"ProbeMaxWidthAString", [](json& j) { j["probe"]["max_width"] = "auto"; }, "probe.max_width",
         "expected an integer, got string"},
        {"ProbeSunScaleZero", [](json& j) { j["probe"]["sun_scale"] = 0; }, "probe.sun_scale",
         "must be in (0, 1e+06] (got 0)"},
        {"ProbeSunScaleHuge", [](json& j) { j["probe"]["sun_scale"] = 2e6; }, "probe.sun_scale",
         "must be in (0, 1e+06] (got 2e+06)"},
        {"FxZero", [](json& j) { j["camera"]["fx"] = 0; }, "camera.fx",
         "must be > 0 pixels (got 0)"},
        {"FyNegative", [](json& j) { j["camera"]["fy"] = -1000; }, "camera.fy", "must be > 0"},
        {"CxMissing", [](json& j) { j["camera"].erase("cx"); }, "camera.cx",
         "required field is missing"},
        {"DistortionWrongLength", [](json& j) { j["camera"]["distortion"] = {0.1, 0.2, 0.3}; },
         "camera.distortion", "expected 4 or 5 coefficients"},
        {"RotationNotOrthonormal",
         [](json& j) { j["camera"]["rotation"] = {{1, 0, 0}, {0, 2, 0}, {0, 0, 1}}; },
         "camera.rotation", "must be a rotation matrix"},
        {"RotationReflection",
         [](json& j) { j["camera"]["rotation"] = {{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}}; },
         "camera.rotation", "determinant is -1"},
        {"RotationRowTooShort", [](json& j) { j["camera"]["rotation"][1] = {0, 1}; },
         "camera.rotation[1]", "expected 3 numbers, got 2"},
        {"LookAtKeyOnOpenCvCamera", [](json& j) { j["camera"]["vfov_deg"] = 40; },
         "camera.vfov_deg", "unknown key 'vfov_deg' for camera model 'opencv'"},
        {"VfovZero",
         [](json& j) {
             j["camera"] = kLookAt;
             j["camera"]["vfov_deg"] = 0;
         },
         "camera.vfov_deg", "must be in (0, 180) degrees (got 0)"},
        {"VfovStraight",
         [](json& j) {
             j["camera"] = kLookAt;
             j["camera"]["vfov_deg"] = 180;
         },
         "camera.vfov_deg", "must be in (0, 180) degrees (got 180)"},
        {"EyeMissing",
         [](json& j) {
             j["camera"] = kLookAt;
             j["camera"].erase("eye");
         },
         "camera.eye", "required field is missing"},
        {"EyeEqualsTarget",
         [](json& j) {
             j["camera"] = kLookAt;
             j["camera"]["target"] = j["camera"]["eye"];
         },
         "camera.target", "must differ from camera.eye"},
        {"UpAlongViewDirection",
         [](json& j) {
             j["camera"] = kLookAt;
             j["camera"]["eye"] = {0, 5, 0};
             j["camera"]["target"] = {0, 0, 0};
         },
         "camera.up", "parallel to the viewing direction"},
        {"LightTypeUnknown", [](json& j) { j["lights"] = {{{"type", "sun"}}}; }, "lights[0].type",
         "unknown light type 'sun'"},
        {"LightPowerNegative", [](json& j) { j["lights"] = {{{"type", "point"}, {"power_w", -5}}}; },
         "lights[0].power_w", "must be in [0, 1e+09] (got -5)"},
        {"SpotAngleZero", [](json& j) { j["lights"] = {{{"type", "spot"}, {"spot_angle_deg", 0}}}; },
         "lights[0].spot_angle_deg", "must be > 0"},
        {"SpotFieldOnAPoint", [](json& j) { j["lights"] = {{{"type", "point"}, {"spot_blend", 0.5}}}; },
         "lights[0].spot_blend", "for light type 'point'"},
        {"DiskSizeTwoNumbers", [](json& j) { j["lights"] = {{{"type", "disk"}, {"size", {1, 2}}}}; },
         "lights[0].size", "a disk's size is one number, its diameter: [d]"},
        {"RectSizeZero", [](json& j) { j["lights"] = {{{"type", "rect"}, {"size", {1, 0}}}}; }, "lights[0].size[1]",
         "must be in (0, 1e6] metres (got 0)"},
        {"LightColourAboveOne", [](json& j) { j["lights"] = {{{"type", "point"}, {"colour", {2, 1, 1}}}}; },
         "lights[0].colour[0]", "must be in [0, 1] (got 2)"},
        {"GlossAboveOne", [](json& j) { j["real"][0]["gloss"] = {{"specular", 1.5}}; }, "real[0].gloss.specular",
         "must be in [0, 1] (got 1.5)"},
        {"GlossUnknownKey", [](json& j) { j["real"][0]["gloss"] = {{"shine", 1}}; }, "real[0].gloss.shine",
         "unknown key 'shine'"},
        {"HoldoutDepthZero", [](json& j) { j["holdouts"] = {{{"mask", "m.png"}, {"depth", 0}}}; },
         "holdouts[0].depth", "must be in (0, 1e+06] metres from the camera (got 0)"},
        {"HoldoutMaskMissing", [](json& j) { j["holdouts"] = {{{"depth", 2}}}; }, "holdouts[0].mask",
         "required field is missing"},
        {"HoldoutDepthMissing", [](json& j) { j["holdouts"] = {{{"mask", "m.png"}}}; }, "holdouts[0].depth",
         "required field is missing"},
        {"HoldoutsNotAnArray", [](json& j) { j["holdouts"] = {{"mask", "m.png"}}; }, "holdouts",
         "expected an array"},
        {"FloatOverflow", [](json& j) { j["objects"][0]["transform"]["translation"][0] = 1e39; },
         "objects[0].transform.translation[0]", "must be a finite number"},
    };
}

class BadProject : public dp::test::TempDirTest,
                   public ::testing::WithParamInterface<BadCase> {};

TEST_P(BadProject, ThrowsInputErrorNamingFileAndField) {
    json doc = json::parse(dp::test::kRichProject);
    GetParam().mutate(doc);
    std::string path = write("bad.json", doc.dump(2));
    try {
        load_project(path);
        FAIL() << "expected InputError for " << GetParam().name;
    } catch (const InputError& e) {
        std::string what = e.what();
        EXPECT_EQ(e.file(), path);
        EXPECT_EQ(e.field(), GetParam().field) << what;
        EXPECT_EQ(what.rfind(path + ": field '" + GetParam().field + "': ", 0), 0u) << what;
        EXPECT_NE(what.find(GetParam().message), std::string::npos) << what;
    }
}

INSTANTIATE_TEST_SUITE_P(Scene, BadProject, ::testing::ValuesIn(bad_cases()),
                         [](const auto& info) { return info.param.name; });

class BadProjectText : public dp::test::TempDirTest {
protected:
    /// Loads `text` and returns the InputError's what(), or "" if nothing was thrown.
    std::string error_of(const std::string& text, std::string* field = nullptr) {
        path_ = write("bad.json", text);
        try {
            load_project(path_);
        } catch (const InputError& e) {
            if (field) *field = e.field();
            return e.what();
        }
        return "";
    }
    std::string path_;
};

}  // namespace

TEST_F(BadProjectText, InvalidJsonNamesTheBytePosition) {
    std::string what = error_of("{\n  \"schema_version\": 1,\n  \"photo\": {\"path\": \"a\",}\n}");
    EXPECT_EQ(what.rfind(path_ + ": ", 0), 0u) << what;
    EXPECT_NE(what.find("invalid JSON at byte "), std::string::npos) << what;
    EXPECT_NE(what.find("line 3"), std::string::npos) << what;
}

TEST_F(BadProjectText, EmptyFileIsInvalidJson) {
    EXPECT_NE(error_of("").find("invalid JSON"), std::string::npos);
}

TEST_F(BadProjectText, TopLevelMustBeAnObject) {
    EXPECT_NE(error_of("[1, 2]").find("expected a JSON object at the top level, got array"),
              std::string::npos);
}

TEST_F(BadProjectText, NumberBeyondDoubleRangeIsNotFinite) {
    json doc = json::parse(dp::test::kRichProject);
    std::string text = doc.dump();
    std::string from = "\"intensity\":1.25";
    ASSERT_NE(text.find(from), std::string::npos);
    text.replace(text.find(from), from.size(), "\"intensity\":1e999");
    std::string what = error_of(text);
    EXPECT_EQ(what.rfind(path_ + ": invalid JSON at byte ", 0), 0u) << what;
    EXPECT_NE(what.find("1e999"), std::string::npos) << what;
    EXPECT_NE(what.find("numbers must be finite"), std::string::npos) << what;
}

TEST_F(BadProjectText, DuplicateKeysAreRejectedWithTheirPath) {
    json doc = json::parse(dp::test::kRichProject);
    std::string text = doc.dump();
    std::string from = "\"radius\":0.3";
    ASSERT_NE(text.find(from), std::string::npos);
    text.replace(text.find(from), from.size(), "\"radius\":0.3,\"radius\":0.4");
    std::string field;
    std::string what = error_of(text, &field);
    EXPECT_EQ(field, "objects[0].shape.radius") << what;
    EXPECT_NE(what.find("duplicate key"), std::string::npos) << what;
}

TEST_F(BadProjectText, MissingFileNamesThePath) {
    std::string missing = (dir_ / "nope.json").string();
    try {
        load_project(missing);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(missing + ": ", 0), 0u) << e.what();
    }
}

TEST(ParseProject, ErrorsUseTheGivenFileLabel) {
    json doc = json::parse(dp::test::kRichProject);
    doc["render"]["alpha"] = 2;
    try {
        parse_project(doc, "memory.json", "/base");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("memory.json: field 'render.alpha': ", 0), 0u)
            << e.what();
    }
}
