// NaN and Inf in the inputs (albedo textures of real proxies and virtual objects, photo pixels)
// are replaced by 0 before rendering, counted, and never reach the output.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/test_scenes.h"
#include "image/image_io.h"
#include "render/progressive.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr int kW = 64, kH = 48;

Image gradient_texture(int w, int h) {
    Image t(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) t.at(x, y) = vec3(0.2f + 0.6f * x / w, 0.3f, 0.2f + 0.6f * y / h);
    return t;
}

Project textured_project() {
    Project p = look_at_project(vec3(0, 2.0f, 3.2f), vec3(0, 0.4f, 0), 45);
    RealProxy ground = ground_plane(vec3(0.5f), 4.0f);  // the texture spans the part in view
    ground.albedo.kind = Albedo::Kind::Texture;
    p.real.push_back(ground);
    Material m = diffuse(vec3(0.5f));
    m.albedo.kind = Albedo::Kind::Texture;
    p.objects.push_back(sphere(vec3(0, 0.55f, 0), 0.5f, m));
    return p;
}

struct Inputs {
    Image photo, ground_texture, sphere_texture;
};

/// Clean inputs, and the same with NaN/Inf written into the photo and both textures (every
/// texel of a 4x4 block, so bilinear lookups there read nothing else).
std::pair<Inputs, Inputs> clean_and_poisoned(size_t& poisoned_channels) {
    Inputs clean{Image(kW, kH, vec3(0.25f)), gradient_texture(32, 32), gradient_texture(32, 16)};
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) clean.photo.at(x, y) = vec3(0.1f + 0.3f * x / kW, 0.2f, 0.3f);
    Inputs bad = clean;
    poisoned_channels = 0;
    auto poison = [&](Image& clean_img, Image& img, int x0, int y0) {
        for (int y = y0; y < y0 + 4; ++y)
            for (int x = x0; x < x0 + 4; ++x) {
                img.at(x, y) = vec3(NAN, (x + y) % 2 ? INFINITY : -INFINITY, NAN);
                clean_img.at(x, y) = vec3(0);  // what a load replaces them with
                poisoned_channels += 3;
            }
    };
    poison(clean.photo, bad.photo, 30, 30);  // a ground pixel near the shadow
    poison(clean.photo, bad.photo, 30, 14);  // a pixel the sphere covers
    poison(clean.ground_texture, bad.ground_texture, 14, 14);
    poison(clean.sphere_texture, bad.sphere_texture, 6, 6);
    return {clean, bad};
}

std::shared_ptr<RenderScene> scene_of(const Inputs& in, const Image& probe) {
    SceneAssets a;
    a.photo = in.photo;
    a.probe_latlong = probe;
    a.real_textures = {in.ground_texture};
    a.object_textures = {in.sphere_texture};
    return std::make_shared<RenderScene>(textured_project(), std::move(a));
}

Image render(const std::shared_ptr<RenderScene>& scene, size_t* bad_samples = nullptr) {
    ProgressiveRenderer r(scene, settings(20000, 4));
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(r.render_pass());
    if (bad_samples) *bad_samples = r.stats().non_finite_samples;
    return r.image();
}

}  // namespace

TEST(NonFiniteInputs, NaNInTexturesAndPhotoRendersExactlyAsZerosThere) {
    size_t poisoned = 0;
    auto [clean, bad] = clean_and_poisoned(poisoned);
    Image probe = make_sun_sky_probe(128, 64, glm::normalize(vec3(1, 1.3f, 0.4f)), vec3(400.0f), 5.0f,
                                     vec3(0.2f, 0.35f, 0.8f), vec3(0.7f, 0.8f, 0.9f));
    auto bad_scene = scene_of(bad, probe);
    // Check 1: the scene replaced and counted every poisoned channel.
    EXPECT_EQ(bad_scene->assets().non_finite_replaced, poisoned);
    EXPECT_FALSE(bad_scene->assets().warnings.empty());
    size_t bad_samples = 0;
    Image out = render(bad_scene, &bad_samples);
    // Check 2: no NaN/Inf pixel, no sample even had to be discarded.
    for (size_t i = 0; i < out.size(); ++i) ASSERT_TRUE(is_finite(out[i])) << "pixel " << i;
    EXPECT_EQ(bad_samples, 0u);
    // Check 3: no artefact beyond the poisoned texels themselves: the image is, bit for bit, the
    // one rendered from inputs holding 0 where the NaN/Inf were.
    Image expected = render(scene_of(clean, probe));
    EXPECT_TRUE(out == expected);
}

TEST(NonFiniteInputs, NaNInAnAlbedoTextureFileIsReplacedAndReportedOnLoad) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("dp_nan_texture_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    Image tex = gradient_texture(16, 16);
    tex.at(3, 4) = vec3(NAN, 0.5f, INFINITY);
    save_exr((dir / "tex.exr").string(), {{"", &tex}});
    Image photo(8, 8, vec3(0.2f));
    save_exr((dir / "photo.exr").string(), {{"", &photo}});
    Image probe = make_constant_probe(16, 8, vec3(1.0f));
    save_exr((dir / "probe.exr").string(), {{"", &probe}});
    Project p = textured_project();
    p.base_dir = dir;
    p.photo.path = "photo.exr";
    p.probe.path = "probe.exr";
    p.real[0].albedo.texture_path = "tex.exr";
    p.objects[0].material.albedo.texture_path = "tex.exr";
    SceneAssets a = load_assets(p);
    std::filesystem::remove_all(dir);
    // Check: both uses of the file count its two bad channels, and no texel stays non-finite.
    EXPECT_EQ(a.non_finite_replaced, 4u);
    ASSERT_EQ(a.real_textures.size(), 1u);
    ASSERT_EQ(a.object_textures.size(), 1u);
    for (const Image* t : {&a.real_textures[0], &a.object_textures[0]})
        for (size_t i = 0; i < t->size(); ++i) ASSERT_TRUE(is_finite((*t)[i]));
    bool warned = false;
    for (const std::string& w : a.warnings) warned |= w.find("NaN") != std::string::npos;
    EXPECT_TRUE(warned);
}
