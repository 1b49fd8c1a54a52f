#include "render/edit_region.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "scene/project_diff.h"

namespace dp {

void EditedStates::remember(uint64_t generation, const Project& project, const RenderScene& scene, uint64_t keep) {
    State s;
    s.project = project;
    for (size_t i = 0; i < project.objects.size(); ++i) {
        EditedBounds e;
        if (scene.object_bounds(int(i), e.center, e.radius)) s.bounds.push_back(e);
        else s.bounds.push_back(std::nullopt);
    }
    states_[generation] = std::move(s);
    // The refined picture's state, and the latest few that may replace it.
    for (auto it = states_.begin(); it != states_.end();) {
        const bool recent = std::distance(it, states_.end()) <= 8;
        it = it->first == keep || (it->first > keep && recent) ? std::next(it) : states_.erase(it);
    }
}

std::shared_ptr<const EditRegion> EditedStates::region(uint64_t base_generation, const Project& project,
                                                       const RenderScene& scene) const {
    auto it = states_.find(base_generation);
    if (it == states_.end()) return nullptr;
    const State& base = it->second;
    std::vector<int> edited;
    if (!edited_objects(base.project, project, edited)) return nullptr;
    // An object that glows (before or after the edit) lights far beyond its reach.
    auto glows = [](const Project& p, int i) {
        if (size_t(i) >= p.objects.size()) return false;
        const Material& m = p.objects[size_t(i)].material;
        return p.objects[size_t(i)].visible && m.kind == Material::Kind::Principled && m.principled.emission != vec3(0);
    };
    for (int i : edited)
        if (glows(base.project, i) || glows(project, i)) return nullptr;
    std::vector<EditedBounds> spheres;
    for (int i : edited) {
        if (size_t(i) < base.bounds.size() && base.bounds[size_t(i)]) spheres.push_back(*base.bounds[size_t(i)]);
        EditedBounds now;
        if (size_t(i) < project.objects.size() && scene.object_bounds(i, now.center, now.radius)) spheres.push_back(now);
    }
    auto region = std::make_shared<EditRegion>();
    // About 25,000 rays whatever the scene's size: the region's edge is widened anyway.
    const int W = scene.photo().width(), H = scene.photo().height();
    const int step = std::max(1, int(std::ceil(std::sqrt(double(W) * H / 25000.0))));
    region->width = (W + step - 1) / step;
    region->height = (H + step - 1) / step;
    region->base_generation = base_generation;
    region->mask = change_region(scene, spheres, kChangeReach, step);
    // A cell of the mask stands for several pixels of the picture: the edge of the region is
    // widened by one, so soft shadows are not cut at it.
    dilate_mask(region->mask, region->width, region->height, 1);
    return region;
}

void compose_over(RenderFrame& f, const RenderFrame& base, const EditRegion& region, int max_width) {
    const Image& bi = base.image();
    const Image& bd = base.dL();
    const int W = bi.width(), H = bi.height();
    const Image& pi = f.update.image;
    const Image& pd = f.update.dL;
    if (W == 0 || bd.width() != W || pi.empty() || region.mask.empty()) return;
    const int w = pi.width(), h = pi.height();
    const int step = W > max_width ? (W + max_width - 1) / max_width : 1;
    const int OW = W / step, OH = H / step;
    auto image = std::make_shared<Image>(OW, OH);
    auto dL = std::make_shared<Image>(OW, OH);
    auto from_edit = std::make_shared<std::vector<uint8_t>>(size_t(OW) * OH, 0);
    // The mask is looked up at its own scale: a full-size pass uses its preview's region.
    const float sx = float(w) / float(W), sy = float(h) / float(H);
    const float mx = float(region.width) / float(W), my = float(region.height) / float(H);
    tbb::parallel_for(0, OH, [&](int oy) {
        const int y = oy * step + step / 2;
        const int ry = std::min(region.height - 1, int((float(y) + 0.5f) * my));
        for (int ox = 0; ox < OW; ++ox) {
            const int x = ox * step + step / 2;
            const size_t i = size_t(y) * W + x, o = size_t(oy) * OW + ox;
            const int rx = std::min(region.width - 1, int((float(x) + 0.5f) * mx));
            (*from_edit)[o] = region.mask[size_t(ry) * region.width + rx];
            if (!(*from_edit)[o]) {
                (*image)[o] = bi[i];
                (*dL)[o] = bd[i];
            } else if (w == W && h == H) {
                (*image)[o] = pi[i];
                (*dL)[o] = pd[i];
            } else {
                const float px = (float(x) + 0.5f) * sx - 0.5f, py = (float(y) + 0.5f) * sy - 0.5f;
                (*image)[o] = pi.bilinear(px, py);
                (*dL)[o] = pd.bilinear(px, py);
            }
        }
    });
    f.shown_image = std::move(image);
    f.shown_dL = std::move(dL);
    f.shown_from_edit = std::move(from_edit);
    f.base_generation = base.generation;
    f.shown_step = step;
    f.refined_passes = base.refined_passes;
}

}  // namespace dp
