#include "scene/project_diff.h"

#include <algorithm>

namespace dp {

namespace {

bool same_geometry(const VirtualObject& a, const VirtualObject& b) {
    // The material source picks which textures are loaded with the assets: a rebuild, as for
    // a texture.
    return a.shape == b.shape && a.transform == b.transform && a.visible == b.visible &&
           a.material_source == b.material_source;
}

}  // namespace

Change classify(const Project& a, const Project& b) {
    // The sun's scale is applied to the probe's pixels as they load.
    if (a.photo != b.photo || a.probe.path != b.probe.path || a.probe.format != b.probe.format ||
        a.probe.sun_scale != b.probe.sun_scale || a.base_dir != b.base_dir)
        return Change::Assets;
    // A mask is an image loaded with the assets; a depth is read when the scene is built.
    if (a.holdouts.size() != b.holdouts.size()) return Change::Assets;
    for (size_t i = 0; i < a.holdouts.size(); ++i)
        if (a.holdouts[i].mask != b.holdouts[i].mask) return Change::Assets;
    if (a.holdouts != b.holdouts) return Change::Scene;
    if (!(a.probe == b.probe) || !(a.camera == b.camera) || a.real != b.real || a.objects.size() != b.objects.size())
        return Change::Scene;
    bool material = false;
    for (size_t i = 0; i < a.objects.size(); ++i) {
        if (!same_geometry(a.objects[i], b.objects[i])) return Change::Scene;
        // Albedo textures are images loaded with the assets: a texture edit needs a rebuild.
        const Material &ma = a.objects[i].material, &mb = b.objects[i].material;
        if (ma.albedo.kind != mb.albedo.kind || ma.albedo.texture_path != mb.albedo.texture_path ||
            ma.principled.metallic_roughness_texture != mb.principled.metallic_roughness_texture ||
            ma.principled.normal_texture != mb.principled.normal_texture)
            return Change::Scene;
        // A principled material's textures are loaded only while it is principled.
        const bool textured = !ma.principled.metallic_roughness_texture.empty() || !ma.principled.normal_texture.empty();
        if (textured && (ma.kind == Material::Kind::Principled) != (mb.kind == Material::Kind::Principled))
            return Change::Scene;
        material |= !(ma == mb);
    }
    // Lights are not in the BVH: a scene takes new ones as it takes new materials.
    if (material || a.lights != b.lights) return Change::Material;
    return a.render != b.render ? Change::Settings : Change::None;
}

bool edited_objects(const Project& a, const Project& b, std::vector<int>& edited) {
    edited.clear();
    if (classify(a, b) == Change::Assets || !(a.probe == b.probe) || !(a.camera == b.camera) || a.real != b.real ||
        a.render != b.render || a.lights != b.lights || a.holdouts != b.holdouts)
        return false;
    const size_t n = std::max(a.objects.size(), b.objects.size());
    for (size_t i = 0; i < n; ++i)
        if (i >= a.objects.size() || i >= b.objects.size() || !same_geometry(a.objects[i], b.objects[i]) ||
            !(a.objects[i].material == b.objects[i].material))
            edited.push_back(int(i));
    return true;
}

}  // namespace dp
