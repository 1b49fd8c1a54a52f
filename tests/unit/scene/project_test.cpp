#include <gtest/gtest.h>

#include <cmath>

#include "scene/project.h"

using namespace dp;

namespace {

void expect_matrix_near(const glm::mat4& got, const glm::mat4& want, float tol = 1e-5f) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            EXPECT_NEAR(got[c][r], want[c][r], tol) << "column " << c << ", row " << r;
}

vec3 apply(const glm::mat4& m, const vec3& p) { return vec3(m * glm::vec4(p, 1.0f)); }

void expect_vec_near(const vec3& got, const vec3& want, float tol = 1e-5f) {
    EXPECT_NEAR(got.x, want.x, tol);
    EXPECT_NEAR(got.y, want.y, tol);
    EXPECT_NEAR(got.z, want.z, tol);
}

/// Row-major 3x3 written as in a textbook, returned as a glm 4x4 (glm is column-major).
glm::mat4 rows(float a, float b, float c, float d, float e, float f, float g, float h, float i) {
    glm::mat4 m(1.0f);
    float v[3][3] = {{a, b, c}, {d, e, f}, {g, h, i}};
    for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col) m[col][r] = v[r][col];
    return m;
}

}  // namespace

TEST(Transform, DefaultIsIdentity) { expect_matrix_near(Transform{}.matrix(), glm::mat4(1.0f)); }

TEST(Transform, ScalesThenRotatesThenTranslates) {
    Transform t;
    t.translation = vec3(1, 2, 3);
    t.rotation_deg = vec3(0, 0, 90);
    t.scale = vec3(2, 1, 1);
    // Row-major T * Rz(90) * S: [[0,-1,0,1],[2,0,0,2],[0,0,1,3],[0,0,0,1]].
    glm::mat4 want(1.0f);
    want[0] = glm::vec4(0, 2, 0, 0);
    want[1] = glm::vec4(-1, 0, 0, 0);
    want[2] = glm::vec4(0, 0, 1, 0);
    want[3] = glm::vec4(1, 2, 3, 1);
    expect_matrix_near(t.matrix(), want);
    expect_vec_near(apply(t.matrix(), vec3(1, 0, 0)), vec3(1, 4, 3));
}

TEST(Transform, RotatesAboutXThenYThenZ) {
    Transform t;
    t.rotation_deg = vec3(90, 90, 0);
    // Rx(90) takes +Y to +Z, then Ry(90) takes +Z to +X (the reverse order would give +Z).
    expect_vec_near(apply(t.matrix(), vec3(0, 1, 0)), vec3(1, 0, 0));
    t.rotation_deg = vec3(0, 90, 90);
    // Ry(90) takes +Z to +X, then Rz(90) takes +X to +Y.
    expect_vec_near(apply(t.matrix(), vec3(0, 0, 1)), vec3(0, 1, 0));
}

TEST(Transform, MatchesTheProductOfTextbookRotations) {
    Transform t;
    t.rotation_deg = vec3(30, -45, 60);
    t.scale = vec3(0.5f, 2, 3);
    t.translation = vec3(-1, 0.25f, 4);
    const float a = glm::radians(30.0f), b = glm::radians(-45.0f), g = glm::radians(60.0f);
    glm::mat4 rx = rows(1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a));
    glm::mat4 ry = rows(std::cos(b), 0, std::sin(b), 0, 1, 0, -std::sin(b), 0, std::cos(b));
    glm::mat4 rz = rows(std::cos(g), -std::sin(g), 0, std::sin(g), std::cos(g), 0, 0, 0, 1);
    glm::mat4 s = rows(0.5f, 0, 0, 0, 2, 0, 0, 0, 3);
    glm::mat4 tr(1.0f);
    tr[3] = glm::vec4(-1, 0.25f, 4, 1);
    expect_matrix_near(t.matrix(), tr * rz * ry * rx * s);
}

TEST(CameraSpec, LookAtBuildsTheSameCameraAsCameraLookAt) {
    CameraSpec spec;
    spec.model = CameraSpec::Model::LookAt;
    spec.eye = vec3(1, 2, 3);
    spec.target = vec3(0, 0.5f, -1);
    spec.up = vec3(0, 1, 0);
    spec.vfov_deg = 40;
    Camera cam = spec.build(640, 480);
    Camera ref = Camera::look_at(640, 480, spec.eye, spec.target, spec.up, 40);
    EXPECT_FLOAT_EQ(cam.cx(), 319.5f);
    EXPECT_FLOAT_EQ(cam.cy(), 239.5f);
    EXPECT_NEAR(cam.fy(), 240.0f / std::tan(glm::radians(20.0f)), 1e-3f);
    vec3 point(0.3f, 0.9f, -0.5f);
    vec2 got, want;
    ASSERT_TRUE(cam.project(point, got));
    ASSERT_TRUE(ref.project(point, want));
    EXPECT_FLOAT_EQ(got.x, want.x);
    EXPECT_FLOAT_EQ(got.y, want.y);
}

