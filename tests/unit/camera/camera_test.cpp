#include <gtest/gtest.h>

#include "camera/camera.h"

#include <glm/gtc/matrix_transform.hpp>

using namespace dp;

TEST(Camera, ProjectingAGeneratedRayPointReturnsThePixel) {
    Distortion d{-0.2f, 0.05f, 0.001f, -0.002f, 0.01f};
    glm::mat3 R = glm::mat3(glm::rotate(glm::mat4(1.0f), 0.3f, vec3(0.2f, 1.0f, 0.1f)));
    Camera cam(640, 480, 500, 510, 321, 239, d, R, vec3(0.1f, -0.2f, 3.0f));
    for (vec2 px : {vec2(0, 0), vec2(320, 240), vec2(639, 479), vec2(100, 400)}) {
        Ray ray = cam.generate_ray(px.x, px.y);
        vec2 back;
        ASSERT_TRUE(cam.project(ray.org + 2.5f * ray.dir, back));
        EXPECT_NEAR(back.x, px.x, 1e-2);
        EXPECT_NEAR(back.y, px.y, 1e-2);
    }
}

TEST(Camera, LookAtPutsTheTargetAtTheImageCentre) {
    Camera cam = Camera::look_at(101, 51, vec3(1, 2, 3), vec3(0, 0.5f, -1), vec3(0, 1, 0), 40);
    vec2 px;
    ASSERT_TRUE(cam.project(vec3(0, 0.5f, -1), px));
    EXPECT_NEAR(px.x, 50.0f, 1e-3);
    EXPECT_NEAR(px.y, 25.0f, 1e-3);
    // World up appears towards the top of the image (smaller y).
    ASSERT_TRUE(cam.project(vec3(0, 1.5f, -1), px));
    EXPECT_LT(px.y, 25.0f);
    EXPECT_NEAR(glm::length(cam.position() - vec3(1, 2, 3)), 0.0f, 1e-5);
}

TEST(Camera, PointsBehindTheCameraDoNotProject) {
    Camera cam = Camera::look_at(64, 64, vec3(0, 0, 0), vec3(0, 0, -1), vec3(0, 1, 0), 60);
    vec2 px;
    EXPECT_FALSE(cam.project(vec3(0, 0, 1), px));
}
