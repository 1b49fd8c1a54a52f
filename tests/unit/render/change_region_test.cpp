// The pixels an object edit can change: the object itself, its surroundings and its sun
// shadow, virtual mirrors; never the rest of the frame.
#include <gtest/gtest.h>

#include "common/test_scenes.h"
#include "render/change_region.h"

using namespace dp;
using namespace dp::test;

namespace {

struct Scene {
    SunProbe sun;
    Project p;
    std::shared_ptr<RenderScene> scene;
    static constexpr int W = 160, H = 96;

    explicit Scene(Material other) {
        p = look_at_project(vec3(0, 2.5f, 6), vec3(0, 0, 0), 50);
        p.real.push_back(ground_plane(vec3(0.5f)));
        p.objects.push_back(sphere(vec3(-1.5f, 0.3f, 0), 0.3f, diffuse(vec3(0.7f))));  // edited
        p.objects.push_back(sphere(vec3(2.0f, 0.3f, 0), 0.3f, other));
        scene = build(p, Image(W, H, vec3(0.3f)), sun.image());
    }
    EditedBounds bounds(int i) const {
        EditedBounds b;
        EXPECT_TRUE(scene->object_bounds(i, b.center, b.radius));
        return b;
    }
    bool at(const std::vector<uint8_t>& mask, const vec3& world) const {
        vec2 px;
        EXPECT_TRUE(scene->camera().project(world, px));
        const int x = int(std::lround(px.x)), y = int(std::lround(px.y));
        EXPECT_TRUE(x >= 0 && y >= 0 && x < W && y < H) << "outside the frame";
        return mask[size_t(y) * W + x] != 0;
    }
};

}  // namespace

TEST(ChangeRegion, CoversTheEditedObjectItsSurroundingsAndItsSunShadowButNotTheRest) {
    Scene s(diffuse(vec3(0.7f)));
    const EditedBounds a = s.bounds(0);
    EXPECT_NEAR(a.radius, 0.3f, 1e-4f);
    const std::vector<uint8_t> mask = change_region(*s.scene, {a});
    EXPECT_TRUE(s.at(mask, a.center));                       // the object
    EXPECT_TRUE(s.at(mask, a.center + vec3(0.6f, -0.3f, 0)));  // the ground beside it
    // Its sun shadow, however long: where the line towards the sun meets the ground.
    const vec3 to_sun = s.sun.direction();
    ASSERT_GT(to_sun.y, 0.05f);
    const vec3 shadow = a.center - to_sun * (a.center.y / to_sun.y);
    if (glm::length(shadow - a.center) > 3 * a.radius) {
        EXPECT_TRUE(s.at(mask, shadow));
    }
    // The other (diffuse) object and the ground far from both are not in it.
    EXPECT_FALSE(s.at(mask, s.bounds(1).center));
    EXPECT_FALSE(s.at(mask, vec3(0.5f, 0, -0.5f)));
    size_t in = 0;
    for (uint8_t m : mask) in += m;
    EXPECT_LT(in, mask.size() / 2) << "the region is most of the frame";
}

TEST(ChangeRegion, CoversWhereTheObjectWasSeenEvenWhereTheNewStateShowsAFarSurface) {
    // The object moves from the air close to the camera down to the ground: its old place is
    // now seen as ground metres behind it, far from both its old and new spheres.
    Scene s(diffuse(vec3(0.7f)));
    EditedBounds before;
    before.center = vec3(0, 2.0f, 3.5f);
    before.radius = 0.3f;
    const EditedBounds after = s.bounds(0);
    const std::vector<uint8_t> mask = change_region(*s.scene, {before, after});
    int seenBefore = 0, farNow = 0;
    for (int y = 0; y < Scene::H; ++y)
        for (int x = 0; x < Scene::W; ++x) {
            const Ray ray = s.scene->camera_ray(float(x), float(y));
            const vec3 to_c = before.center - ray.org;
            const float t = glm::dot(to_c, ray.dir);
            if (t <= 0 || glm::length(to_c - t * ray.dir) > before.radius) continue;
            ++seenBefore;
            EXPECT_TRUE(mask[size_t(y) * Scene::W + x]) << "pixel " << x << "," << y << " showed the object";
            const Hit hit = s.scene->intersect(ray);
            if (hit && glm::length(hit.p - before.center) > kChangeReach * before.radius &&
                glm::length(hit.p - after.center) > kChangeReach * after.radius)
                ++farNow;
        }
    EXPECT_GT(seenBefore, 50);
    // The case the test is about: pixels that now see a surface out of both spheres' reach.
    EXPECT_GT(farNow, seenBefore / 2);
}

TEST(ChangeRegion, IncludesVirtualMirrorsThatMayShowTheEditedObject) {
    Scene s(mirror());
    const std::vector<uint8_t> mask = change_region(*s.scene, {s.bounds(0)});
    EXPECT_TRUE(s.at(mask, s.bounds(1).center));
}

TEST(ChangeRegion, NothingEditedChangesNothing) {
    Scene s(mirror());
    const std::vector<uint8_t> mask = change_region(*s.scene, {});
    for (uint8_t m : mask) ASSERT_EQ(m, 0);
}

TEST(ChangeRegion, DilationGrowsASinglePixelIntoASquareClippedAtTheBorder) {
    const int W = 7, H = 5;
    std::vector<uint8_t> mask(W * H, 0);
    mask[2 * W + 3] = 1;
    mask[0] = 1;
    dilate_mask(mask, W, H, 1);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const bool centre = std::abs(x - 3) <= 1 && std::abs(y - 2) <= 1;
            const bool corner = x <= 1 && y <= 1;
            EXPECT_EQ(mask[size_t(y) * W + x] != 0, centre || corner) << x << "," << y;
        }
}
