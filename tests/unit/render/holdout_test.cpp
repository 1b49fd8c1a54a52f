// Holdouts: a real occluder the proxies do not model, painted over the photo at a depth. What lies
// beyond it is hidden where its mask covers the frame; what it casts still falls where it is seen.
#include <gtest/gtest.h>

#include "common/test_scenes.h"
#include "reference/standard_differential.h"
#include "render/progressive.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr int kW = 64, kH = 48;

/// A clay ball on a grey floor, lit from the left so that its shadow falls to the right of it.
struct BallScene {
    SunProbe sun;
    Project project = look_at_project(vec3(0, 1.5f, 4), vec3(0, 0.4f, 0), 45);
    BallScene() {
        // The probe pixel nearest a sun 35 degrees up in the -x direction.
        const vec3 want = glm::normalize(vec3(-1, 0.7f, 0));
        float best = -2;
        for (int y = 0; y < sun.height; ++y)
            for (int x = 0; x < sun.width; ++x) {
                const float c = glm::dot(latlong_direction((x + 0.5f) / sun.width, (y + 0.5f) / sun.height), want);
                if (c > best) best = c, sun.px = x, sun.py = y;
            }
        project.real.push_back(ground_plane(vec3(0.5f)));
        project.objects.push_back(sphere(vec3(-0.4f, 0.4f, 0), 0.4f, diffuse(vec3(0.8f))));
    }
    /// A mask over columns [x0, x1) of the frame, at `depth` metres.
    static HoldoutMask columns(int x0, int x1, float depth) {
        Image m(kW, kH);
        for (int y = 0; y < kH; ++y)
            for (int x = x0; x < x1; ++x) m.at(x, y) = vec3(1);
        return HoldoutMask::from_image(m, depth);
    }
    std::shared_ptr<RenderScene> scene(std::vector<HoldoutMask> holdouts = {}) const {
        SceneAssets a;
        a.photo = analytic_ground_photo(project, kW, kH, sun, vec3(0.5f));
        a.probe_latlong = sun.image();
        a.holdouts = std::move(holdouts);
        Project p = project;
        for (size_t i = 0; i < a.holdouts.size(); ++i) p.holdouts.push_back({"h", "h.png", a.holdouts[i].depth});
        return std::make_shared<RenderScene>(p, std::move(a));
    }
};

struct Rendered {
    Image image, alpha;
};

Rendered render(std::shared_ptr<RenderScene> scene) {
    RenderSettings s = settings(40000, 7);
    s.adaptive_threshold = 0;  // every pixel every pass: renders compare pixel for pixel
    ProgressiveRenderer r(scene, s);
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(r.render_pass());
    return {r.image(), r.alpha_layer()};
}

/// The columns [x0, x1) the ball covers in `alpha`.
void ball_columns(const Image& alpha, int& x0, int& x1) {
    x0 = kW, x1 = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            if (alpha.at(x, y).x > 0) x0 = std::min(x0, x), x1 = std::max(x1, x + 1);
}

}  // namespace

TEST(Holdout, AnObjectBehindTheOccluderIsHiddenAndItsShadowStillFalls) {
    BallScene b;
    const Rendered plain = render(b.scene());
    int x0, x1;
    ball_columns(plain.alpha, x0, x1);
    ASSERT_LT(x0, x1);
    // The occluder covers the ball's columns and one more on each side (a sample on a pixel's
    // edge may round into its neighbour), 2 m from the camera (the ball is about 4 m off).
    auto held = b.scene({BallScene::columns(x0 - 1, x1 + 1, 2.0f)});
    const Rendered out = render(held);
    const Image& photo = held->photo();
    size_t shadowed = 0, shadowed_plain = 0, outside = 0;
    double diff = 0, sum = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            if (x >= x0 && x < x1) {
                // Check: under the mask the photo stands, untouched, and nothing is covered.
                ASSERT_EQ(out.image.at(x, y), photo.at(x, y)) << x << "," << y;
                ASSERT_EQ(out.alpha.at(x, y), vec3(0)) << x << "," << y;
            } else if (x < x0 - 1 || x > x1) {
                // Elsewhere: the render without the holdout, shadow included, but for noise (the
                // floor behind the occluder now sends rho E / pi, not the photo, as bounce light).
                diff += std::abs(luminance(out.image.at(x, y)) - luminance(plain.image.at(x, y)));
                sum += luminance(plain.image.at(x, y));
                ++outside;
                shadowed += luminance(out.image.at(x, y)) < 0.7f * luminance(photo.at(x, y));
                shadowed_plain += luminance(plain.image.at(x, y)) < 0.7f * luminance(photo.at(x, y));
            }
        }
    EXPECT_LT(diff / sum, 0.01);
    // Check: the hidden ball's shadow still falls where the photo is seen, as without the holdout.
    EXPECT_GT(shadowed, 20u);
    EXPECT_NEAR(double(shadowed), double(shadowed_plain), 0.1 * double(shadowed_plain));
}