TEST(CameraSpec, IntrinsicsBuildTheSameCameraAsTheConstructor) {
    CameraSpec spec;
    spec.model = CameraSpec::Model::Intrinsics;
    spec.fx = 800;
    spec.fy = 790;
    spec.cx = 330;
    spec.cy = 250;
    spec.distortion = Distortion{-0.1f, 0.02f, 0.001f, -0.001f, 0.003f};
    spec.rotation = glm::mat3(rows(0, 0, 1, 0, 1, 0, -1, 0, 0));
    spec.translation = vec3(0.1f, -0.2f, 2.0f);
    Camera cam = spec.build(640, 480);
    EXPECT_EQ(cam.width(), 640);
    EXPECT_EQ(cam.height(), 480);
    Camera ref(640, 480, 800, 790, 330, 250, spec.distortion, spec.rotation, spec.translation);
    vec3 point(-1.5f, 0.4f, 0.3f);
    vec2 got, want;
    ASSERT_TRUE(cam.project(point, got));
    ASSERT_TRUE(ref.project(point, want));
    EXPECT_FLOAT_EQ(got.x, want.x);
    EXPECT_FLOAT_EQ(got.y, want.y);
}

TEST(CameraSpec, EqualityIgnoresTheInactiveModel) {
    CameraSpec a, b;
    b.fx = 123;  // intrinsics fields do not describe a look-at camera
    EXPECT_EQ(a, b);
    b.vfov_deg = 50;
    EXPECT_NE(a, b);
    a.model = b.model = CameraSpec::Model::Intrinsics;
    EXPECT_NE(a, b);  // now fx matters
    a.fx = 123;
    EXPECT_EQ(a, b);
    a.distortion.k2 = 0.1f;
    EXPECT_NE(a, b);
}

TEST(Project, ResolveKeepsAbsolutePathsAndJoinsRelativeOnes) {
    Project p;
    p.base_dir = "/data/scenes/kitchen";
    EXPECT_EQ(p.resolve("photo.exr"), std::filesystem::path("/data/scenes/kitchen/photo.exr"));
    EXPECT_EQ(p.resolve("../probes/p.hdr").lexically_normal(),
              std::filesystem::path("/data/scenes/probes/p.hdr"));
    EXPECT_EQ(p.resolve("/elsewhere/bunny.obj"), std::filesystem::path("/elsewhere/bunny.obj"));
}

TEST(Project, EqualityIgnoresBaseDir) {
    Project a, b;
    a.base_dir = "/one";
    b.base_dir = "/two";
    EXPECT_EQ(a, b);
    b.render.seed = 7;
    EXPECT_NE(a, b);
}

TEST(Shape, AZUpMeshFileIsTurnedSoItsUpIsPlusYAndItsFrontFacesPlusZ) {
    Shape s;
    s.kind = Shape::Kind::Mesh;
    s.up_axis = UpAxis::Z;
    // Blender's up (+Z) becomes +Y; its front view looks along +Y at the model's -Y side,
    // which faces +Z here as Blender's exporters to +Y up put it.
    expect_vec_near(apply(s.file_frame(), vec3(0, 0, 1)), vec3(0, 1, 0));
    expect_vec_near(apply(s.file_frame(), vec3(0, -1, 0)), vec3(0, 0, 1));
    expect_vec_near(apply(s.file_frame(), vec3(1, 0, 0)), vec3(1, 0, 0));
}

TEST(Shape, EveryUpAxisIsTurnedToPlusYByAProperRotationAndUnitScaleScalesAfter) {
    const vec3 up_in_file[] = {vec3(0, 1, 0), vec3(0, 0, 1), vec3(0, -1, 0), vec3(0, 0, -1)};
    for (const auto& [name, axis] : kUpAxes) {
        SCOPED_TRACE(name);
        Shape s;
        s.kind = Shape::Kind::Mesh;
        s.up_axis = axis;
        s.unit_scale = 0.01f;
        const glm::mat4 m = s.file_frame();
        expect_vec_near(apply(m, 100.0f * up_in_file[int(axis)]), vec3(0, 1, 0));
        EXPECT_NEAR(glm::determinant(glm::mat3(m)), 1e-6f, 1e-9f);  // no mirroring: windings kept
        EXPECT_EQ(std::string(up_axis_name(axis)), name);
    }
}

TEST(Shape, OnlyMeshesHaveAFileFrame) {
    Shape box;
    box.kind = Shape::Kind::Box;
    box.unit_scale = 0.01f;  // meaningless for a box, and ignored
    box.up_axis = UpAxis::Z;
    expect_matrix_near(box.file_frame(), glm::mat4(1.0f));
}
