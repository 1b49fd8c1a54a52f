#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "probe/probe.h"

using namespace dp;

namespace {

constexpr double kPiD = std::numbers::pi;

// A smooth, asymmetric environment (a mirrored unwrap would not match it) with a few bumps per
// hemisphere so that a wrong camera model shows.
vec3 environment(const vec3& d) {
    return vec3(1.0f + 0.5f * d.x + 0.3f * std::sin(4 * d.y + 2 * d.z),
                1.0f + 0.4f * d.y * d.z + 0.4f * std::cos(3 * d.x - d.y),
                1.0f + 0.5f * d.z * std::cos(2 * d.x + 3 * d.y));
}

Image make_map(int w, int h) {
    Image map(w, h);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            map.at(i, j) = environment(latlong_direction((i + 0.5f) / w, (j + 0.5f) / h));
    return map;
}

// Bilinear lookup in a lat-long map, wrapping around in u.
vec3 lookup(const Image& map, const vec3& dir) {
    vec2 uv = latlong_uv(dir);
    float x = uv.x * map.width() - 0.5f;
    float y = std::clamp(uv.y * map.height() - 0.5f, 0.0f, float(map.height() - 1));
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    float fx = x - x0, fy = y - y0;
    int y1 = std::min(y0 + 1, map.height() - 1);
    int xa = (x0 + map.width()) % map.width(), xb = (x0 + 1) % map.width();
    vec3 top = glm::mix(map.at(xa, y0), map.at(xb, y0), fx);
    vec3 bottom = glm::mix(map.at(xa, y1), map.at(xb, y1), fx);
    return glm::mix(top, bottom, fy);
}

// The forward model: photograph a unit mirror ball filling a size x size image, camera looking
// along -Z (orthographic for fov 0, otherwise a pinhole with that vertical field of view).
Image render_ball(const Image& map, int size, float fov_deg) {
    Image ball(size, size);
    double half_fov = fov_deg * kPiD / 360;
    double distance = fov_deg > 0 ? 1 / std::sin(half_fov) : 0;
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            double a = (x + 0.5 - size / 2.0) / (size / 2.0);
            double b = (size / 2.0 - (y + 0.5)) / (size / 2.0);
            dvec3 normal, view;
            if (fov_deg == 0) {
                if (a * a + b * b >= 1) continue;
                normal = dvec3(a, b, std::sqrt(1 - a * a - b * b));
                view = dvec3(0, 0, -1);
            } else {
                dvec3 origin(0, 0, distance);
                view = glm::normalize(dvec3(a * std::tan(half_fov), b * std::tan(half_fov), -1));
                double ov = glm::dot(origin, view);
                double disc = ov * ov - (distance * distance - 1);
                if (disc < 0) continue;
                normal = origin + (-ov - std::sqrt(disc)) * view;
            }
            dvec3 reflected = view - 2 * glm::dot(view, normal) * normal;
            ball.at(x, y) = lookup(map, vec3(reflected));
        }
    }
    return ball;
}

// Mean relative error (|difference| / |reference|), weighted by solid angle, over directions
// more than `exclude_deg` away from the back pole -Z.
double mean_relative_error(const Image& got, const Image& want, double exclude_deg) {
    double sum = 0, weight = 0;
    for (int j = 0; j < want.height(); ++j) {
        double omega = std::sin(kPiD * (j + 0.5) / want.height());
        for (int i = 0; i < want.width(); ++i) {
            vec3 d = latlong_direction((i + 0.5f) / want.width(), (j + 0.5f) / want.height());
            if (std::acos(std::clamp(-d.z, -1.0f, 1.0f)) * 180 / kPiD <= exclude_deg) continue;
            sum += omega * glm::length(got.at(i, j) - want.at(i, j)) / glm::length(want.at(i, j));
            weight += omega;
        }
    }
    return sum / weight;
}

