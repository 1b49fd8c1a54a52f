#include <gtest/gtest.h>

#include <cmath>

#include "base/euler.h"
#include "base/error.h"
#include "probe/probe.h"
#include "reconstruction/probe_align.h"
#include "common/synthetic_photo.h"

using namespace dp;
using namespace dp::test;

namespace {

constexpr float kDeg = 180.0f / kPi;

float angle_deg(vec3 a, vec3 b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f)) * kDeg;
}
float azimuth_deg(vec3 d) { return std::atan2(d.x, -d.z) * kDeg; }

Camera cue_camera() {
    return Camera::look_at(640, 480, vec3(0.5f, 1.7f, 6.0f), vec3(0, 0.3f, 0), vec3(0, 1, 0), 55.0f);
}

/// Clicks for a vertical pole at `base` of height `h` under a sun in world direction `sun`.
ShadowCue pole_cue(const Camera& cam, vec3 base, float h, vec3 sun, bool click_base, bool round) {
    vec3 top = base + vec3(0, h, 0);
    vec3 tip = top - sun * (h / sun.y);
    vec2 a, b;
    EXPECT_TRUE(cam.project(click_base ? base : top, a));
    EXPECT_TRUE(cam.project(tip, b));
    if (round) {
        a = glm::round(a);
        b = glm::round(b);
    }
    ShadowCue cue;
    cue.object_px = a;
    cue.height = h;
    cue.object_is_base = click_base;
    cue.shadow_px = b;
    return cue;
}

}  // namespace

TEST(ProbeAlign, EulerAnglesOfARotationMatrixRebuildTheSameMatrix) {
    for (vec3 deg : {vec3(0), vec3(10, 20, 30), vec3(-70, 45, 160), vec3(5, -89, 12), vec3(170, 10, -100)}) {
        glm::mat3 R = euler_xyz_deg(deg);
        glm::mat3 back = euler_xyz_deg(euler_xyz_from_matrix(R));
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) EXPECT_NEAR(back[c][r], R[c][r], 1e-4f) << deg.x << " " << deg.y << " " << deg.z;
    }
}

TEST(ProbeAlign, BrightestRegionOfASunAndSkyProbeIsTheSun) {
    vec3 sun = glm::normalize(vec3(-0.3f, 0.5f, 0.8f));
    Image probe = make_sun_sky_probe(256, 128, sun, vec3(5000.0f), 1.5f, vec3(0.3f, 0.4f, 0.8f), vec3(0.6f));
    // A pixel of this map spans 1.4 degrees.
    EXPECT_LT(angle_deg(brightest_direction(probe), sun), 0.5f);
}

TEST(ProbeAlign, AShadowCueClickedToTheNearestPixelRecoversAKnownProbeYawWithinOneDegree) {
    // The probe was shot with its sun at `sun_probe`; in the photo's world the sun is that
    // direction turned by `true_yaw` about +Y. The clicks are rounded to whole pixels.
    const vec3 sun_probe = glm::normalize(vec3(0.5f, 0.6f, 0.4f));
    Image probe = make_sun_sky_probe(512, 256, sun_probe, vec3(5000.0f), 1.0f, vec3(0.3f, 0.4f, 0.8f), vec3(0.6f));
    Camera cam = cue_camera();
    for (float true_yaw : {-150.0f, -40.0f, 25.0f, 110.0f}) {
        vec3 sun_world = euler_xyz_deg(vec3(0, true_yaw, 0)) * sun_probe;
        for (bool click_base : {false, true}) {
            ShadowCue cue = pole_cue(cam, vec3(-0.4f, 0, 0.5f), 1.2f, sun_world, click_base, true);
            vec3 sun = sun_direction_from_shadow(cam, cue);
            EXPECT_LT(angle_deg(sun, sun_world), 1.0f) << true_yaw;
            ProbeYaw yaw = align_probe_yaw(brightest_direction(probe), vec3(0), sun);
            float err = std::abs(std::remainder(yaw.rotation_deg.y - true_yaw, 360.0f));
            RecordProperty("yaw_error_deg_" + std::to_string(int(true_yaw)) + (click_base ? "_base" : "_top"),
                           std::to_string(err));
            EXPECT_LT(err, 1.0f) << true_yaw << (click_base ? " base" : " top");
            EXPECT_LT(std::abs(yaw.elevation_mismatch_deg), 1.0f);
        }
    }
}

