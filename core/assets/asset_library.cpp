#include "assets/asset_library.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <system_error>

#include "assets/file_materials.h"
#include "assets/mesh_units.h"
#include "assets/scene_checks.h"
#include "base/error.h"
#include "base/error_reason.h"
#include "base/input_file.h"
#include "base/euler.h"
#include "base/memory.h"
#include "base/text.h"
#include "image/image_io.h"
#include "probe/probe.h"
#include "probe/probe_resize.h"
#include "probe/probe_sun.h"

namespace dp {

namespace fs = std::filesystem;

namespace {

std::string indexed(const char* list, size_t i, const char* field) {
    return std::string(list) + "[" + std::to_string(i) + "]." + field;
}

fs::file_time_type modified(const fs::path& path) {
    std::error_code ec;
    const fs::file_time_type t = fs::last_write_time(path, ec);
    return ec ? fs::file_time_type{} : t;
}

}  // namespace

/// Loads an image, noting replaced NaN/Inf in the cache entry.
static Image load_noted(const fs::path& path, const std::string& field, ImageLoadReport& report,
                        std::vector<std::string>& warnings, size_t& non_finite, const ImageLoadOptions& options = {}) {
    Image img = load_image(path.string(), field, &report, options);
    for (const std::string& w : report.warnings) warnings.push_back(field + ": " + w);
    non_finite = report.non_finite_replaced;
    if (report.non_finite_replaced > 0)
        warnings.push_back(shorten_path(path.string()) + ": " + std::to_string(report.non_finite_replaced) +
                           " NaN/Inf values replaced by 0 (field '" + field + "')");
    return img;
}

namespace {

std::string percent(double share) {
    char buf[32];
    // Whole percents where they are many, two figures where few ("0.71%").
    std::snprintf(buf, sizeof(buf), share >= 0.1 ? "%.0f%%" : "%.2g%%", 100.0 * share);
    return buf;
}

/// An albedo is a reflectance: outside [0, 1] it is an editing or export mistake (a texture in
/// the wrong colour space, an HDR bake). Rendering clamps it; the warning says how much.
void check_albedo_values(const Image& texture, const std::string& label, std::vector<std::string>& warnings) {
    // Bakes and 16-bit exports overshoot by rounding; that is not worth a word.
    constexpr float kTolerance = 1e-3f;
    size_t outside = 0;
    float lo = 0, hi = 1;
    for (size_t i = 0; i < texture.size(); ++i) {
        const vec3& v = texture[i];
        const float a = std::min({v.x, v.y, v.z}), b = std::max({v.x, v.y, v.z});
        if (a < -kTolerance || b > 1 + kTolerance) ++outside;
        lo = std::min(lo, a);
        hi = std::max(hi, b);
    }
    if (outside == 0) return;
    char range[96];
    std::snprintf(range, sizeof(range), " (values from %g to %g)", double(lo), double(hi));
    warnings.push_back(label + ": " + percent(double(outside) / double(texture.size())) +
                       " of the texels are outside the albedo range [0, 1]" + range +
                       "; they are clamped to [0, 0.98] (is it in the wrong colour space?)");
}

/// Clipped highlights hold an unknown amount of light: where an object should darken them, the
/// render cannot know by how much. A few clipped pixels (specular glints) are normal.
void check_clipped_photo(size_t clipped, size_t pixels, std::vector<std::string>& warnings) {
    constexpr double kVisibleShare = 0.005;
    if (pixels == 0 || double(clipped) <= kVisibleShare * double(pixels)) return;
    warnings.push_back("photo.path: " + percent(double(clipped) / double(pixels)) +
                       " of the photo's pixels are clipped (a channel at the top code value); shadows "
                       "and reflections over them come out too weak: shoot raw or bracketed for an HDR photo");
}

/// A texture file a mesh's material names that is a FIFO, a device or a folder: refused like
/// any input of that kind. Only a texture that cannot be read as an image (missing, corrupt)
/// leaves its material its colour; reading this one would block the render or never end.
void refuse_special_texture(const FileMaterial& f, const std::string& texture, const fs::path& mesh_path,
                            const std::string& field) {
    const std::string kind = special_file_kind(texture);
    if (kind.empty()) return;
    throw InputError(texture, field,
                     "is " + kind + ", not a texture: material '" + f.name + "' of mesh '" +
                         shorten_path(mesh_path.filename().string()) + "' names it");
}

}  // namespace

template <class T, class Make>
std::shared_ptr<const T> AssetLibrary::cached(const std::string& key, const fs::path& path, Make&& make) {
    const fs::file_time_type mtime = modified(path);
    {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = entries_.find(key);
        if (it != entries_.end() && it->second.mtime == mtime) return std::static_pointer_cast<const T>(it->second.data);
    }
    // Decoded outside the lock: another thread may decode the same file meanwhile, and the
    // later one wins; both results are equal.
    Entry e;
    e.mtime = mtime;
    e.data = std::make_shared<const T>(make(e));
    std::lock_guard<std::mutex> lock(mutex_);
    entries_[key] = e;
    return std::static_pointer_cast<const T>(e.data);
}

void AssetLibrary::report(const std::string& key, SceneAssets& assets) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = entries_.find(key);
    if (it == entries_.end()) return;
    assets.warnings.insert(assets.warnings.end(), it->second.warnings.begin(), it->second.warnings.end());
    assets.non_finite_replaced += it->second.non_finite;
}

