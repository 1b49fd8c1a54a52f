#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <utility>

#include "geometry/mesh.h"
#include "mesh_checks.h"

using namespace dp;
using namespace dp::test;

namespace {

/// Every triangle's geometric normal points away from the origin (for shapes centred on it).
bool all_triangles_face_away_from_origin(const TriangleMesh& m) {
    for (size_t i = 0; i < m.triangle_count(); ++i) {
        const glm::uvec3 t = m.triangles[i];
        const vec3 centroid = (m.positions[t.x] + m.positions[t.y] + m.positions[t.z]) / 3.0f;
        if (glm::dot(geometric_normal(m, i), centroid) <= 0.0f) return false;
    }
    return true;
}

void expect_consistent_attributes(const TriangleMesh& m) {
    EXPECT_EQ(m.normals.size(), m.positions.size());
    EXPECT_EQ(m.uvs.size(), m.positions.size());
    for (const glm::uvec3& t : m.triangles) {
        ASSERT_LT(glm::max(t.x, glm::max(t.y, t.z)), m.positions.size());
    }
}

}  // namespace

TEST(Primitives, PlaneNormalsPointUpAndAgreeWithWinding) {
    TriangleMesh m = make_plane(2.0f, 3.0f);
    expect_consistent_attributes(m);
    ASSERT_EQ(m.triangle_count(), 2u);
    for (const vec3& n : m.normals) EXPECT_EQ(n, vec3(0, 1, 0));
    for (size_t i = 0; i < m.triangle_count(); ++i) {
        const vec3 g = glm::normalize(geometric_normal(m, i));
        EXPECT_NEAR(g.y, 1.0f, 1e-6f);
    }
    EXPECT_NEAR(surface_area(m), 6.0, 1e-5);
    vec3 lo, hi;
    ASSERT_TRUE(m.bounds(lo, hi));
    EXPECT_EQ(lo, vec3(-1.0f, 0.0f, -1.5f));
    EXPECT_EQ(hi, vec3(1.0f, 0.0f, 1.5f));
}

TEST(Primitives, PlaneUvsCoverTheUnitSquare) {
    TriangleMesh m = make_plane(4.0f, 1.0f);
    vec2 lo(1e9f), hi(-1e9f);
    for (const vec2& uv : m.uvs) {
        lo = glm::min(lo, uv);
        hi = glm::max(hi, uv);
    }
    EXPECT_EQ(lo, vec2(0.0f));
    EXPECT_EQ(hi, vec2(1.0f));
    // u follows +X, v follows -Z from 0 on the +Z edge: the renderer reads the image's top row
    // at v = 0, so the top lies along +Z (docs/reconstruction.md). Loading mesh files flips
    // their v; the built-in plane must keep this layout, which estimated albedo textures use.
    for (size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_FLOAT_EQ(m.uvs[i].x, m.positions[i].x / 4.0f + 0.5f);
        EXPECT_FLOAT_EQ(m.uvs[i].y, 0.5f - m.positions[i].z / 1.0f);
    }
}

TEST(Primitives, BoxNormalsPointOutwardAndAgreeWithWinding) {
    TriangleMesh m = make_box(vec3(1.0f, 2.0f, 3.0f));
    expect_consistent_attributes(m);
    EXPECT_EQ(m.positions.size(), 24u);
    EXPECT_EQ(m.triangle_count(), 12u);
    EXPECT_TRUE(all_triangles_face_away_from_origin(m));
    // Flat faces: each vertex normal equals its triangle's geometric normal.
    EXPECT_GT(min_winding_agreement(m), 0.9999f);
    EXPECT_GT(signed_volume(m), 0.0);
}

TEST(Primitives, BoxAreaIsTwiceTheSumOfFaceAreasAndItEnclosesItsVolume) {
    const vec3 s(1.0f, 2.0f, 3.0f);
    TriangleMesh m = make_box(s);
    EXPECT_NEAR(surface_area(m), 2.0 * (s.x * s.y + s.y * s.z + s.z * s.x), 1e-4);
    EXPECT_NEAR(signed_volume(m), s.x * s.y * s.z, 1e-4);
    vec3 lo, hi;
    ASSERT_TRUE(m.bounds(lo, hi));
    EXPECT_EQ(lo, -0.5f * s);
    EXPECT_EQ(hi, 0.5f * s);
}

TEST(Primitives, SphereNormalsPointOutwardAndAgreeWithWinding) {
    const float r = 2.0f;
    TriangleMesh m = make_uv_sphere(r, 32, 16);
    expect_consistent_attributes(m);
    EXPECT_TRUE(all_triangles_face_away_from_origin(m));
    EXPECT_GT(min_winding_agreement(m), 0.9f);
    for (size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::distance(m.normals[i] * r, m.positions[i]), 0.0f, 1e-5f);
    }
}