TEST(ProbeAlign, AlignmentKeepsATiltedProbesTiltAndMatchesTheAzimuth) {
    const vec3 bright = glm::normalize(vec3(0.2f, 0.7f, -0.6f));
    const vec3 target = glm::normalize(vec3(-0.8f, 0.5f, 0.3f));
    ProbeYaw yaw = align_probe_yaw(bright, vec3(8, 30, -5), target);
    vec3 now = euler_xyz_deg(yaw.rotation_deg) * bright;
    EXPECT_NEAR(std::remainder(azimuth_deg(now) - azimuth_deg(target), 360.0f), 0.0f, 0.01f);
    // Only a turn about world Y was added: the elevation is unchanged.
    vec3 before = euler_xyz_deg(vec3(8, 30, -5)) * bright;
    EXPECT_NEAR(now.y, before.y, 1e-5f);
    EXPECT_NEAR(yaw.elevation_mismatch_deg, (std::asin(now.y) - std::asin(target.y)) * kDeg, 1e-3f);
}

TEST(ProbeAlign, BadShadowCuesAreRejectedWithAClearMessage) {
    Camera cam = cue_camera();
    ShadowCue cue = pole_cue(cam, vec3(0), 1, glm::normalize(vec3(0.3f, 0.8f, 0.2f)), true, false);
    ShadowCue sky = cue;
    sky.shadow_px = vec2(320, 3);  // above the horizon
    EXPECT_THROW(sun_direction_from_shadow(cam, sky), InputError);
    ShadowCue flat = cue;
    flat.height = 0;
    EXPECT_THROW(sun_direction_from_shadow(cam, flat), InputError);
    ShadowCue overhead = cue;
    overhead.shadow_px = overhead.object_px;
    EXPECT_THROW(sun_direction_from_shadow(cam, overhead), InputError);
    EXPECT_THROW(brightest_direction(Image(8, 4)), InputError);
}

TEST(ProbeAlign, AGreyCardRecoversTheProbeIntensityWithinTwoPercent) {
    // The photo was lit by the probe at 2.5 times its file's intensity; the project says 1.
    Project p = look_at_project(vec3(0, 2.0f, 4.0f), vec3(0, 0, 0), 40.0f);
    p.real.push_back(ground_plane(vec3(0.18f), 8.0f));
    p.probe.intensity = 2.5f;
    Image probe = sky_probe(glm::normalize(vec3(0.4f, 0.7f, 0.3f)));
    auto scene = photographed(p, probe, {Image()}, 64, 48, 64);
    Project q = scene->project();
    q.probe.intensity = 1.0f;
    auto scene1 = build(q, scene->photo(), probe);
    GreyCard card;
    card.x0 = 24;
    card.y0 = 28;
    card.x1 = 39;
    card.y1 = 38;
    card.reflectance = 0.18f;
    ExposureMatch m = match_exposure_grey_card(*scene1, card);
    RecordProperty("intensity", std::to_string(m.intensity));
    EXPECT_NEAR(m.intensity, 2.5f, 0.05f);  // 2%
    EXPECT_EQ(m.pixels, 16 * 11);
    // A card that leaves the photo, or shows no proxy, is an error.
    GreyCard outside = card;
    outside.x1 = 200;
    EXPECT_THROW(match_exposure_grey_card(*scene1, outside), InputError);
    GreyCard sky_card = card;
    sky_card.y0 = 0;
    sky_card.y1 = 2;
    EXPECT_THROW(match_exposure_grey_card(*scene1, sky_card), InputError);
}

namespace {

/// The card of the grey-card tests: a rectangle of the ground seen by their camera.
GreyCard ground_card() {
    GreyCard card;
    card.x0 = 24;
    card.y0 = 28;
    card.x1 = 39;
    card.y1 = 38;
    card.reflectance = 0.18f;
    return card;
}

/// A photo of a grey ground lit by the probe with `tint` (and `intensity`), and the scene of a
/// project that says the probe is neutral at intensity 1.
std::shared_ptr<RenderScene> photographed_with_tint(vec3 tint, float intensity) {
    Project p = look_at_project(vec3(0, 2.0f, 4.0f), vec3(0, 0, 0), 40.0f);
    p.real.push_back(ground_plane(vec3(0.18f), 8.0f));
    p.probe.intensity = intensity;
    p.probe.white_balance = tint;
    Image probe = sky_probe(glm::normalize(vec3(0.4f, 0.7f, 0.3f)));
    auto scene = photographed(p, probe, {Image()}, 64, 48, 64);
    Project q = scene->project();
    q.probe.intensity = 1.0f;
    q.probe.white_balance = vec3(1.0f);
    return build(q, scene->photo(), probe);
}

}  // namespace