namespace {

std::string photo_key(const Project& p) {
    return "photo|" + p.resolve(p.photo.path).string() + "|" + std::to_string(p.photo.exposure) + "|" +
           p.photo.colorspace + "|" + p.photo.layer;
}

std::string probe_key(const Project& p) {
    return "probe|" + p.resolve(p.probe.path).string() + "|" + std::to_string(int(p.probe.format)) + "|" +
           std::to_string(p.probe.mirror_ball_fov_deg) + "|" + std::to_string(probe_max_width(p.probe)) + "|" +
           std::to_string(p.probe.sun_scale);
}

}  // namespace

std::shared_ptr<const Image> AssetLibrary::photo(const Project& p) {
    const fs::path path = p.resolve(p.photo.path);
    return cached<Image>(photo_key(p), path, [&](Entry& e) {
        ImageLoadReport report;
        ImageLoadOptions options;
        options.colorspace = p.photo.colorspace;
        options.layer = p.photo.layer;
        Image img = load_noted(path, "photo.path", report, e.warnings, e.non_finite, options);
        e.linear = report.linear_source;
        if (report.window_differs)
            e.warnings.push_back("photo.path: its data window (" + std::to_string(report.data_width) + "x" +
                                 std::to_string(report.data_height) + " at " + std::to_string(report.data_x) + ", " +
                                 std::to_string(report.data_y) +
                                 ") differs from its display window: the photo is the display window, black "
                                 "outside the data");
        check_clipped_photo(report.clipped, img.size(), e.warnings);
        const float gain = std::exp2(p.photo.exposure);
        if (gain != 1.0f)
            for (size_t i = 0; i < img.size(); ++i) img[i] *= gain;
        return img;
    });
}

std::shared_ptr<const Image> AssetLibrary::photo_at(const Project& p, int width, int height) {
    std::shared_ptr<const Image> full = photo(p);
    if (width <= 0 || height <= 0 || (width == full->width() && height == full->height())) return full;
    const std::string key = photo_key(p) + "|" + std::to_string(width) + "x" + std::to_string(height);
    return cached<Image>(key, p.resolve(p.photo.path),
                         [&](Entry&) { return resample(*full, width, height); });
}

namespace {

/// Negative radiance has no meaning (an editing artefact): read as 0, and said. A black probe
/// lights nothing, so the objects would render black and cast no shadow.
void check_probe_values(Image& probe, std::vector<std::string>& warnings) {
    size_t negative = 0;
    double total = 0, removed = 0;
    for (size_t i = 0; i < probe.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            if (probe[i][c] < 0) {
                removed -= probe[i][c];
                probe[i][c] = 0;
                ++negative;
            }
            total += probe[i][c];
        }
    // Real probes carry a few slightly negative texels from their processing (Blender's city
    // has 506); they are said only where they hold a visible share of the light.
    if (negative > 0 && removed > 1e-3 * total)
        warnings.push_back("probe.path: " + std::to_string(negative) + " negative values read as 0");
    if (!(total > 0)) warnings.push_back("probe.path: the probe is black: nothing lights the virtual objects");
}

}  // namespace

