// A virtual mirror shows the photograph: rays reflected onto real surfaces read the photo
// where the camera sees them.
#include <gtest/gtest.h>

#include "render/camera_gather.h"
#include "common/test_scenes.h"

using namespace dp;
using namespace dp::test;

TEST(Mirror, AReflectedRayReturnsTheBackProjectedPhotoValue) {
    SunProbe sun;
    Project p = look_at_project(vec3(0, 1.6f, 4), vec3(0, 0.6f, 0), 50);
    p.real.push_back(ground_plane(vec3(0.4f)));
    const vec3 c(0, 1, 0);
    const float R = 0.5f;
    p.objects.push_back(sphere(c, R, mirror(vec3(1.0f))));
    const int W = 128, H = 96;
    Image photo(W, H);  // a distinct value in every pixel, so a wrong texel cannot pass
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) photo.at(x, y) = vec3(x / float(W), y / float(H), 0.25f + 0.5f * ((x * 7 + y * 13) % 17) / 17.0f);
    auto scene = build(p, photo, sun.image());
    PassMaps empty;
    empty.radius = 0.01f;
    CameraGather gather(*scene, empty);
    const Camera& cam = scene->camera();
    int checked = 0;
    for (int y = 0; y < H; y += 3)
        for (int x = 0; x < W; x += 3) {
            Ray r = cam.generate_ray(float(x), float(y));
            // Independent analytic sphere hit and reflection.
            vec3 oc = r.org - c;
            float b = glm::dot(oc, r.dir), cc = glm::dot(oc, oc) - R * R, disc = b * b - cc;
            if (disc <= 0) continue;
            vec3 hp = r.org + r.dir * (-b - std::sqrt(disc));
            vec3 n = glm::normalize(hp - c);
            vec3 d = r.dir - 2 * glm::dot(r.dir, n) * n;
            if (d.y >= -0.05f) continue;  // reflects the sky or grazes the ground
            vec3 g = hp + d * (-hp.y / d.y);
            vec2 px;
            if (!cam.project(g, px) || !cam.in_image(px)) continue;
            // The ground point must be visible to the camera (not behind the sphere).
            vec3 to = glm::normalize(g - cam.position());
            vec3 oc2 = cam.position() - c;
            float b2 = glm::dot(oc2, to), disc2 = b2 * b2 - (glm::dot(oc2, oc2) - R * R);
            if (disc2 > 0 && -b2 - std::sqrt(disc2) > 0) continue;
            vec3 expected = photo.bilinear(px.x, px.y);
            Rng rng(1, 1);
            PixelSampler ps(1, 0, 0);
            SampleResult s = gather.shade_camera(x, y, float(x), float(y), ps, rng);
            vec3 got = photo.at(x, y) + s.pixel_change;
            EXPECT_NEAR(got.x, expected.x, 2e-3f) << x << "," << y;
            EXPECT_NEAR(got.y, expected.y, 2e-3f) << x << "," << y;
            EXPECT_NEAR(got.z, expected.z, 2e-3f) << x << "," << y;
            EXPECT_EQ(s.alpha, 1.0f);
            ++checked;
        }
    EXPECT_GT(checked, 20);
}

TEST(Mirror, ReflectionsOfTheSkyShowTheProbe) {
    Project p = look_at_project(vec3(0, 1, 4), vec3(0, 1, 0), 40);
    p.real.push_back(ground_plane(vec3(0.4f)));
    p.objects.push_back(sphere(vec3(0, 1, 0), 0.5f, mirror(vec3(0.5f, 0.8f, 1.0f))));
    Image probe = make_constant_probe(64, 32, vec3(2.0f, 3.0f, 4.0f));
    auto scene = build(p, Image(64, 48), probe);
    PassMaps empty;
    empty.radius = 0.01f;
    CameraGather gather(*scene, empty);
    Rng rng(1, 1);
    // The top of the sphere reflects the sky straight up.
    vec2 top;
    ASSERT_TRUE(scene->camera().project(vec3(0, 1.45f, 0.2f), top));
    PixelSampler ps(1, 0, 0);
    SampleResult s = gather.shade_camera(int(top.x), int(top.y), top.x, top.y, ps, rng);
    EXPECT_NEAR(s.pixel_change.x, 1.0f, 1e-4f);
    EXPECT_NEAR(s.pixel_change.y, 2.4f, 1e-4f);
    EXPECT_NEAR(s.pixel_change.z, 4.0f, 1e-4f);
}
