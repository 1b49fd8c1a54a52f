// A clipped sun restored from a lit and a shadowed patch of the floor in a path-traced photo.
#include <gtest/gtest.h>

#include <cmath>

#include "base/error.h"
#include "common/test_scenes.h"
#include "probe/probe_sun.h"
#include "probe/synthetic_probe.h"
#include "reconstruction/sun_from_shadow.h"
#include "reference/path_tracer.h"

using namespace dp;
using namespace dp::test;

namespace {

const vec3 kSunDir = glm::normalize(vec3(-0.5f, 1.0f, -0.4f));

Image sky_with_sun(float sun) {
    return make_sun_sky_probe(256, 128, kSunDir, vec3(sun), 2.0f, vec3(0.25f, 0.4f, 0.9f), vec3(0.7f, 0.8f, 0.9f));
}

/// A grey floor under a real slab standing on legs we do not model, floating 0.6 above it:
/// its shadow falls on the floor in view.
Project slab_scene() {
    Project p = look_at_project(vec3(0, 2.2f, 3.2f), vec3(0, 0, 0), 50);
    p.real.push_back(ground_plane(vec3(0.5f), 6.0f));  // the sky above the frame's top
    RealProxy slab;
    slab.name = "slab";
    slab.shape.kind = Shape::Kind::Box;
    slab.shape.size = vec3(0.8f, 0.05f, 0.8f);
    slab.transform.translation = vec3(0, 0.6f, 0);
    slab.albedo.rgb = vec3(0.5f);
    p.real.push_back(slab);
    return p;
}

/// The pixel of world point x.
vec2 pixel_of(const RenderScene& scene, const vec3& x) {
    vec2 px;
    EXPECT_TRUE(scene.camera_sees(x, vec3(0, 1, 0), &px));
    return px;
}

}  // namespace

TEST(SunFromShadow, ASunClippedToATwentiethIsRestoredFromThePhotosShadow) {
    const Project p = slab_scene();
    const int w = 96, h = 72;
    // The photograph: the real scene path-traced under the whole sun.
    const auto truth_scene = build(p, Image(w, h), sky_with_sun(2000));
    ReferenceOptions ro;
    ro.samples_per_pixel = 1024;
    ro.include_virtual = false;
    const Image photo = render_reference(*truth_scene, ro);

    // The probe as a camera that clipped its sun would hold it.
    const auto scene = build(p, photo, sky_with_sun(100));
    ASSERT_FALSE(clipped_sun_warning(find_probe_sun(scene->probe().image())).empty());
    // A floor point in the open, and one in the slab's shadow (the sun along kSunDir).
    const vec3 shadowed = vec3(0, 0.6f, 0) - kSunDir * (0.6f / kSunDir.y);
    SunShadowPatches patches;
    patches.lit = pixel_of(*scene, vec3(1.1f, 0, 0.6f));
    patches.shadow = pixel_of(*scene, vec3(shadowed.x, 0, shadowed.z));
    const SunFromShadow m = match_sun_to_shadow(*scene, patches);
    std::printf("photo contrast %.3f, probe %.3f before; scale %.3f (exact 20)\n", m.photo_contrast,
                m.probe_contrast, double(m.scale));
    EXPECT_GT(m.photo_contrast, 3 * m.probe_contrast);
    // The light the slab's underside sends down into its shadow is in the model (one bounce);
    // left out, the scale came out 13.6.
    EXPECT_NEAR(m.scale / 20.0, 1.0, 0.05);
    EXPECT_FLOAT_EQ(m.sun_scale, m.scale);  // the project's scale was 1

    // The restored probe gives the photo's contrast back.
    Image restored = sky_with_sun(100);
    scale_probe_sun(restored, find_probe_sun(restored), m.scale);
    const auto again = build(p, photo, restored);
    const SunFromShadow check = match_sun_to_shadow(*again, patches);
    EXPECT_NEAR(check.scale, 1.0, 0.01);
    EXPECT_NEAR(check.probe_contrast / check.photo_contrast, 1.0, 0.01);
}

TEST(SunFromShadow, PatchesThatCannotTellAreRefusedWithTheReason) {
    const Project p = slab_scene();
    const int w = 96, h = 72;
    const auto scene = build(p, Image(w, h, vec3(0.2f)), sky_with_sun(100));
    auto reason = [&](vec2 lit, vec2 shadow) {
        SunShadowPatches patches{lit, shadow, 2};
        try {
            match_sun_to_shadow(*scene, patches);
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), "sun_from_shadow");
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    const vec2 floor_a = pixel_of(*scene, vec3(1.1f, 0, 0.6f)), floor_b = pixel_of(*scene, vec3(-1.0f, 0, 0.8f));
    EXPECT_NE(reason(vec2(1, 1), floor_b).find("not inside the photo"), std::string::npos);
    EXPECT_NE(reason(floor_a, vec2(w / 2.0f, 2)).find("shows no real proxy"), std::string::npos);
    EXPECT_NE(reason(floor_a, pixel_of(*scene, vec3(0, 0.625f, 0))).find("two real proxies"), std::string::npos);
    // An even photo: no contrast beyond the sky's.
    EXPECT_NE(reason(floor_a, floor_b).find("is not one the probe's sky"), std::string::npos);
    // No sun at all.
    const auto overcast = build(p, Image(w, h, vec3(0.2f)), make_constant_probe(64, 32, vec3(1)));
    SunShadowPatches patches{floor_a, floor_b, 2};
    EXPECT_THROW(match_sun_to_shadow(*overcast, patches), InputError);
}