std::shared_ptr<const Image> AssetLibrary::probe(const Project& p) {
    const fs::path path = p.resolve(p.probe.path);
    return cached<Image>(probe_key(p), path, [&](Entry& e) {
        ImageLoadReport report;
        Image probe = load_noted(path, "probe.path", report, e.warnings, e.non_finite);
        if (!report.linear_source)
            e.warnings.push_back("probe.path: the light probe is not an HDR image (EXR/HDR); "
                               "bright lights are clipped and shadows will be too weak");
        check_probe_values(probe, e.warnings);
        if (p.probe.format == ProbeSpec::Format::MirrorBall && probe.width() != probe.height())
            e.warnings.push_back("probe.path: a mirror ball is " + std::to_string(probe.width()) + "x" +
                                 std::to_string(probe.height()) +
                                 ", not square: crop the photo to the ball, or the unwrap is distorted");
        if (p.probe.format == ProbeSpec::Format::LatLong && probe.width() != 2 * probe.height())
            e.warnings.push_back("probe.path: a lat-long probe is " + std::to_string(probe.width()) + "x" +
                                 std::to_string(probe.height()) +
                                 ", not 2:1: it is read as 2:1 and looks stretched (is it a mirror ball?)");
        if (p.probe.format == ProbeSpec::Format::MirrorBall) {
            const int h = std::max(16, probe.height() / 2);
            probe = unwrap_mirror_ball(probe, 2 * h, h, p.probe.mirror_ball_fov_deg);
        }
        limit_probe_size(probe, probe_max_width(p.probe), e.warnings);
        const ProbeSun sun = find_probe_sun(probe);
        if (p.probe.sun_scale != 1.0f) {
            if (!sun.found)
                e.warnings.push_back("probe.sun_scale: the probe has no compact sun to scale; it is left as shot");
            scale_probe_sun(probe, sun, p.probe.sun_scale);
        } else if (const std::string why = clipped_sun_warning(sun); !why.empty()) {
            e.warnings.push_back(why);
        }
        return probe;
    });
}

int probe_max_width(const ProbeSpec& spec) {
    if (spec.max_width > 0) return spec.max_width;
    static const int automatic = automatic_probe_max_width(usable_memory_bytes(), kProbeBytesPerPixel);
    return automatic;
}

void limit_probe_size(Image& probe, int max_width, std::vector<std::string>& warnings) {
    int width = 0, height = 0;
    shrunk_latlong_size(probe.width(), probe.height(), max_width, width, height);
    if (width == probe.width() && height == probe.height()) return;
    warnings.push_back("probe.path: the " + std::to_string(probe.width()) + "x" + std::to_string(probe.height()) +
                       " probe is reduced to " + std::to_string(width) + "x" + std::to_string(height) +
                       " on load, its light kept (max width " + std::to_string(max_width) +
                       ": probe.max_width in docs/project-format.md)");
    probe = shrink_latlong(probe, width, height);
}

std::shared_ptr<const LitProbe> AssetLibrary::lit_probe(const Project& p) {
    const std::shared_ptr<const Image> latlong = probe(p);
    char settings[224];
    // The file's time in the key: a probe file rewritten is a new probe. The gain per channel
    // (intensity times white balance) is what the tables are built from.
    const vec3 gain = p.probe.gain();
    std::snprintf(settings, sizeof(settings), "|%.9g,%.9g,%.9g|%.9g,%.9g,%.9g|%lld", double(p.probe.rotation_deg.x),
                  double(p.probe.rotation_deg.y), double(p.probe.rotation_deg.z), double(gain.x), double(gain.y),
                  double(gain.z), static_cast<long long>(modified(p.resolve(p.probe.path)).time_since_epoch().count()));
    const std::string key = probe_key(p) + settings;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (auto& [k, lit] : lit_probes_)
            if (k == key) return lit;
    }
    auto lit = std::make_shared<const LitProbe>(latlong, euler_xyz_deg(p.probe.rotation_deg), gain);
    std::lock_guard<std::mutex> lock(mutex_);
    constexpr size_t kKept = 4;
    if (lit_probes_.size() >= kKept) lit_probes_.erase(lit_probes_.begin());
    lit_probes_.emplace_back(key, lit);
    return lit;
}

