// Where the virtual objects change nothing, the output is the photograph bit for bit.
#include <gtest/gtest.h>

#include "render/progressive.h"
#include "common/test_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {
Image noisy_photo(int w, int h) {
    Image img(w, h);
    Rng rng(5, 9);
    for (size_t i = 0; i < img.size(); ++i) img[i] = vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 3.0f;
    return img;
}
}  // namespace

TEST(Identity, WithoutVirtualObjectsTheOutputIsThePhotoBitForBit) {
    SunProbe sun;
    Project p = look_at_project(vec3(0, 2, 5), vec3(0, 0, 0), 50);
    p.real.push_back(ground_plane(vec3(0.4f)));
    Image photo = noisy_photo(64, 48);
    auto scene = build(p, photo, sun.image());
    ProgressiveRenderer r(scene, settings(10000, 1));
    ASSERT_TRUE(r.render_pass());
    ASSERT_TRUE(r.render_pass());
    EXPECT_TRUE(r.image() == photo);
    EXPECT_EQ(r.stats().pixels_gathered, 0u);
}

TEST(Identity, AVirtualObjectBehindTheCameraLeavesThePhotoBitForBit) {
    SunProbe sun;
    sun.px = 0;  // a sun near the zenith: the shadow falls straight under the object
    sun.py = 2;
    Project p = look_at_project(vec3(0, 2, 5), vec3(0, 0, 0), 50);
    p.real.push_back(ground_plane(vec3(0.4f)));
    // Black, so it bounces no light into view: its only effect is a shadow behind the camera.
    p.objects.push_back(sphere(vec3(0, 1, 9), 0.5f, diffuse(vec3(0.0f))));
    Image photo = noisy_photo(64, 48);
    for (Estimator e : {Estimator::Photons, Estimator::Split}) {
        p.render.estimator = e;
        auto scene = build(p, photo, sun.image());
        ProgressiveRenderer r(scene, settings(50000, 1, p.render));
        for (int i = 0; i < 3; ++i) ASSERT_TRUE(r.render_pass());
        // The object does cast a shadow, out of view: shadow photons under the all-photon
        // estimator, rays under the split one (which stores no photon here).
        if (e == Estimator::Photons) {
            EXPECT_GT(r.stats().photons_stored, 0u);
        }
        EXPECT_TRUE(r.image() == photo);
    }
}
