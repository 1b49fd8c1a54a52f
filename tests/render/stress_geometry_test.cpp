// Awkward geometry: objects sunk into the ground, and meshes with zero-area and sliver
// triangles. (A camera inside or on a virtual object: tests/unit/render/camera_contact_test.cpp.)
#include <gtest/gtest.h>

#include <cstdio>

#include "render/stress_common.h"

using namespace dp;
using namespace dp::test;

namespace {

Image sun_sky() {
    return make_sun_sky_probe(256, 128, glm::normalize(vec3(1, 1.3f, 0.4f)), vec3(600.0f), 4.0f,
                              vec3(0.2f, 0.35f, 0.8f), vec3(0.7f, 0.8f, 0.9f));
}

}  // namespace

TEST(AwkwardGeometry, ObjectsSunkIntoTheGroundMatchThePathTracer) {
    Project p = look_at_project(vec3(0, 2.0f, 3.2f), vec3(-0.1f, 0.2f, 0), 45);
    p.real.push_back(ground_plane(vec3(0.5f)));
    // A diffuse sphere whose centre is 0.3 radii above the ground, and a diffuse box half buried
    // and tilted: both cut the ground plane along a curve the camera sees. (Diffuse: a mirror's
    // sun caustic would be too noisy in the path-traced truth to compare pixel by pixel.)
    p.objects.push_back(sphere(vec3(-0.6f, 0.15f, 0), 0.5f, diffuse(vec3(0.6f, 0.5f, 0.4f))));
    VirtualObject box;
    box.name = "buried box";
    box.shape.kind = Shape::Kind::Box;
    box.shape.size = vec3(0.6f, 0.6f, 0.6f);
    box.transform.translation = vec3(0.6f, 0.05f, 0.2f);
    box.transform.rotation_deg = vec3(20, 35, 10);
    box.material = diffuse(vec3(0.3f, 0.5f, 0.7f));
    p.objects.push_back(box);
    TruthAndRender t = render_against_truth(p, sun_sky(), 64, 48, 512, 16, 200000);
    // Check 1: all finite.
    EXPECT_EQ(count_non_finite(t.render), 0u);
    EXPECT_EQ(t.non_finite_samples, 0u);
    // Check 2: the changed pixels (shadows, the objects, their contact curves) match the truth.
    std::vector<bool> changed = changed_pixels(t);
    size_t n = std::count(changed.begin(), changed.end(), true);
    double e = relative_rmse(t.render, t.truth, [&](size_t i) { return changed[i]; });
    std::printf("sunk objects: relative RMSE over %zu changed pixels: %.4f\n", n, e);
    EXPECT_GT(n, 500u);
    EXPECT_LT(e, 0.1);
    // Check 3: no light leaks under the objects onto the ground: no ground pixel is brighter
    // than the truth by more than half the brightest photo pixel (a leak through the contact
    // curve would show as a spike).
    float photo_max = 0;
    for (size_t i = 0; i < t.photo.size(); ++i) photo_max = std::max(photo_max, luminance(t.photo[i]));
    size_t spikes = 0;
    for (size_t i = 0; i < t.render.size(); ++i)
        spikes += t.alpha[i].x == 0 && luminance(t.render[i]) - luminance(t.truth[i]) > 0.5f * photo_max;
    EXPECT_EQ(spikes, 0u);
}