SceneAssets AssetLibrary::load(const Project& project, int photo_width, int photo_height, bool with_probe) {
    SceneAssets a;
    if (photo_width >= 0) a.photo = *photo_at(project, photo_width, photo_height);  // < 0: warnings only
    if (with_probe) a.probe_latlong = *probe(project);
    // The width the camera sees at a point's distance (0 behind it, or without a camera).
    std::optional<Camera> view;
    auto view_width_at = [&](const vec3& at) -> float {
        if (!view) {
            int pw = 0, ph = 0;
            try {
                photo_size(project, pw, ph);
                view = project.camera.build(pw, ph);
            } catch (const std::exception&) {
                view = Camera();  // a photo or camera that cannot be read is said elsewhere
            }
        }
        if (view->width() <= 0 || !(view->fx() > 0)) return 0.0f;
        const float depth = glm::dot(at - view->position(), view->forward());
        return depth > 0 ? depth * float(view->width()) / view->fx() : 0.0f;
    };
    auto load_list = [&](auto const& list, const char* name, std::vector<TriangleMesh>& meshes,
                         std::vector<UpAxis>& ups, std::vector<Image>& textures, auto albedo_of) {
        meshes.resize(list.size());
        ups.assign(list.size(), UpAxis::Y);
        textures.resize(list.size());
        for (size_t i = 0; i < list.size(); ++i) {
            if (list[i].shape.kind == Shape::Kind::Mesh) {
                const fs::path path = project.resolve(list[i].shape.mesh_path);
                const std::string field = indexed(name, i, "shape.path");
                auto mesh = cached<LoadedMesh>("mesh|" + path.string(), path,
                                               [&](Entry&) { return load_mesh(path.string(), field); });
                a.degenerate_triangles_dropped += mesh->dropped_degenerate;
                meshes[i] = mesh->mesh;
                ups[i] = declared_up_axis(mesh->declared_up);
                // Said on every load: the size depends on the transform, which edits change.
                const float size =
                    placed_mesh_size(mesh->bounds_lo, mesh->bounds_hi, list[i].shape, list[i].transform, ups[i]);
                std::string why = mesh_size_warning(indexed(name, i, "shape.unit_scale"), list[i].name, size,
                                                    list[i].shape.unit_scale);
                // Within what things can be, but not for where it stands in the view: a 30 cm
                // vase modelled in centimetres, 30 m tall on a desk 3 m away.
                if (why.empty())
                    if (const float width = view_width_at(list[i].transform.translation); width > 0)
                        why = mesh_view_warning(indexed(name, i, "shape.unit_scale"), list[i].name, size,
                                                list[i].shape.unit_scale, width);
                if (!why.empty()) a.warnings.push_back(why);
            }
            const Albedo& alb = albedo_of(list[i]);
            if (alb.kind == Albedo::Kind::Texture) {
                const fs::path path = project.resolve(alb.texture_path);
                const std::string field = indexed(name, i, "albedo.texture");
                const std::string key = "texture|" + path.string();
                textures[i] = *cached<Image>(key, path, [&](Entry& e) {
                    ImageLoadReport report;
                    Image texture = load_noted(path, field, report, e.warnings, e.non_finite);
                    check_albedo_values(texture, field + " '" + shorten_path(alb.texture_path) + "'", e.warnings);
                    return texture;
                });
                report(key, a);
            }
        }
    };
    load_list(project.real, "real", a.real_meshes, a.real_mesh_up, a.real_textures,
              [](const RealProxy& r) -> const Albedo& { return r.albedo; });
    load_list(project.objects, "objects", a.object_meshes, a.object_mesh_up, a.object_textures,
              [](const VirtualObject& o) -> const Albedo& { return o.material.albedo; });
    a.object_metallic_roughness.resize(project.objects.size());
    a.object_normal_maps.resize(project.objects.size());
    for (size_t i = 0; i < project.objects.size(); ++i) {
        const Material& m = project.objects[i].material;
        if (m.kind != Material::Kind::Principled) continue;
        // Data, not colour: read as stored, whatever the file's tag says (glTF's rule).
        auto data = [&](const std::string& written, const char* key, Image& out) {
            if (written.empty()) return;
            const fs::path path = project.resolve(written);
            const std::string field = indexed("objects", i, (std::string("material.") + key).c_str());
            const std::string cache_key = "texture|" + path.string() + "|linear";
            out = *cached<Image>(cache_key, path, [&](Entry& e) {
                ImageLoadReport report;
                ImageLoadOptions linear;
                linear.colorspace = "linear";
                return load_noted(path, field, report, e.warnings, e.non_finite, linear);
            });
            report(cache_key, a);
        };
        data(m.principled.metallic_roughness_texture, "metallic_roughness_texture", a.object_metallic_roughness[i]);
        data(m.principled.normal_texture, "normal_texture", a.object_normal_maps[i]);
    }
    a.object_file_materials.resize(project.objects.size());
    for (size_t i = 0; i < project.objects.size(); ++i) {
        const VirtualObject& o = project.objects[i];
        if (o.shape.kind != Shape::Kind::Mesh || o.material_source != MaterialSource::File)
            continue;
        const fs::path path = project.resolve(o.shape.mesh_path);
        const std::string field = indexed("objects", i, "shape.path");
        // Loaded (and cached) by load_list just now.
        auto mesh = cached<LoadedMesh>("mesh|" + path.string(), path,
                                       [&](Entry&) { return load_mesh(path.string(), field); });
        a.object_file_materials[i] = file_materials(*mesh, path, field, a);
    }
    load_holdouts(project, a);
    SceneAssets head;
    report(photo_key(project), head);
    report(probe_key(project), head);
    a.warnings.insert(a.warnings.begin(), head.warnings.begin(), head.warnings.end());
    a.non_finite_replaced += head.non_finite_replaced;
    if (a.degenerate_triangles_dropped > 0)
        a.warnings.push_back(std::to_string(a.degenerate_triangles_dropped) + " zero-area triangles dropped");
    return a;
}

