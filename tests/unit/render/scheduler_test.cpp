// The viewer's render policy without a window: the quick pass of an edit and of a drag frame,
// the drag's size steps, the refinement's budget, when a refinement is clean, and when a
// refined frame is denoised.
#include <gtest/gtest.h>

#include "render/scheduler.h"

using namespace dp;

namespace {

RenderSettings project_settings() {
    RenderSettings s;
    s.photons_per_pass = 400000;
    s.passes = 24;
    s.initial_radius = 0.05f;
    return s;
}

}  // namespace

TEST(RenderScheduler, AnEditsQuickPassIsHalfSizeAtMostAHundredThousandPixelsWithAnEighthOfThePhotons) {
    RenderScheduler s;
    const RenderScheduler::Pass small = s.quick_pass(project_settings(), 320, 180, false);
    EXPECT_EQ(small.width, 160);
    EXPECT_EQ(small.height, 90);
    EXPECT_EQ(small.settings.photons_per_pass, 50000);
    EXPECT_GT(small.settings.passes, 1000) << "refines at its size until the full render replaces it";
    EXPECT_FLOAT_EQ(*small.settings.initial_radius, 0.1f) << "fewer photons gather wider";
    const RenderScheduler::Pass hd = s.quick_pass(project_settings(), 1920, 1080, false);
    EXPECT_LE(double(hd.width) * hd.height, 100000.0);
    EXPECT_NEAR(double(hd.width) / hd.height, 1920.0 / 1080.0, 0.02);
}

TEST(RenderScheduler, ADragFrameIsOnePassAtItsLevelsBudgetWithPhotonsFollowingThePixels) {
    RenderScheduler s;
    const RenderScheduler::Pass edit = s.quick_pass(project_settings(), 1280, 720, false);
    const RenderScheduler::Pass drag = s.quick_pass(project_settings(), 1280, 720, true);
    EXPECT_EQ(drag.settings.passes, 1);
    EXPECT_LE(double(drag.width) * drag.height, drag_preview_pixels(s.drag_level()) * 1.0001);
    EXPECT_LT(drag.width, edit.width);
    const double share = drag_preview_pixels(s.drag_level()) / drag_preview_pixels(0);
    EXPECT_EQ(drag.settings.photons_per_pass, int64_t(50000 * share));
    // Never fewer than 2000 photons, however small.
    RenderSettings few = project_settings();
    few.photons_per_pass = 1000;
    EXPECT_EQ(s.quick_pass(few, 1280, 720, true).settings.photons_per_pass, 2000);
}

TEST(RenderScheduler, SlowDragFramesStepTheSizeDownToTheSmallestAndFastOnesStepItBackUp) {
    RenderScheduler s;
    s.set_drag_target(40);
    const int start = s.drag_level();
    s.drag_frame_took(40);  // on target: no step
    EXPECT_EQ(s.drag_level(), start);
    s.drag_frame_took(0);  // no frame yet: no step
    EXPECT_EQ(s.drag_level(), start);
    for (int i = 0; i < 20; ++i) s.drag_frame_took(100);
    EXPECT_EQ(s.drag_level(), kDragPreviewLevels - 1);
    const int smallest = s.quick_pass(project_settings(), 1280, 720, true).width;
    s.drag_frame_took(10);
    EXPECT_EQ(s.drag_level(), kDragPreviewLevels - 2);
    EXPECT_GT(s.quick_pass(project_settings(), 1280, 720, true).width, smallest);
    for (int i = 0; i < 20; ++i) s.drag_frame_took(10);
    EXPECT_EQ(s.drag_level(), 0);
}

TEST(RenderScheduler, AnEndlessRefinementHasNoBudgetAndAFiniteOneKeepsTheProjects) {
    RenderSettings p = project_settings();
    p.time_budget_s = 30;
    const RenderSettings endless = RenderScheduler::refinement(p, true);
    EXPECT_EQ(endless.time_budget_s, 0);
    EXPECT_GE(endless.passes, 1 << 30);
    EXPECT_EQ(endless.photons_per_pass, p.photons_per_pass);
    EXPECT_EQ(RenderScheduler::refinement(p, false), p);
}

TEST(RenderScheduler, ARefinementIsCleanAfterAFewPassesOnceItsErrorIsAtTheTarget) {
    RenderScheduler s;
    RenderStats st;
    st.mean_changed_value = 0.18;
    st.passes = 7;
    st.estimated_rel_error = 0.0001;
    EXPECT_FALSE(s.clean_enough(st)) << "the estimate needs a few passes";
    st.passes = 8;
    st.estimated_rel_error = -1;
    EXPECT_FALSE(s.clean_enough(st)) << "no estimate yet";
    // Without a target: invisible at the display exposure; a brighter display shows less noise.
    const double invisible = invisible_relative_error(0.18, 0);
    EXPECT_DOUBLE_EQ(s.stop_error(st), invisible);
    st.estimated_rel_error = 0.99 * invisible;
    EXPECT_TRUE(s.clean_enough(st));
    st.estimated_rel_error = 1.01 * invisible;
    EXPECT_FALSE(s.clean_enough(st));
    s.set_display_exposure(2);
    EXPECT_LT(s.stop_error(st), invisible);
    // An explicit target wins.
    s.set_noise_target(0.05);
    st.estimated_rel_error = 0.049;
    EXPECT_TRUE(s.clean_enough(st));
    st.estimated_rel_error = 0.051;
    EXPECT_FALSE(s.clean_enough(st));
}

TEST(RenderScheduler, TheDenoiserTakesANewStateAndTheLastFrameAtOnceAndOthersEveryFewSeconds) {
    EXPECT_TRUE(RenderScheduler::denoise_due(true, false, 0, 5000));
    EXPECT_TRUE(RenderScheduler::denoise_due(false, true, 10, 5000));
    EXPECT_FALSE(RenderScheduler::denoise_due(false, false, 1999, 100));
    EXPECT_TRUE(RenderScheduler::denoise_due(false, false, 2000, 100));
    // An expensive denoise is asked for less often: three times its cost apart.
    EXPECT_FALSE(RenderScheduler::denoise_due(false, false, 5000, 2000));
    EXPECT_TRUE(RenderScheduler::denoise_due(false, false, 6000, 2000));
}

TEST(RenderScheduler, TheShownPictureIsCleanAtTheSameTargetAfterTheSameFewPasses) {
    RenderScheduler s;
    s.set_noise_target(0.02);
    RenderStats st;
    st.passes = RenderScheduler::kMinPassesBeforeStop;
    st.estimated_rel_error = 0.06;  // the raw sums are far from it
    EXPECT_FALSE(s.clean_enough(st));
    EXPECT_TRUE(s.shown_clean(0.019, st));
    EXPECT_FALSE(s.shown_clean(0.021, st));
    EXPECT_FALSE(s.shown_clean(-1, st)) << "no estimate yet";
    st.passes = RenderScheduler::kMinPassesBeforeStop - 1;
    EXPECT_FALSE(s.shown_clean(0.001, st));
}
