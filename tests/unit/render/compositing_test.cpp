// The compositing layers rebuild the beauty over the plate, as docs/compositing.md's recipe does.
#include "render/compositing.h"

#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <filesystem>

#include "common/test_scenes.h"
#include "render/progressive.h"
#include "render/render_output.h"

using namespace dp;
using namespace dp::test;

namespace {

/// A red diffuse ball and a mirror ball on a grey floor under the sun, a few passes.
struct Rendered {
    Image photo, image, dL, alpha;
};

Rendered render_balls() {
    SunProbe sun;
    Project p = look_at_project(vec3(0, 1.5f, 4), vec3(0, 0.3f, 0), 45);
    p.real.push_back(ground_plane(vec3(0.5f, 0.45f, 0.4f)));
    p.objects.push_back(sphere(vec3(-0.5f, 0.4f, 0), 0.4f, diffuse(vec3(0.8f, 0.2f, 0.1f))));
    p.objects.push_back(sphere(vec3(0.6f, 0.35f, 0.2f), 0.35f, mirror()));
    Rendered r;
    r.photo = analytic_ground_photo(p, 96, 64, sun, vec3(0.5f, 0.45f, 0.4f));
    ProgressiveRenderer pr(build(p, r.photo, sun.image()), settings(20000, 3));
    for (int i = 0; i < 4; ++i) pr.render_pass();
    r.image = pr.image();
    r.dL = pr.dL_layer();
    r.alpha = pr.alpha_layer();
    return r;
}

}  // namespace

TEST(Compositing, ObjectsPlusThePlateTimesTheCatcherRebuildTheBeauty) {
    const Rendered r = render_balls();
    const Image objects = objects_premultiplied(r.image, r.photo, r.alpha, r.dL);
    const Image catcher = shadow_catcher(r.photo, r.alpha, r.dL);
    const Image again = recomposite(objects, r.alpha, r.photo, catcher);
    size_t checked = 0;
    for (size_t i = 0; i < again.size(); ++i) {
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(again[i][c], r.image[i][c], 1e-4f * std::max(1.0f, r.image[i][c])) << "pixel " << i;
        ++checked;
    }
    EXPECT_EQ(checked, r.image.size());
}

TEST(Compositing, TheRecipeGivesANoisyBeautyBackExactlyWhereTheCatcherIsHeld) {
    // Few photons, one pass: dL is noisy; a black ball's edge and a black photo channel (no ratio:
    // the catcher held at 1) are where the old recipe missed.
    SunProbe sun;
    Project p = look_at_project(vec3(0, 1.5f, 4), vec3(0, 0.3f, 0), 45);
    p.real.push_back(ground_plane(vec3(0.5f, 0.0f, 0.4f)));
    // A nearly black ball: at its edge the noise of dL outweighs its own light.
    p.objects.push_back(sphere(vec3(-0.5f, 0.4f, 0), 0.4f, diffuse(vec3(0.01f))));
    p.objects.push_back(sphere(vec3(0.6f, 0.3f, 0.3f), 0.3f, glass(1.5f)));  // caustics: noisy dL
    const Image photo = analytic_ground_photo(p, 96, 64, sun, vec3(0.5f, 0.0f, 0.4f));
    ProgressiveRenderer pr(build(p, photo, sun.image()), settings(1500, 5));
    ASSERT_TRUE(pr.render_pass());
    const Image image = pr.image(), dL = pr.dL_layer(), alpha = pr.alpha_layer();
    const Image objects = objects_premultiplied(image, photo, alpha, dL);
    const Image catcher = shadow_catcher(photo, alpha, dL);
    const Image again = recomposite(objects, alpha, photo, catcher);
    // Guard: pixels where the catcher is held and the old recipe (objects = beauty - plate - dL,
    // held at 0) would have missed the beauty.
    size_t held = 0;
    for (size_t i = 0; i < image.size(); ++i) {
        const vec3 old_objects = alpha[i].x > 0 ? glm::max(image[i] - (1 - alpha[i].x) * photo[i] - dL[i], vec3(0.0f)) : vec3(0.0f);
        const vec3 old = old_objects + (1 - alpha[i].x) * photo[i] * catcher[i];
        held += glm::length(old - image[i]) > 1e-3f;
    }
    EXPECT_GT(held, 5u);
    for (size_t i = 0; i < again.size(); ++i)
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(again[i][c], image[i][c], 1e-6f * std::max(1.0f, std::abs(image[i][c]))) << "pixel " << i;
    // Where nothing of the objects is and the catcher is the true ratio, the objects are exactly 0.
    size_t zero = 0;
    for (size_t i = 0; i < image.size(); ++i) zero += alpha[i].x == 0 && objects[i] == vec3(0.0f);
    EXPECT_GT(zero, image.size() / 2);
}

TEST(Compositing, TheCatcherDarkensTheShadowKeepsColourAndLeavesTheRestAtOne) {
    const Rendered r = render_balls();
    const Image catcher = shadow_catcher(r.photo, r.alpha, r.dL);
    const Image objects = objects_premultiplied(r.image, r.photo, r.alpha, r.dL);
    size_t shadowed = 0, untouched = 0;
    for (size_t i = 0; i < catcher.size(); ++i) {
        for (int c = 0; c < 3; ++c) ASSERT_GE(catcher[i][c], 0.0f);
        if (r.alpha[i].x == 0 && r.dL[i] == vec3(0)) {
            ASSERT_EQ(catcher[i], vec3(1.0f)) << "pixel " << i;
            ASSERT_EQ(objects[i], vec3(0.0f)) << "pixel " << i;
            ++untouched;
        }
        if (r.alpha[i].x == 0 && luminance(catcher[i]) < 0.7f) ++shadowed;
    }
    EXPECT_GT(shadowed, 50u);    // the balls' shadows on the floor
    EXPECT_GT(untouched, 1000u); // most of the floor
    // Beside the red ball the floor gains red light more than blue: the ratio keeps colour.
    double red = 0, blue = 0;
    for (size_t i = 0; i < catcher.size(); ++i)
        if (r.alpha[i].x == 0 && catcher[i].x > 1.0f) red += catcher[i].x - 1, blue += std::max(0.0f, catcher[i].z - 1);
    EXPECT_GT(red, blue);
}

TEST(Compositing, TheRenderExrIsRgbaWithObjectsAndCatcherLayers) {
    Rendered r = render_balls();
    RenderUpdate u;
    u.image = r.image;
    u.dL = r.dL;
    u.alpha = r.alpha;
    const std::string path = (std::filesystem::path(::testing::TempDir()) / "compositing_layers.exr").string();
    save_render_exr(path, u, r.photo, true);
    Imf::InputFile file(path.c_str());
    const Imf::ChannelList& ch = file.header().channels();
    for (const char* name : {"R", "G", "B", "A", "objects.R", "objects.A", "catcher.R", "catcher.B", "dL.R", "shadow.R"})
        EXPECT_NE(ch.findChannel(name), nullptr) << name;
    const Image objects = load_exr_layer(path, "objects"), catcher = load_exr_layer(path, "catcher");
    const Image again = recomposite(objects, r.alpha, r.photo, catcher);
    for (size_t i = 0; i < again.size(); ++i)
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(again[i][c], r.image[i][c], 1e-4f * std::max(1.0f, r.image[i][c])) << "pixel " << i;
}
