#include "scene_builder.h"

#include <cmath>

#include "geometry/mesh.h"
#include "image/image_io.h"
#include "probe/probe.h"
#include "assets/scene_checks.h"

namespace dp::ui {

Image resample(const Image& image, int width, int height) {
    if (width == image.width() && height == image.height()) return image;
    Image out(width, height);
    const float sx = float(image.width()) / float(width),
                sy = float(image.height()) / float(height);
    // Averages a small footprint when shrinking so previews do not alias.
    const int taps = std::max(1, int(std::ceil(std::max(sx, sy))));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            vec3 sum(0);
            for (int j = 0; j < taps; ++j)
                for (int i = 0; i < taps; ++i) {
                    const float fx = (x + (i + 0.5f) / taps) * sx - 0.5f;
                    const float fy = (y + (j + 0.5f) / taps) * sy - 0.5f;
                    sum += image.bilinear(fx, fy);
                }
            out.at(x, y) = sum / float(taps * taps);
        }
    return out;
}

CameraSpec scaled_camera(const CameraSpec& c, int photo_w, int photo_h, int width, int height) {
    CameraSpec out = c;
    if (c.model != CameraSpec::Model::Intrinsics || (width == photo_w && height == photo_h))
        return out;
    const float ax = float(width) / float(photo_w), ay = float(height) / float(photo_h);
    out.fx = c.fx * ax;
    out.fy = c.fy * ay;
    out.cx = (c.cx + 0.5f) * ax - 0.5f;
    out.cy = (c.cy + 0.5f) * ay - 0.5f;
    return out;
}

void SceneBuilder::load(const Project& p) {
    const std::string photo_key =
        p.resolve(p.photo.path).string() + "|" + std::to_string(p.photo.exposure);
    if (photo_key != photo_key_ || !photo_) {
        Image photo = load_image(p.resolve(p.photo.path).string(), "photo.path");
        const float gain = std::exp2(p.photo.exposure);
        if (gain != 1.0f)
            for (size_t i = 0; i < photo.size(); ++i) photo[i] *= gain;
        photo_ = std::make_shared<const Image>(std::move(photo));
        photo_key_ = photo_key;
        resampled_.clear();
    }
    const std::string probe_key =
        p.resolve(p.probe.path).string() + "|" + std::to_string(int(p.probe.format));
    if (probe_key != probe_key_) {
        Image probe = load_image(p.resolve(p.probe.path).string(), "probe.path");
        if (p.probe.format == ProbeSpec::Format::MirrorBall) {
            const int h = std::max(16, probe.height() / 2);
            probe = unwrap_mirror_ball(probe, 2 * h, h, 0.0f);
        }
        probe_ = std::move(probe);
        probe_key_ = probe_key;
    }
    auto load_list = [&](const auto& list) {
        for (const auto& item : list) {
            if (item.shape.kind != Shape::Kind::Mesh) continue;
            const std::string path = p.resolve(item.shape.mesh_path).string();
            if (!meshes_.count(path)) meshes_[path] = load_mesh(path, "shape.path").mesh;
        }
    };
    load_list(p.real);
    load_list(p.objects);
    auto load_texture = [&](const Albedo& a) {
        if (a.kind != Albedo::Kind::Texture) return;
        const std::string path = p.resolve(a.texture_path).string();
        if (!textures_.count(path)) textures_[path] = load_image(path, "albedo.texture");
    };
    for (const RealProxy& r : p.real) load_texture(r.albedo);
    for (const VirtualObject& o : p.objects) load_texture(o.material.albedo);
}

std::shared_ptr<RenderScene> SceneBuilder::build(const Project& project, int width, int height,
                                                 const RenderSettings& render) {
    const Image& photo = *photo_;
    if (width <= 0 || height <= 0) {
        width = photo.width();
        height = photo.height();
    }
    Project p = project;
    p.render = render;
    p.camera = scaled_camera(project.camera, photo.width(), photo.height(), width, height);
    SceneAssets a;
    // Every edit builds at the same two sizes: resample the photo once per size.
    auto it = resampled_.find({width, height});
    if (it == resampled_.end())
        it = resampled_.emplace(std::pair{width, height}, resample(photo, width, height)).first;
    a.photo = it->second;
    a.probe_latlong = probe_;
    auto fill = [&](const auto& list, std::vector<TriangleMesh>& meshes,
                    std::vector<Image>& textures, auto albedo_of) {
        meshes.resize(list.size());
        textures.resize(list.size());
        for (size_t i = 0; i < list.size(); ++i) {
            if (list[i].shape.kind == Shape::Kind::Mesh)
                meshes[i] = meshes_.at(p.resolve(list[i].shape.mesh_path).string());
            const Albedo& alb = albedo_of(list[i]);
            if (alb.kind == Albedo::Kind::Texture)
                textures[i] = textures_.at(p.resolve(alb.texture_path).string());
        }
    };
    fill(p.real, a.real_meshes, a.real_textures,
         [](const RealProxy& r) -> const Albedo& { return r.albedo; });
    fill(p.objects, a.object_meshes, a.object_textures,
         [](const VirtualObject& o) -> const Albedo& { return o.material.albedo; });
    auto scene = std::make_shared<RenderScene>(p, std::move(a));
    check_scene(*scene);
    return scene;
}

}  // namespace dp::ui