// Bounds on the mean relative error of an unwrapped smooth environment: measured about 1e-4
// (orthographic and 30 degrees) more than 30 degrees from the back pole, and 6e-4 / 7e-3 over
// the whole sphere, where the ball's rim squeezes the back hemisphere into a few pixels.
constexpr double kFrontBound = 0.01, kWholeSphereBound = 0.05;

}  // namespace

TEST(MirrorBall, UnwrappingAnOrthographicBallReproducesTheEnvironment) {
    Image map = make_map(256, 128);
    Image ball = render_ball(map, 512, 0);
    Image unwrapped = unwrap_mirror_ball(ball, 256, 128, 0);
    double error = mean_relative_error(unwrapped, map, 30);
    RecordProperty("mean_relative_error", std::to_string(error));
    EXPECT_LT(error, kFrontBound);
    // The whole sphere, back pole included, still comes out close on average.
    EXPECT_LT(mean_relative_error(unwrapped, map, 0), kWholeSphereBound);
}

TEST(MirrorBall, UnwrappingAPerspectiveBallReproducesTheEnvironment) {
    Image map = make_map(256, 128);
    Image ball = render_ball(map, 512, 30);
    Image unwrapped = unwrap_mirror_ball(ball, 256, 128, 30);
    double error = mean_relative_error(unwrapped, map, 30);
    RecordProperty("mean_relative_error", std::to_string(error));
    EXPECT_LT(error, kFrontBound);
    EXPECT_LT(mean_relative_error(unwrapped, map, 0), kWholeSphereBound);
    // Reading the same photograph as orthographic misplaces directions (about 6% error).
    Image wrong = unwrap_mirror_ball(ball, 256, 128, 0);
    EXPECT_GT(mean_relative_error(wrong, map, 30), 2 * kFrontBound);
}

TEST(MirrorBall, HiddenDirectionsTakeTheNearestValueOnTheBall) {
    // Colour on the ball, black around it: no output direction may pick up the black corners.
    const int size = 200;
    const vec3 colour(0.2f, 0.7f, 1.3f);
    Image ball(size, size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            if (std::hypot(x + 0.5 - size / 2.0, y + 0.5 - size / 2.0) < size / 2.0)
                ball.at(x, y) = colour;
    for (float fov : {0.0f, 30.0f, 90.0f}) {
        Image out = unwrap_mirror_ball(ball, 128, 64, fov);
        for (size_t k = 0; k < out.size(); ++k) {
            ASSERT_NEAR(out[k].x, colour.x, 1e-5f) << "fov " << fov << " pixel " << k;
            ASSERT_NEAR(out[k].y, colour.y, 1e-5f);
            ASSERT_NEAR(out[k].z, colour.z, 1e-5f);
        }
    }
}

TEST(MirrorBall, TheRightSideOfThePhotoIsPlusXAndTheTopIsPlusY) {
    const int size = 64;
    Image ball(size, size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            ball.at(x, y) = vec3(x >= size / 2 ? 1 : 0, y < size / 2 ? 1 : 0, 0);
    for (float fov : {0.0f, 30.0f}) {
        Image out = unwrap_mirror_ball(ball, 64, 32, fov);
        auto at = [&](vec3 d) {
            vec2 uv = latlong_uv(d);
            return out.at(int(uv.x * 64), int(uv.y * 32));
        };
        EXPECT_EQ(at(glm::normalize(vec3(1, 0.3f, 0))), vec3(1, 1, 0)) << fov;
        EXPECT_EQ(at(glm::normalize(vec3(-1, 0.3f, 0))), vec3(0, 1, 0)) << fov;
        EXPECT_EQ(at(glm::normalize(vec3(1, -0.3f, 0))), vec3(1, 0, 0)) << fov;
    }
}

TEST(MirrorBall, RejectsAnEmptyPhotoOrOutputSize) {
    EXPECT_THROW(unwrap_mirror_ball(Image(), 16, 8), std::invalid_argument);
    EXPECT_THROW(unwrap_mirror_ball(Image(4, 4), 0, 8), std::invalid_argument);
    EXPECT_THROW(unwrap_mirror_ball(Image(4, 4), 16, 8, 180), std::invalid_argument);
}
