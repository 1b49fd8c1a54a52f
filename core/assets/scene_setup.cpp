// Scene set-up work beside the BVHs: image sanitising, emission clusters, albedo estimation.
#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "base/rng.h"
#include "assets/irradiance.h"
#include "assets/render_scene.h"

namespace dp {

namespace {

std::string indexed(const char* list, size_t i, const char* field) {
    return std::string(list) + "[" + std::to_string(i) + "]." + field;
}

}  // namespace

void RenderScene::sanitize_images() {
    // Images made in memory never went through load_image: the same rule applies to them.
    auto clean = [&](Image& img, const std::string& what) {
        const size_t replaced = replace_non_finite(img);
        if (replaced == 0) return;
        assets_->non_finite_replaced += replaced;
        assets_->warnings.push_back(what + ": " + std::to_string(replaced) + " NaN/Inf values replaced by 0");
    };
    clean(assets_->photo, "photo");
    for (size_t i = 0; i < assets_->real_textures.size(); ++i)
        clean(assets_->real_textures[i], indexed("real", i, "albedo.texture"));
    for (size_t i = 0; i < assets_->object_textures.size(); ++i)
        clean(assets_->object_textures[i], indexed("objects", i, "albedo.texture"));
    for (size_t i = 0; i < assets_->object_metallic_roughness.size(); ++i)
        clean(assets_->object_metallic_roughness[i], indexed("objects", i, "material.metallic_roughness_texture"));
    for (size_t i = 0; i < assets_->object_normal_maps.size(); ++i)
        clean(assets_->object_normal_maps[i], indexed("objects", i, "material.normal_texture"));
    for (size_t i = 0; i < assets_->object_file_materials.size(); ++i)
        for (FileMaterialAsset& f : assets_->object_file_materials[i]) {
            const std::string what = indexed("objects", i, "shape.path") + " material '" + f.name + "'";
            clean(f.texture, what);
            clean(f.metallic_roughness, what + " metallic-roughness texture");
            clean(f.normal, what + " normal map");
        }
}

void enclose(vec3 c1, float r1, vec3 c2, float r2, vec3& c, float& r) {
    float d = glm::length(c2 - c1);
    if (d + r2 <= r1) { c = c1; r = r1; return; }
    if (d + r1 <= r2) { c = c2; r = r2; return; }
    r = 0.5f * (d + r1 + r2);
    c = c1 + (c2 - c1) * ((r - r1) / d);
}

std::vector<EmissionCluster> cluster_objects(const std::vector<vec3>& centers, const std::vector<float>& radii) {
    std::vector<EmissionCluster> clusters;
    for (size_t i = 0; i < centers.size(); ++i) clusters.push_back({centers[i], radii[i], {int(i)}});
    // Greedy: merge the pair whose merged cross-section saves the most, while any saves.
    for (;;) {
        double best_gain = 0;
        size_t bi = 0, bj = 0;
        for (size_t i = 0; i < clusters.size(); ++i)
            for (size_t j = i + 1; j < clusters.size(); ++j) {
                vec3 c;
                float r;
                enclose(clusters[i].center, clusters[i].radius, clusters[j].center, clusters[j].radius, c, r);
                double gain = double(clusters[i].radius) * clusters[i].radius +
                              double(clusters[j].radius) * clusters[j].radius - double(r) * r;
                if (gain > best_gain) { best_gain = gain; bi = i; bj = j; }
            }
        if (best_gain <= 0) break;
        EmissionCluster merged;
        enclose(clusters[bi].center, clusters[bi].radius, clusters[bj].center, clusters[bj].radius, merged.center,
                merged.radius);
        merged.objects = clusters[bi].objects;
        merged.objects.insert(merged.objects.end(), clusters[bj].objects.begin(), clusters[bj].objects.end());
        clusters.erase(clusters.begin() + bj);
        clusters[bi] = std::move(merged);
    }
    return clusters;
}

bool RenderScene::object_bounds(int index, vec3& center, float& radius) const {
    if (index < 0 || size_t(index) >= virtual_surfaces_.size()) return false;
    const Surface& s = virtual_surfaces_[size_t(index)];
    if (s.analytic_sphere) {
        center = s.sphere_center;
        radius = s.sphere_radius;
        return true;
    }
    vec3 lo, hi;
    if (!s.mesh || !s.mesh->bounds(lo, hi)) return false;
    center = 0.5f * (lo + hi);
    float r2 = 0;
    for (const vec3& p : s.mesh->positions) r2 = std::max(r2, glm::dot(p - center, p - center));
    radius = std::sqrt(r2);
    return true;
}

void RenderScene::compute_clusters() {
    std::vector<vec3> centers;
    std::vector<float> radii;
    std::vector<int> ids;
    for (size_t i = 0; i < virtual_surfaces_.size(); ++i) {
        vec3 c;
        float r;
        if (!project_.objects[i].visible || !object_bounds(int(i), c, r)) continue;
        centers.push_back(c);
        radii.push_back(r);
        ids.push_back(int(i));
    }
    clusters_ = cluster_objects(centers, radii);
    for (EmissionCluster& c : clusters_) {
        for (int& o : c.objects) o = ids[o];
        c.radius *= 1.0f + 1e-4f;  // the disk must cover the silhouette despite rounding
        c.radius += ray_epsilon();
    }
}

void RenderScene::estimate_albedos() {
    bool any = std::any_of(project_.real.begin(), project_.real.end(),
                           [](const RealProxy& r) { return r.albedo.kind == Albedo::Kind::Estimate; });
    if (!any || probe().total_luminance_power() <= 0) return;
    const int W = camera_.width(), H = camera_.height();
    std::vector<std::vector<vec3>> estimates(real_surfaces_.size());
    Rng rng(0x5eed, 17);
    const int stride = std::max(1, int(std::sqrt(double(W) * H / 4096.0)));
    const int kProbeSamples = 64;
    for (int y = stride / 2; y < H; y += stride)
        for (int x = stride / 2; x < W; x += stride) {
            const Ray ray = camera_ray(float(x), float(y));
            Hit hit = intersect_real(ray);
            if (!hit || project_.real[hit.surface->index].albedo.kind != Albedo::Kind::Estimate) continue;
            if (hit.t > holdout_t(ray)) continue;  // the photo shows the occluder there, not the proxy
            vec3 n = glm::dot(hit.ng, camera_.position() - hit.p) >= 0 ? hit.ng : -hit.ng;
            dvec3 E = real_irradiance(*this, hit.p, n, rng, kProbeSamples).E;
            if (luminance(E) <= 0) continue;
            dvec3 rho = double(kPi) * dvec3(assets_->photo.at(x, y)) / glm::max(E, dvec3(1e-30));
            estimates[hit.surface->index].push_back(vec3(rho));
        }
    for (size_t i = 0; i < real_surfaces_.size(); ++i) {
        if (project_.real[i].albedo.kind != Albedo::Kind::Estimate) continue;
        auto& e = estimates[i];
        if (e.empty()) {
            assets_->warnings.push_back("real[" + std::to_string(i) +
                                       "].albedo: 'estimate' but the photo never sees this proxy lit; using " +
                                       "the constant albedo instead");
            continue;
        }
        vec3 median;
        for (int c = 0; c < 3; ++c) {
            std::vector<float> ch;
            for (const vec3& v : e) ch.push_back(v[c]);
            std::nth_element(ch.begin(), ch.begin() + ch.size() / 2, ch.end());
            median[c] = ch[ch.size() / 2];
        }
        real_surfaces_[i].albedo = glm::clamp(median, vec3(0.0f), vec3(0.98f));
    }
}

}  // namespace dp
