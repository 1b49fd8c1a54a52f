// `diffphoton calibrate holdout`: a real occluder cut out of the photo (GrabCut from a rectangle,
// or a mask painted elsewhere) at a depth typed or found under a pixel; added to the project or
// replacing the holdout of that name, and written back (docs/holdouts.md).
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "assets/render_scene.h"
#include "base/error.h"
#include "calibrate_scene_common.h"
#include "commands.h"
#include "common.h"
#include "image/image_io.h"
#include "reconstruction/holdout_matte.h"
#include "scene/json_reader.h"
#include "scene/project_io.h"

namespace dp::cli {

namespace {

struct HoldoutOptions {
    std::string project, output, name = "holdout", mask;
    std::vector<float> rect, depth_at, occluder, background;
    float depth = 0;
    float radius = 4;
    bool force = false;
};

/// Marks discs of `radius` pixels around each "x y" pair of `xy` as `label`.
void mark(std::vector<MatteLabel>& labels, int W, int H, const std::vector<float>& xy, float radius, MatteLabel label) {
    for (size_t i = 0; i + 1 < xy.size(); i += 2)
        for (int y = std::max(0, int(xy[i + 1] - radius)); y <= std::min(H - 1, int(xy[i + 1] + radius)); ++y)
            for (int x = std::max(0, int(xy[i] - radius)); x <= std::min(W - 1, int(xy[i] + radius)); ++x)
                if (std::hypot(x - xy[i], y - xy[i + 1]) <= radius) labels[size_t(y) * W + x] = label;
}

/// The depth (along the camera's view axis) of the real surface under photo pixel (x, y).
float depth_under(const RenderScene& scene, float x, float y) {
    const Ray ray = scene.camera_ray(x, y);
    const Hit hit = scene.intersect_real(ray);
    if (!hit)
        throw InputError("", "--depth-at", "no real proxy under pixel (" + shortest_decimal(x) + ", " +
                                               shortest_decimal(y) + "): add the floor first (calibrate proxy)");
    return glm::dot(hit.p - scene.camera().position(), scene.camera().forward());
}

void run_holdout(const HoldoutOptions& o) {
    Project p = load_project(o.project);
    check_scene_outputs(p, o.project, o.output, {}, o.force);
    const std::string target = o.output.empty() ? o.project : o.output;
    SceneAssets assets = load_assets(p);
    for (const std::string& w : assets.warnings) warn(w);
    const Image photo = assets.photo;
    const int W = photo.width(), H = photo.height();
    Holdout h;
    h.name = o.name;
    size_t covered = 0;
    if (!o.rect.empty()) {
        std::vector<MatteLabel> labels =
            matte_labels_from_rect(W, H, int(std::lround(o.rect[0])), int(std::lround(o.rect[1])),
                                   int(std::lround(o.rect[2])), int(std::lround(o.rect[3])));
        mark(labels, W, H, o.occluder, o.radius, MatteLabel::Occluder);
        mark(labels, W, H, o.background, o.radius, MatteLabel::Background);
        std::vector<uint8_t> cut;
        try {
            cut = grabcut_matte(photo, labels);
        } catch (const std::invalid_argument& e) {
            throw InputError(o.project, "--rect", e.what());
        }
        for (uint8_t c : cut) covered += c;
        h.mask = save_holdout_mask(cut, W, H, target, h.name);
    } else {
        // A mask painted elsewhere, kept where it is; checked by loading it as the renderer will.
        h.mask = o.mask;
        ImageLoadOptions linear;
        linear.colorspace = "linear";
        const Image m = load_image(p.resolve(o.mask).string(), "--mask", nullptr, linear);
        covered = size_t(HoldoutMask::from_image(m, 1).coverage() * double(W) * double(H) + 0.5);
    }
    if (!o.depth_at.empty()) {
        RenderScene scene(p, std::move(assets));
        try {
            h.depth = depth_under(scene, o.depth_at[0], o.depth_at[1]);
        } catch (const InputError& e) {
            rethrow_for(e, o.project);
        }
    } else {
        h.depth = o.depth;
    }
    bool replaced = false;
    for (Holdout& old : p.holdouts)
        if (old.name == h.name) old = h, replaced = true;
    if (!replaced) p.holdouts.push_back(h);
    std::printf("%s holdout '%s': %zu pixels (%.1f%% of the photo), depth %.4g m, mask %s\n",
                replaced ? "replaced" : "added", h.name.c_str(), covered, 100.0 * double(covered) / (double(W) * H),
                h.depth, h.mask.c_str());
    write_back(p, o.project, o.output);
}

}  // namespace

Command add_calibrate_holdout_command(CLI::App& calibrate) {
    auto o = std::make_shared<HoldoutOptions>();
    CLI::App* sub = calibrate.add_subcommand(
        "holdout", "Add a real occluder that hides the objects behind it: cut out of the photo or from a mask");
    sub->add_option("project", o->project, "Project file (JSON)")->required();
    auto* rect = sub->add_option("--rect", o->rect, "X0 Y0 X1 Y1: a rectangle around the occluder (photo pixels); "
                                                    "GrabCut cuts it out")
                     ->expected(4)
                     ->check(kFinite);
    auto* mask = sub->add_option("--mask", o->mask, "An image whose white (>= 0.5 as stored) is the occluder, "
                                                    "stretched over the photo");
    rect->excludes(mask);
    sub->add_option("--occluder", o->occluder, "X Y ...: points surely on the occluder (with --rect)")->check(kFinite);
    sub->add_option("--background", o->background, "X Y ...: points surely not on it (with --rect)")->check(kFinite);
    sub->add_option("--stroke-radius", o->radius, "Radius of each --occluder / --background point (pixels, default 4)")
        ->check(CLI::Range(0.5f, 1000.0f));
    auto* depth = sub->add_option("--depth", o->depth, "How far the occluder stands (metres along the view axis)")
                      ->check(CLI::Range(1e-6f, kMaxHoldoutDepth));
    auto* depth_at = sub->add_option("--depth-at", o->depth_at,
                                     "X Y: the depth of the real proxy under this photo pixel (where it stands)")
                         ->expected(2)
                         ->check(kFinite);
    depth->excludes(depth_at);
    sub->add_option("--name", o->name, "Holdout name (default: holdout); an existing one is replaced");
    sub->add_option("-o,--output", o->output, "Write the project here instead of updating it");
    add_force_flag(sub, o->force);
    auto check = [o, rect, mask, depth, depth_at] {
        if (rect->count() == 0 && mask->count() == 0)
            throw InputError("", "--rect", "give --rect (a cut from the photo) or --mask (a painted mask)");
        if (depth->count() == 0 && depth_at->count() == 0)
            throw InputError("", "--depth", "give --depth (metres) or --depth-at X Y (a pixel on the real surface where it stands)");
        if (rect->count() == 0 && (!o->occluder.empty() || !o->background.empty()))
            throw InputError("", "--occluder", "--occluder and --background guide a cut: they need --rect");
        if (o->occluder.size() % 2 || o->background.size() % 2)
            throw InputError("", o->occluder.size() % 2 ? "--occluder" : "--background", "takes x y pairs");
        if (o->name.empty()) throw InputError("", "--name", "must not be empty");
    };
    return {sub,
            [o, check] {
                check();
                run_holdout(*o);
                return 0;
            },
            check};
}

}  // namespace dp::cli
