// A camera inside a virtual object, or with its eye on the object's surface: the object is seen
// from inside or not at all, never as a self-hit at the eye.
#include <gtest/gtest.h>

#include "common/test_scenes.h"
#include "reference/path_tracer.h"
#include "render/progressive.h"

using namespace dp;
using namespace dp::test;

TEST(CameraContact, ACameraInsideADiffuseSphereSeesExactlyBlack) {
    // Inside a closed diffuse sphere no probe light arrives: every pixel is the sphere's inner
    // wall, black, whatever the photo says.
    SunProbe sun;
    Project p = look_at_project(vec3(0, 1, 0), vec3(0, 1, -1), 60);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.objects.push_back(sphere(vec3(0, 1, 0.2f), 0.5f, diffuse(vec3(0.8f))));
    auto scene = build(p, Image(48, 36, vec3(0.3f)), sun.image());
    ProgressiveRenderer r(scene, settings(50000, 2));
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(r.render_pass());
    Image out = r.image(), alpha = r.alpha_layer();
    // Check: every pixel exactly 0 and fully covered by the object.
    for (size_t i = 0; i < out.size(); ++i) {
        ASSERT_EQ(out[i], vec3(0)) << "pixel " << i;
        ASSERT_EQ(alpha[i], vec3(1)) << "pixel " << i;
    }
}

TEST(CameraContact, ACameraOnASpheresSurfaceLookingOutwardDoesNotSeeIt) {
    // The eye lies on the surface (to float precision); the camera looks away from the centre.
    SunProbe sun;
    sun.px = 0;
    sun.py = 2;  // overhead: the shadow falls under the sphere, out of view
    for (float s : {1e-3f, 1.0f, 1e4f}) {
        const vec3 c = vec3(0, 1.2f, 0) * s;
        const float radius = 0.4f * s;
        const vec3 out_dir = glm::normalize(vec3(0.2f, -0.3f, -1));
        const vec3 eye = c + radius * out_dir;
        Project p = look_at_project(eye, eye + out_dir * s, 50);
        p.real.push_back(ground_plane(vec3(0.5f), 40 * s));
        p.objects.push_back(sphere(c, radius, diffuse(vec3(0.8f))));
        auto scene = build(p, analytic_ground_photo(p, 48, 36, sun, vec3(0.5f)), sun.image());
        ProgressiveRenderer r(scene, settings(50000, 2));
        for (int i = 0; i < 2; ++i) ASSERT_TRUE(r.render_pass());
        Image out = r.image(), alpha = r.alpha_layer();
        // Check: no pixel sees the sphere (no self-hit at the eye), and all are finite.
        size_t covered = 0;
        for (size_t i = 0; i < out.size(); ++i) covered += alpha[i].x > 0;
        EXPECT_EQ(covered, 0u) << "scale " << s;
        for (size_t i = 0; i < out.size(); ++i) ASSERT_TRUE(is_finite(out[i])) << "scale " << s;
    }
}

TEST(CameraContact, AReferenceRenderFromTheSurfaceLooksPastTheSphere) {
    // The same contact for the path tracer: the eye on the surface, looking away from the centre.
    SunProbe sun;
    const vec3 c(0, 1.2f, 0);
    const float radius = 0.4f;
    const vec3 out_dir = glm::normalize(vec3(-0.3f, -0.2f, -1));
    const vec3 eye = c + radius * out_dir;
    Project p = look_at_project(eye, eye + out_dir, 50);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.objects.push_back(sphere(c, radius, diffuse(vec3(0.8f))));
    auto scene = build(p, Image(32, 24), sun.image());
    // Check: every camera ray that meets nothing real sees the probe (black here but the sun),
    // so a pixel whose ray hits the sphere at the eye would differ from the real-only render.
    ReferenceOptions o;
    o.samples_per_pixel = 2;
    Image with = render_reference(*scene, o);
    o.include_virtual = false;
    Image without = render_reference(*scene, o);
    size_t differ = 0;
    for (size_t i = 0; i < with.size(); ++i) differ += std::abs(luminance(with[i]) - luminance(without[i])) >
                                                        0.5f * std::max(luminance(without[i]), 1e-3f);
    EXPECT_LT(differ, with.size() / 20);
    for (size_t i = 0; i < with.size(); ++i) ASSERT_TRUE(is_finite(with[i]));
}