void AssetLibrary::load_holdouts(const Project& project, SceneAssets& a) {
    int photo_w = 0, photo_h = 0;
    if (!project.holdouts.empty()) photo_size(project, photo_w, photo_h);
    for (size_t i = 0; i < project.holdouts.size(); ++i) {
        const Holdout& h = project.holdouts[i];
        const fs::path path = project.resolve(h.mask);
        const std::string field = indexed("holdouts", i, "mask");
        // A mask is data: painted white means covered, whatever a colour profile says.
        const std::string key = "texture|" + path.string() + "|linear";
        auto image = cached<Image>(key, path, [&](Entry& e) {
            ImageLoadReport report;
            ImageLoadOptions linear;
            linear.colorspace = "linear";
            return load_noted(path, field, report, e.warnings, e.non_finite, linear);
        });
        report(key, a);
        a.holdouts.push_back(HoldoutMask::from_image(*image, h.depth));
        const double mask_aspect = double(image->width()) / image->height(), photo_aspect = double(photo_w) / photo_h;
        if (std::abs(mask_aspect / photo_aspect - 1) > 0.01)
            a.warnings.push_back(field + ": the mask is " + std::to_string(image->width()) + "x" +
                                 std::to_string(image->height()) + " and the photo " + std::to_string(photo_w) + "x" +
                                 std::to_string(photo_h) + ": it is stretched over the photo");
    }
}

