#pragma once
// Synthetic photographs of small real scenes, rendered by the reference path tracer.
#include <algorithm>
#include <memory>
#include <vector>

#include "common/test_scenes.h"
#include "probe/synthetic_probe.h"
#include "reference/path_tracer.h"

namespace dp::test {

/// A sun with a blue sky; the sun is `sun_dir` (probe space) with a 2 degree radius.
inline Image sky_probe(vec3 sun_dir, int w = 128, int h = 64) {
    return make_sun_sky_probe(w, h, sun_dir, vec3(4000.0f), 2.0f, vec3(0.25f, 0.35f, 0.6f),
                              vec3(0.5f, 0.55f, 0.65f));
}

/// A 64 x 64 ground texture in two tones split at u = 1/2 (left warm, right cool).
inline vec3 two_tone(float u) { return u < 0.5f ? vec3(0.7f, 0.5f, 0.3f) : vec3(0.2f, 0.3f, 0.45f); }
inline Image two_tone_texture(int size = 64) {
    Image t(size, size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) t.at(x, y) = two_tone((x + 0.5f) / size);
    return t;
}

/// Renders the real proxies of `p` (textures given per proxy) as the photograph would show them,
/// then returns the scene an artist would start from: that photo, the same probe, and the
/// proxies' albedos reset to a constant (they are what is to be estimated).
inline std::shared_ptr<RenderScene> photographed(Project p, const Image& probe, std::vector<Image> textures,
                                                 int w, int h, int spp, Image* photo_out = nullptr) {
    SceneAssets truth;
    truth.photo = Image(w, h);
    truth.probe_latlong = probe;
    truth.real_textures = textures;
    for (size_t i = 0; i < textures.size(); ++i)
        if (!textures[i].empty()) p.real[i].albedo.kind = Albedo::Kind::Texture;
    RenderScene truth_scene(p, std::move(truth));
    ReferenceOptions o;
    o.samples_per_pixel = spp;
    o.include_virtual = false;
    o.show_probe = false;
    Image photo = render_reference(truth_scene, o);
    if (photo_out) *photo_out = photo;
    for (RealProxy& r : p.real) r.albedo = Albedo{};
    return build(p, std::move(photo), probe);
}

/// A 6 x 6 m two-tone ground and a grey box casting a shadow on it, under a sun and sky.
struct GroundAndBox {
    Project project = look_at_project(vec3(0.3f, 3.0f, 5.0f), vec3(0, 0, -0.2f), 50.0f);
    Image probe = sky_probe(vec3(0.6f, 0.45f, 0.35f));
    vec3 box_albedo{0.5f, 0.45f, 0.4f};
    GroundAndBox() {
        project.real.push_back(ground_plane(vec3(0.5f), 6.0f));
        RealProxy box;
        box.name = "box";
        box.shape.kind = Shape::Kind::Box;
        box.shape.size = vec3(0.8f);
        box.transform.translation = vec3(-0.6f, 0.4f, 0.3f);
        box.albedo.rgb = box_albedo;
        project.real.push_back(box);
    }
    std::shared_ptr<RenderScene> photo(int spp) {
        return photographed(project, probe, {two_tone_texture(), Image()}, 160, 120, spp);
    }
};

}  // namespace dp::test