TEST(Holdout, AnObjectNearerThanTheOccluderShowsOverIt) {
    BallScene b;
    const Rendered plain = render(b.scene());
    int x0, x1;
    ball_columns(plain.alpha, x0, x1);
    // The occluder stands 6 m off, behind the ball: the ball shows over it, the floor beyond
    // 6 m along the view axis is hidden.
    auto held = b.scene({BallScene::columns(x0, x1, 6.0f)});
    const Rendered out = render(held);
    // Check: the ball covers the same pixels, and looks the same but for noise (the floor it
    // sees behind the occluder now sends rho E / pi, estimated, not the photo).
    size_t ball = 0;
    double sum_out = 0, sum_plain = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = x0; x < x1; ++x)
            if (plain.alpha.at(x, y).x > 0) {
                ++ball;
                ASSERT_EQ(out.alpha.at(x, y), plain.alpha.at(x, y)) << x << "," << y;
                ASSERT_NEAR(luminance(out.image.at(x, y)) / luminance(plain.image.at(x, y)), 1.0f, 0.05f)
                    << x << "," << y;
                sum_out += luminance(out.image.at(x, y));
                sum_plain += luminance(plain.image.at(x, y));
            }
    EXPECT_GT(ball, 30u);
    EXPECT_NEAR(sum_out / sum_plain, 1.0, 0.01);
}

TEST(Holdout, TheCameraDoesNotSeeARealPointBehindTheOccluder) {
    BallScene b;
    auto plain = b.scene();
    auto held = b.scene({BallScene::columns(0, kW / 2, 2.0f)});
    // A floor point seen through the left half of the frame, about 4.5 m off, and one in the right half.
    const vec3 left(-1.2f, 0, 0), right(1.2f, 0, 0), up(0, 1, 0);
    EXPECT_TRUE(plain->camera_sees(left, up));
    EXPECT_FALSE(held->camera_sees(left, up));  // the photo shows the occluder there
    EXPECT_TRUE(held->camera_sees(right, up));
    // Nearer than the occluder, the point is seen.
    auto far_occluder = b.scene({BallScene::columns(0, kW / 2, 20.0f)});
    EXPECT_TRUE(far_occluder->camera_sees(left, up));
}

TEST(Holdout, TheStandardDifferentialReferenceHidesWhatIsBehindTheOccluderToo) {
    BallScene b;
    auto plain_scene = b.scene();
    RenderSettings s = settings(0, 3);
    StandardDifferentialRenderer plain(plain_scene, s, StandardDifferentialRenderer::Sampling::Correlated);
    ASSERT_TRUE(plain.render_pass());
    int x0, x1;
    ball_columns(plain.alpha_layer(), x0, x1);
    auto held_scene = b.scene({BallScene::columns(x0, x1, 2.0f)});
    StandardDifferentialRenderer held(held_scene, s, StandardDifferentialRenderer::Sampling::Correlated);
    ASSERT_TRUE(held.render_pass());
    const Image out = held.image(), alpha = held.alpha_layer();
    for (int y = 0; y < kH; ++y)
        for (int x = x0; x < x1; ++x) {
            ASSERT_EQ(out.at(x, y), held_scene->photo().at(x, y)) << x << "," << y;
            ASSERT_EQ(alpha.at(x, y), vec3(0)) << x << "," << y;
        }
}

TEST(Holdout, AMaskIsThresholdedAtHalfAndStretchedOverTheFrame) {
    // A 4x2 mask over any frame: its right half, then the top-left quarter at 0.6, 0.4 below.
    Image m(4, 2);
    m.at(2, 0) = m.at(3, 0) = m.at(2, 1) = m.at(3, 1) = vec3(1);
    m.at(0, 0) = vec3(0.6f);
    m.at(0, 1) = vec3(0.4f);
    const HoldoutMask h = HoldoutMask::from_image(m, 3);
    EXPECT_TRUE(h.covers(0.6f, 0.1f));
    EXPECT_TRUE(h.covers(0.99f, 0.99f));
    EXPECT_FALSE(h.covers(0.3f, 0.5f));
    EXPECT_TRUE(h.covers(0.1f, 0.4f));   // 0.6 >= 0.5
    EXPECT_FALSE(h.covers(0.1f, 0.6f));  // 0.4 < 0.5
    EXPECT_FALSE(h.covers(-0.01f, 0.5f));
    EXPECT_FALSE(h.covers(0.5f, 1.0f));
    EXPECT_DOUBLE_EQ(h.coverage(), 5.0 / 8.0);
}