namespace {

/// A plane of `size` in XZ (normal +Y) cut into a fan of long slivers from one corner, with
/// zero-area triangles (repeated and collinear corners) mixed in.
TriangleMesh sliver_plane(float size) {
    TriangleMesh m;
    const float h = 0.5f * size;
    m.positions.push_back(vec3(-h, 0, -h));  // fan corner
    // Points along the two far edges, some clustered 1e-6 and 1e-8 of the size apart.
    std::vector<float> ts;
    for (int i = 0; i <= 16; ++i) ts.push_back(i / 16.0f);
    for (float t : {0.3f, 0.6f, 1.4f, 1.7f}) {
        ts.push_back(t + 1e-6f);
        ts.push_back(t + 1e-8f);  // rounds to t: a duplicate corner
    }
    std::sort(ts.begin(), ts.end());
    for (float t : ts) {
        // t in [0, 1]: along the edge x = +h from z = -h to +h; [1, 2]: along z = +h back to -h.
        vec3 q = t <= 1 ? vec3(h, 0, -h + 2 * h * t) : vec3(h - 2 * h * (t - 1), 0, h);
        m.positions.push_back(q);
    }
    for (uint32_t i = 1; i + 1 < m.positions.size(); ++i) {
        m.triangles.push_back(glm::uvec3(0, i + 1, i));  // counter-clockwise seen from +Y
    }
    m.triangles.push_back(glm::uvec3(0, 0, 5));   // repeated corner
    m.triangles.push_back(glm::uvec3(1, 2, 3));   // three points on one edge: collinear
    return m;
}

/// A 1 m box as triangles, one face re-cut into slivers, plus zero-area triangles.
TriangleMesh sliver_box(float size) {
    TriangleMesh m = make_box(vec3(size));
    m.normals.clear();
    m.uvs.clear();
    const float h = 0.5f * size;
    // Extra sliver triangles lying exactly in the top face (coplanar with it, inside it).
    const uint32_t base = uint32_t(m.positions.size());
    m.positions.push_back(vec3(-h, h, -h));
    m.positions.push_back(vec3(h, h, h));
    m.positions.push_back(vec3(h, h, h - 1e-6f * size));
    m.positions.push_back(vec3(-h + 1e-7f * size, h, -h));
    m.triangles.push_back(glm::uvec3(base, base + 1, base + 2));
    m.triangles.push_back(glm::uvec3(base, base + 3, base + 1));
    m.triangles.push_back(glm::uvec3(base, base, base + 1));  // zero area
    m.triangles.push_back(glm::uvec3(base + 1, base + 1, base + 1));
    return m;
}

Image render_with_meshes(const Project& p, SceneAssets assets, int passes) {
    auto scene = std::make_shared<RenderScene>(p, std::move(assets));
    ProgressiveRenderer r(scene, settings(100000, 6));
    for (int i = 0; i < passes; ++i) EXPECT_TRUE(r.render_pass());
    EXPECT_EQ(r.stats().non_finite_samples, 0u);
    return r.image();
}

}  // namespace

TEST(AwkwardGeometry, SliverAndZeroAreaTrianglesRenderLikeTheCleanMeshes) {
    // Same surfaces, two triangulations: a plane ground (2 triangles) against a fan of slivers,
    // a box (12 triangles) against one with extra coplanar slivers and zero-area triangles.
    // Check: all finite, and the images agree within 1% relative RMSE over the changed pixels.
    const int w = 96, h = 72;
    Image probe = sun_sky();
    Project p = look_at_project(vec3(0, 2.0f, 3.2f), vec3(0, 0.3f, 0), 45);
    RealProxy ground = ground_plane(vec3(0.5f));
    ground.shape.kind = Shape::Kind::Mesh;
    p.real.push_back(ground);
    VirtualObject box;
    box.name = "box";
    box.shape.kind = Shape::Kind::Mesh;
    box.transform.translation = vec3(0, 0.5f, 0);
    box.transform.rotation_deg = vec3(0, 25, 0);
    box.material = diffuse(vec3(0.6f, 0.5f, 0.4f));
    p.objects.push_back(box);
    p.objects.push_back(sphere(vec3(-1.0f, 0.3f, 0.4f), 0.3f, glass(1.5f)));

    SceneAssets clean;
    SunProbe dummy;
    {
        SceneAssets a;
        a.photo = Image(w, h);
        a.probe_latlong = probe;
        a.real_meshes = {make_plane(40, 40)};
        a.object_meshes = {make_box(vec3(1.0f)), TriangleMesh{}};
        RenderScene tmp(p, a);
        ReferenceOptions o;
        o.samples_per_pixel = 8;
        o.include_virtual = false;
        clean.photo = render_reference(tmp, o);
    }
    clean.probe_latlong = probe;
    SceneAssets slivers = clean;
    clean.real_meshes = {make_plane(40, 40)};
    clean.object_meshes = {make_box(vec3(1.0f)), TriangleMesh{}};
    clean.object_meshes[0].normals.clear();
    clean.object_meshes[0].uvs.clear();
    slivers.real_meshes = {sliver_plane(40)};
    slivers.object_meshes = {sliver_box(1.0f), TriangleMesh{}};

    Image a = render_with_meshes(p, clean, 4);
    Image b = render_with_meshes(p, slivers, 4);
    EXPECT_EQ(count_non_finite(a), 0u);
    EXPECT_EQ(count_non_finite(b), 0u);
    auto changed = [&](size_t i) { return a[i] != clean.photo[i] || b[i] != clean.photo[i]; };
    size_t n = 0;
    for (size_t i = 0; i < a.size(); ++i) n += changed(i);
    double e = relative_rmse(b, a, changed);
    std::printf("slivers: relative RMSE against the clean meshes over %zu changed pixels: %.2e\n", n, e);
    EXPECT_GT(n, a.size() / 10);
    EXPECT_LT(e, 0.01);
}
