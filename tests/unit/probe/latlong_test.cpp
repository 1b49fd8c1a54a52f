#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "base/euler.h"
#include "base/rng.h"
#include "base/sampling.h"
#include "probe/probe.h"

using namespace dp;

namespace {

void expect_vec_near(const vec3& a, const vec3& b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// Distance on the circle of u, where 0 and 1 are the same meridian.
float wrapped_distance(float a, float b) {
    float d = std::abs(a - b);
    return std::min(d, 1.0f - d);
}

}  // namespace

TEST(LatLong, DirectionAndUvAreInversesOfEachOther) {
    Rng rng(7, 1);
    for (int k = 0; k < 100000; ++k) {
        float u = rng.uniform(), v = 0.001f + 0.998f * rng.uniform();
        vec3 d = latlong_direction(u, v);
        ASSERT_NEAR(glm::length(d), 1.0f, 1e-6f);
        vec2 uv = latlong_uv(d);
        ASSERT_LT(wrapped_distance(uv.x, u), 2e-6f) << u << " " << v;
        ASSERT_NEAR(uv.y, v, 2e-6f);

        vec3 w = sample_uniform_sphere(vec2(rng.uniform(), rng.uniform()));
        vec2 back = latlong_uv(w);
        vec3 again = latlong_direction(back.x, back.y);
        ASSERT_LT(glm::length(again - w), 2e-6f);
    }
}

TEST(LatLong, AxesFollowTheDocumentedConvention) {
    expect_vec_near(latlong_direction(0.5f, 0.5f), vec3(0, 0, -1), 1e-6f);   // image centre
    expect_vec_near(latlong_direction(0.75f, 0.5f), vec3(1, 0, 0), 1e-6f);   // u = 3/4
    expect_vec_near(latlong_direction(0.25f, 0.5f), vec3(-1, 0, 0), 1e-6f);  // u = 1/4
    expect_vec_near(latlong_direction(0.0f, 0.5f), vec3(0, 0, 1), 1e-6f);    // the seam
    expect_vec_near(latlong_direction(0.3f, 0.0f), vec3(0, 1, 0), 1e-6f);    // top row
    expect_vec_near(latlong_direction(0.3f, 1.0f), vec3(0, -1, 0), 1e-6f);   // bottom row

    vec2 uv = latlong_uv(vec3(0, 0, -1));
    EXPECT_NEAR(uv.x, 0.5f, 1e-6f);
    EXPECT_NEAR(uv.y, 0.5f, 1e-6f);
    uv = latlong_uv(vec3(1, 0, 0));
    EXPECT_NEAR(uv.x, 0.75f, 1e-6f);
    EXPECT_NEAR(uv.y, 0.5f, 1e-6f);
    EXPECT_NEAR(latlong_uv(vec3(0, 1, 0)).y, 0.0f, 1e-6f);

    // In a 64 x 32 map, straight up is in the top row and -Z in the middle of the image.
    EXPECT_EQ(latlong_pixel(vec3(0, 1, 0), 64, 32) / 64, 0u);
    EXPECT_EQ(latlong_pixel(vec3(0.01f, -0.02f, -1), 64, 32), size_t(16 * 64 + 32));
}

TEST(LatLong, UvStaysInsideTheUnitSquareAtTheSeamAndPoles) {
    for (vec3 d : {vec3(0, 0, 1), vec3(1e-7f, 0, 1), vec3(-1e-7f, 0, 1), vec3(1e-30f, 0.3f, 1),
                   vec3(0, -1, 0), vec3(0, 1, 0), vec3(0, -1, 1e-20f), vec3(0),
                   vec3(std::nanf(""), 0, 1)}) {
        vec2 uv = latlong_uv(d);
        EXPECT_GE(uv.x, 0.0f);
        EXPECT_LT(uv.x, 1.0f);
        EXPECT_GE(uv.y, 0.0f);
        EXPECT_LT(uv.y, 1.0f);
        EXPECT_LT(latlong_pixel(d, 64, 32), size_t(64 * 32));
    }
    // Either side of the seam lands in the first or the last column.
    EXPECT_EQ(latlong_pixel(vec3(-1e-3f, 0, 1), 64, 32) % 64, 0u);
    EXPECT_EQ(latlong_pixel(vec3(1e-3f, 0, 1), 64, 32) % 64, 63u);
    // latlong_direction is periodic in u.
    expect_vec_near(latlong_direction(1.2f, 0.4f), latlong_direction(0.2f, 0.4f), 1e-6f);
    expect_vec_near(latlong_direction(-0.1f, 0.4f), latlong_direction(0.9f, 0.4f), 1e-6f);
}

TEST(LatLong, UvIgnoresTheLengthOfTheDirection) {
    vec3 d = glm::normalize(vec3(0.3f, -0.5f, 0.7f));
    vec2 a = latlong_uv(d), b = latlong_uv(42.0f * d), c = latlong_uv(1e-3f * d);
    EXPECT_NEAR(a.x, b.x, 1e-7f);
    EXPECT_NEAR(a.y, b.y, 1e-7f);
    EXPECT_NEAR(a.x, c.x, 1e-7f);
    EXPECT_NEAR(a.y, c.y, 1e-7f);
}

TEST(EulerXyz, AppliesXThenYThenZInDegrees) {
    expect_vec_near(euler_xyz_deg(vec3(90, 0, 0)) * vec3(0, 1, 0), vec3(0, 0, 1), 1e-6f);
    expect_vec_near(euler_xyz_deg(vec3(0, 90, 0)) * vec3(0, 0, 1), vec3(1, 0, 0), 1e-6f);
    expect_vec_near(euler_xyz_deg(vec3(0, 0, 90)) * vec3(1, 0, 0), vec3(0, 1, 0), 1e-6f);
    // X first: +Y -> +Z under X, then Z leaves +Z alone. Z first would give -X.
    expect_vec_near(euler_xyz_deg(vec3(90, 0, 90)) * vec3(0, 1, 0), vec3(0, 0, 1), 1e-6f);
    // Y before Z: +Z -> +X under Y, then +X -> +Y under Z.
    expect_vec_near(euler_xyz_deg(vec3(0, 90, 90)) * vec3(0, 0, 1), vec3(0, 1, 0), 1e-6f);
    glm::mat3 r = euler_xyz_deg(vec3(12, -34, 56));
    glm::mat3 should_be_identity = glm::transpose(r) * r;
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(should_be_identity[c][k], c == k ? 1 : 0, 1e-6f);
}