std::vector<FileMaterialAsset> AssetLibrary::file_materials(const LoadedMesh& mesh,
                                                            const fs::path& mesh_path,
                                                            const std::string& field,
                                                            SceneAssets& a) {
    for (const std::string& w : mesh.warnings) a.warnings.push_back(field + ": " + w);
    std::vector<FileMaterialAsset> out;
    for (const FileMaterial& f : mesh.materials) {
        const bool embedded =
            f.embedded_texture >= 0 && size_t(f.embedded_texture) < mesh.embedded_textures.size();
        const std::string label = embedded ? shorten_path(mesh_path.filename().string()) +
                                                 " (embedded texture " +
                                                 std::to_string(f.embedded_texture) + ")"
                                           : f.texture;
        FileMaterialAsset asset{
            f.name, material_from_file(f, embedded || !f.texture.empty() ? label : ""), {}};
        if (asset.material.kind == Material::Kind::Principled) {
            asset.metallic_roughness = data_texture(mesh, f, f.metallic_roughness, "metallic-roughness", mesh_path, field, a);
            asset.normal = data_texture(mesh, f, f.normal, "normal", mesh_path, field, a);
            asset.normal_scale = std::clamp(f.normal_scale, 0.0f, 10.0f);
        }
        const bool textured_kind = asset.material.kind == Material::Kind::Diffuse ||
                                   asset.material.kind == Material::Kind::Principled;
        if (!textured_kind || asset.material.albedo.kind != Albedo::Kind::Texture) {
            out.push_back(std::move(asset));
            continue;
        }
        // glTF's base colour texture is multiplied by its base colour: the product is cached.
        const vec3 factor =
            f.texture_times_colour ? glm::clamp(f.colour, vec3(0.0f), vec3(1.0f)) : vec3(1.0f);
        char tag[96];
        std::snprintf(tag, sizeof(tag), "|%.9g,%.9g,%.9g", double(factor.x), double(factor.y),
                      double(factor.z));
        if (!embedded) refuse_special_texture(f, f.texture, mesh_path, field);
        const std::string key =
            (embedded ? "embedded|" + mesh_path.string() + "|" + std::to_string(f.embedded_texture)
                      : "texture|" + f.texture) +
            tag;
        try {
            asset.texture =
                *cached<Image>(key, embedded ? mesh_path : fs::path(f.texture), [&](Entry& e) {
                    ImageLoadReport report;
                    Image texture =
                        embedded ? decode_embedded_texture(
                                       mesh.embedded_textures[size_t(f.embedded_texture)],
                                       f.embedded_texture, mesh_path.string(), field, &report)
                                 : load_image(f.texture, field, &report);
                    e.non_finite = report.non_finite_replaced;
                    if (e.non_finite > 0)
                        e.warnings.push_back(
                            shorten_path(label) + ": " + std::to_string(e.non_finite) +
                            " NaN/Inf values replaced by 0 (field '" + field + "')");
                    check_albedo_values(
                        texture,
                        field + " material '" + f.name + "' texture '" + shorten_path(label) + "'",
                        e.warnings);
                    if (factor != vec3(1.0f))
                        for (size_t k = 0; k < texture.size(); ++k) texture[k] *= factor;
                    return texture;
                });
            report(key, a);
        } catch (const InputError& e) {
            // A texture path from another machine is common in files passed around: the
            // material's colour stands in, and the warning says which file is missing.
            a.warnings.push_back(field + ": material '" + f.name +
                                 "': its texture cannot be read (" + e.what() +
                                 "); its colour is used");
            asset.material.albedo.kind = Albedo::Kind::Constant;
            asset.material.albedo.texture_path.clear();
        }
        out.push_back(std::move(asset));
    }
    return out;
}