TEST(Primitives, SphereHasNoDegenerateTrianglesEvenAtThePoles) {
    for (auto [segments, rings] : {std::pair{96, 48}, std::pair{3, 2}, std::pair{7, 3}}) {
        TriangleMesh m = make_uv_sphere(1.0f, segments, rings);
        EXPECT_EQ(m.triangle_count(), size_t(2 * segments * (rings - 1)));
        for (size_t i = 0; i < m.triangle_count(); ++i) {
            ASSERT_GT(glm::length(geometric_normal(m, i)), 1e-6f)
                << "triangle " << i << " of " << segments << "x" << rings;
        }
        EXPECT_GT(signed_volume(m), 0.0);
    }
}

TEST(Primitives, SphereAreaAndVolumeAreWithinHalfAPercentOfAnalytic) {
    const double r = 1.5;
    TriangleMesh m = make_uv_sphere(float(r));
    const double area = 4.0 * glm::pi<double>() * r * r;
    const double volume = 4.0 / 3.0 * glm::pi<double>() * r * r * r;
    EXPECT_NEAR(surface_area(m) / area, 1.0, 0.005);
    EXPECT_NEAR(signed_volume(m) / volume, 1.0, 0.005);
}

TEST(Primitives, SphereUvsSpanTheUnitSquare) {
    TriangleMesh m = make_uv_sphere(1.0f, 12, 6);
    for (const vec2& uv : m.uvs) {
        EXPECT_GE(uv.x, 0.0f);
        EXPECT_LE(uv.x, 1.0f);
        EXPECT_GE(uv.y, 0.0f);
        EXPECT_LE(uv.y, 1.0f);
    }
    // v is 1 at the north pole (+Y) and 0 at the south pole.
    for (size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_NEAR(m.uvs[i].y, 1.0f - std::acos(glm::clamp(m.normals[i].y, -1.0f, 1.0f)) / kPi,
                    1e-5f);
    }
}

TEST(Bounds, AnEmptyMeshHasNoBounds) {
    TriangleMesh m;
    vec3 lo, hi;
    EXPECT_FALSE(m.bounds(lo, hi));
}

TEST(Transform, MovesPositionsByTheAffineMap) {
    TriangleMesh m = make_box(vec3(2.0f));
    m.transform(glm::translate(glm::mat4(1.0f), vec3(1, 2, 3)) *
                glm::scale(glm::mat4(1.0f), vec3(1, 2, 3)));
    vec3 lo, hi;
    ASSERT_TRUE(m.bounds(lo, hi));
    EXPECT_EQ(lo, vec3(0, 0, 0));
    EXPECT_EQ(hi, vec3(2, 4, 6));
}

TEST(Transform, NormalsStayPerpendicularToEdgesUnderNonUniformScaleAndShear) {
    glm::mat4 shear(1.0f);
    shear[1][0] = 0.7f;  // x += 0.7 y
    shear[2][1] = -0.4f;  // y -= 0.4 z
    const glm::mat4 m = glm::rotate(glm::mat4(1.0f), 0.6f, vec3(1, 2, 0.5f)) * shear *
                        glm::scale(glm::mat4(1.0f), vec3(0.2f, 3.0f, 1.5f));
    for (TriangleMesh mesh : {make_box(vec3(1, 2, 3)), make_plane(2, 5)}) {
        mesh.transform(m);
        for (const glm::uvec3& t : mesh.triangles) {
            const vec3 e0 = glm::normalize(mesh.positions[t.y] - mesh.positions[t.x]);
            const vec3 e1 = glm::normalize(mesh.positions[t.z] - mesh.positions[t.x]);
            for (unsigned v : {t.x, t.y, t.z}) {
                EXPECT_NEAR(glm::length(mesh.normals[v]), 1.0f, 1e-5f);
                EXPECT_NEAR(glm::dot(mesh.normals[v], e0), 0.0f, 1e-5f);
                EXPECT_NEAR(glm::dot(mesh.normals[v], e1), 0.0f, 1e-5f);
            }
        }
        EXPECT_GT(min_winding_agreement(mesh), 0.9999f);
    }
}

TEST(Transform, ScaledSphereNormalsFollowTheEllipsoidGradient) {
    const vec3 s(1.0f, 2.0f, 0.5f);
    TriangleMesh m = make_uv_sphere(1.0f, 24, 12);
    m.transform(glm::scale(glm::mat4(1.0f), s));
    for (size_t i = 0; i < m.positions.size(); ++i) {
        const vec3 expected = glm::normalize(m.positions[i] / (s * s));
        EXPECT_NEAR(glm::dot(m.normals[i], expected), 1.0f, 1e-5f);
    }
}

TEST(Transform, MirroringKeepsNormalsOutwardAndInAgreementWithWinding) {
    TriangleMesh m = make_uv_sphere(1.0f, 16, 8);
    m.transform(glm::scale(glm::mat4(1.0f), vec3(-1.0f, 1.0f, 2.0f)));
    EXPECT_TRUE(all_triangles_face_away_from_origin(m));
    EXPECT_GT(min_winding_agreement(m), 0.5f);
    EXPECT_GT(signed_volume(m), 0.0);
    for (size_t i = 0; i < m.positions.size(); ++i) {
        EXPECT_GT(glm::dot(m.normals[i], m.positions[i]), 0.0f);
    }
}
