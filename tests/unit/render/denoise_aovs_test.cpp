// The denoiser's guides: a surface's albedo where the camera sees it directly, the albedo seen
// in a mirror times its reflectance, the reflectance alone where the mirror shows the sky.
#include "render/denoise_aovs.h"

#include <gtest/gtest.h>

#include "common/test_scenes.h"

using namespace dp;
using namespace dp::test;

TEST(DenoiseAovs, AlbedoAndNormalFollowWhatEachPixelCentreSees) {
    SunProbe sun;
    Project p = look_at_project(vec3(0, 1.6f, 4), vec3(0, 0.6f, 0), 50);
    const vec3 ground(0.4f), clay(0.8f, 0.3f, 0.2f), chrome(0.5f);
    p.real.push_back(ground_plane(ground));
    p.objects.push_back(sphere(vec3(-0.8f, 0.5f, 0), 0.5f, diffuse(clay)));
    p.objects.push_back(sphere(vec3(0.8f, 0.5f, 0), 0.5f, mirror(chrome)));
    auto scene = build(p, Image(96, 72, vec3(0.3f)), sun.image());
    const DenoiseAovs aovs = denoise_aovs(*scene);
    ASSERT_EQ(aovs.albedo.width(), 96);
    ASSERT_EQ(aovs.normal.height(), 72);

    auto pixel_of = [&](vec3 world) {
        vec2 px;
        EXPECT_TRUE(scene->camera().project(world, px));
        return glm::ivec2(int(std::lround(px.x)), int(std::lround(px.y)));
    };
    const glm::ivec2 floor = pixel_of(vec3(0, 0, 1.5f)), ball = pixel_of(vec3(-0.8f, 0.5f, 0.5f));
    const vec3 floor_albedo = aovs.albedo.at(floor.x, floor.y);
    EXPECT_NEAR(floor_albedo.x, ground.x, 1e-5f);
    EXPECT_NEAR(aovs.normal.at(floor.x, floor.y).y, 1.0f, 1e-4f);
    const vec3 ball_albedo = aovs.albedo.at(ball.x, ball.y);
    EXPECT_NEAR(ball_albedo.x, clay.x, 1e-5f);
    EXPECT_NEAR(ball_albedo.z, clay.z, 1e-5f);

    // Down the mirror's middle column: its upper part reflects the sky, its lower the floor.
    const glm::ivec2 top = pixel_of(vec3(0.8f, 0.9f, 0.3f)), bottom = pixel_of(vec3(0.8f, 0.12f, 0.3f));
    EXPECT_NEAR(aovs.albedo.at(top.x, top.y).x, chrome.x, 1e-5f);
    EXPECT_NEAR(aovs.albedo.at(bottom.x, bottom.y).x, chrome.x * ground.x, 1e-5f);
    for (size_t i = 0; i < aovs.normal.size(); ++i) {
        const float len = glm::length(aovs.normal[i]);
        ASSERT_TRUE(len == 0 || std::abs(len - 1) < 1e-4f) << "pixel " << i;
    }
}

TEST(DenoiseAovs, AStopAskedForEndsTheWorkWithoutAResult) {
    SunProbe sun;
    Project p = look_at_project(vec3(0, 1.6f, 4), vec3(0, 0.6f, 0), 50);
    p.real.push_back(ground_plane(vec3(0.4f)));
    auto scene = build(p, Image(64, 48, vec3(0.3f)), sun.image());
    std::atomic<bool> cancel{true};
    EXPECT_THROW(denoise_aovs(*scene, &cancel), std::runtime_error);
    cancel.store(false);
    const DenoiseAovs aovs = denoise_aovs(*scene, &cancel);
    EXPECT_NEAR(aovs.albedo.at(32, 40).x, 0.4f, 1e-5f);
}