TEST(ProbeAlign, AGreyCardRecoversTheProbesTintWithinTwoPercentPerChannel) {
    // The probe was shot with another white balance: the card in the photo is warm, while the
    // project's probe lights it with the sky's own colour.
    const vec3 tint(1.2f, 1.0f, 0.7f);
    auto scene = photographed_with_tint(tint, 1.0f);
    const WhiteBalanceMatch m = match_white_balance_grey_card(*scene, ground_card());
    const float lum = luminance(tint);
    RecordProperty("white_balance", std::to_string(m.white_balance.x) + " " +
                                        std::to_string(m.white_balance.y) + " " +
                                        std::to_string(m.white_balance.z));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(m.white_balance[c], tint[c] / lum, 0.02f * tint[c] / lum) << c;
    EXPECT_NEAR(luminance(m.white_balance), 1.0f, 1e-5f);
    EXPECT_NEAR(m.intensity, lum, 0.02f * lum);
    EXPECT_FLOAT_EQ(m.scale, m.intensity);  // from intensity 1
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.channel_scale[c], tint[c], 0.02f * tint[c]) << c;
    EXPECT_EQ(m.pixels, 16 * 11);
    // The card's colour: the probe alone made it bluer than the photo shows; matched, it is the
    // photo's.
    EXPECT_GT(m.photo_chromaticity.x - m.photo_chromaticity.z,
              m.before_chromaticity.x - m.before_chromaticity.z + 0.05f);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(m.after_chromaticity[c], m.photo_chromaticity[c], 1e-5f);
    // The luminance-only match agrees on the intensity (its own definition of it).
    EXPECT_NEAR(match_exposure_grey_card(*scene, ground_card()).intensity, m.intensity,
                0.02f * m.intensity);
}

TEST(ProbeAlign, AGreyCardUnderTheProjectsOwnProbeGivesANeutralWhiteBalance) {
    auto scene = photographed_with_tint(vec3(1.0f), 1.6f);
    const WhiteBalanceMatch m = match_white_balance_grey_card(*scene, ground_card());
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.white_balance[c], 1.0f, 0.01f) << c;
    EXPECT_NEAR(m.intensity, 1.6f, 0.02f * 1.6f);
}

TEST(ProbeAlign, TheWhiteBalanceMatchStartsFromTheProbesCurrentGain) {
    // Matched once, the project's probe lights the card as photographed: a second match moves
    // nothing, but for the noise of E (the tinted probe is sampled by its own luminance, so the
    // directions differ from the first match's: 0.015 % here).
    const vec3 tint(0.8f, 1.0f, 1.3f);
    auto scene = photographed_with_tint(tint, 2.0f);
    const WhiteBalanceMatch first = match_white_balance_grey_card(*scene, ground_card());
    Project q = scene->project();
    q.probe.intensity = first.intensity;
    q.probe.white_balance = first.white_balance;
    auto matched = build(q, scene->photo(), scene->probe().image());
    const WhiteBalanceMatch again = match_white_balance_grey_card(*matched, ground_card());
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(again.channel_scale[c], 1.0f, 1e-3f) << c;
        EXPECT_NEAR(again.white_balance[c], first.white_balance[c], 1e-3f) << c;
    }
    EXPECT_NEAR(again.intensity, first.intensity, 1e-3f * first.intensity);
    EXPECT_NEAR(again.scale, 1.0f, 1e-3f);
}

TEST(ProbeAlign, AWhiteBalanceFromACardBlackInAChannelIsRefused) {
    auto scene = photographed_with_tint(vec3(1.0f), 1.0f);
    Image photo = scene->photo();
    for (size_t i = 0; i < photo.size(); ++i) photo[i].z = 0;  // no blue anywhere
    auto blind = build(scene->project(), photo, scene->probe().image());
    try {
        match_white_balance_grey_card(*blind, ground_card());
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("black in the photo's blue channel"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_NO_THROW(match_exposure_grey_card(*blind, ground_card()));  // luminance is there
}