Image AssetLibrary::data_texture(const LoadedMesh& mesh, const FileMaterial& f, const FileTexture& t,
                                const char* what, const fs::path& mesh_path, const std::string& field,
                                SceneAssets& a) {
    const bool embedded = t.embedded >= 0 && size_t(t.embedded) < mesh.embedded_textures.size();
    if (!embedded && t.path.empty()) return {};
    const std::string label = embedded ? shorten_path(mesh_path.filename().string()) + " (embedded texture " +
                                             std::to_string(t.embedded) + ")"
                                       : t.path;
    // Data, not colour: read as stored, whatever the file's tag says (glTF's rule).
    const std::string key =
        (embedded ? "embedded|" + mesh_path.string() + "|" + std::to_string(t.embedded) : "texture|" + t.path) +
        "|linear";
    if (!embedded) refuse_special_texture(f, t.path, mesh_path, field);  // refused, not ignored
    try {
        Image image = *cached<Image>(key, embedded ? mesh_path : fs::path(t.path), [&](Entry& e) {
            ImageLoadReport report;
            ImageLoadOptions linear;
            linear.colorspace = "linear";
            Image texture = embedded ? decode_embedded_texture(mesh.embedded_textures[size_t(t.embedded)], t.embedded,
                                                               mesh_path.string(), field, &report, linear)
                                     : load_image(t.path, field, &report, linear);
            e.non_finite = report.non_finite_replaced;
            if (e.non_finite > 0)
                e.warnings.push_back(shorten_path(label) + ": " + std::to_string(e.non_finite) +
                                     " NaN/Inf values replaced by 0 (field '" + field + "')");
            return texture;
        });
        report(key, a);
        return image;
    } catch (const InputError& e) {
        a.warnings.push_back(field + ": material '" + f.name + "': its " + what + " texture cannot be read (" +
                             e.what() + "); it is ignored");
        return {};
    }
}

std::vector<std::string> AssetLibrary::warnings(const Project& project) {
    // Decoded (or found decoded) without copying the photo and the probe: a viewer asks on
    // every edit, and a 12 MP photo's copy would cost more than the edit's preview.
    photo(project);
    probe(project);
    return load(project, -1, -1, false).warnings;
}

void AssetLibrary::photo_size(const Project& p, int& width, int& height) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = entries_.find(photo_key(p));
        if (it != entries_.end()) {
            const auto img = std::static_pointer_cast<const Image>(it->second.data);
            width = img->width();
            height = img->height();
            return;
        }
    }
    if (read_image_size(p.resolve(p.photo.path).string(), width, height)) return;
    const auto img = photo(p);
    width = img->width();
    height = img->height();
}

float AssetLibrary::photo_clip_level(const Project& p) {
    photo(p);
    std::lock_guard<std::mutex> lock(mutex_);
    const bool linear = entries_[photo_key(p)].linear;
    // The top code value of an 8-bit photo, less a little for rounding, after the exposure.
    return linear ? INFINITY : 0.99f * std::exp2(p.photo.exposure);
}

void AssetLibrary::clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.clear();
    lit_probes_.clear();
}

SceneAssets load_assets(const Project& project) {
    AssetLibrary library;
    return library.load(project);
}

CameraSpec scaled_camera(const CameraSpec& c, int photo_w, int photo_h, int width, int height) {
    CameraSpec out = c;
    if (c.model != CameraSpec::Model::Intrinsics || (width == photo_w && height == photo_h)) return out;
    const float ax = float(width) / float(photo_w), ay = float(height) / float(photo_h);
    out.fx = c.fx * ax;
    out.fy = c.fy * ay;
    out.cx = (c.cx + 0.5f) * ax - 0.5f;
    out.cy = (c.cy + 0.5f) * ay - 0.5f;
    return out;
}

std::shared_ptr<RenderScene> build_scene(AssetLibrary& library, const Project& project, int width, int height,
                                         const std::string& project_file) {
    // The photo at the scene's size only: a copy of a full 12 MP photo for a preview would
    // cost more than the preview.
    // The probe's tables are shared between the scenes of the same probe settings.
    // (Decoded first, so that load() reports what decoding it found.)
    std::shared_ptr<const LitProbe> lit = library.lit_probe(project);
    SceneAssets a = library.load(project, width, height, false);
    Project p = project;
    const std::shared_ptr<const Image> full = library.photo(project);
    const int pw = full->width(), ph = full->height();
    if (width > 0 && height > 0 && (width != pw || height != ph))
        p.camera = scaled_camera(project.camera, pw, ph, width, height);
    std::shared_ptr<RenderScene> scene;
    try {
        scene = std::make_shared<RenderScene>(p, std::move(a), std::move(lit));
    } catch (const InputError& e) {
        // The scene's checks (its extent, its camera) know fields, not files: the fields are
        // the project file's.
        if (!e.file().empty() || project_file.empty()) throw;
        throw InputError(project_file, e.field(), error_reason(e));
    }
    check_scene(*scene, project_file);
    return scene;
}

}  // namespace dp
