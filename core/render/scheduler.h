#pragma once
#include <atomic>
#include <cstdint>

#include "render/preview.h"
#include "assets/pass_renderer.h"

namespace dp {

/// Decides what a viewer's render does next, as Cycles' RenderScheduler does for its session:
/// the size and photons of the quick pass that answers an edit and of each drag frame (stepping
/// the drag's size to keep its frame time), the refinement's budget, when an endless refinement
/// is clean enough to stop, and when a refined frame goes to the denoiser. It holds no thread
/// and no picture: the session's owner asks it and tells it what happened, so every decision is
/// unit-tested without a window.
///
/// Threads: quick_pass, drag_frame_took and refinement belong to the thread that starts runs;
/// clean_enough may be asked from the render thread while set_noise_target and
/// set_display_exposure are called from another (they are atomics).
class RenderScheduler {
public:
    /// One run's plan: its size and settings.
    struct Pass {
        int width = 0, height = 0;
        RenderSettings settings;
    };

    /// Photons of an edit's quick pass as a fraction of the project's, and its size relative to
    /// the full render (at most PreviewPolicy::max_pixels).
    void set_preview(double photon_fraction, double scale) {
        preview_fraction_ = photon_fraction;
        preview_scale_ = scale;
    }
    /// Time a drag frame should take (milliseconds).
    void set_drag_target(double ms) { drag_target_ms_ = ms; }

    /// The quick pass answering an edit of a width x height render with `project`'s settings.
    /// Interactive (a drag or a slider stroke): one pass at the drag level's pixel budget with
    /// photons following the pixels down (the direct shadow, traced by rays, shows where the
    /// object goes; caustics and bounce light wait for the hand to rest). Otherwise: a preview
    /// at reduced size that refines until the full-size render replaces it.
    Pass quick_pass(const RenderSettings& project, int width, int height, bool interactive) const;
    /// A drag frame took `ms` from request to picture: the next one is a size step smaller
    /// above 1.15 times the target, a step larger under 0.6 times it.
    void drag_frame_took(double ms);
    int drag_level() const { return drag_level_; }

    /// The full-size refinement: the project's passes or time budget, or without a budget
    /// (`endless`: it runs until clean_enough says stop).
    static RenderSettings refinement(const RenderSettings& project, bool endless);

    /// Relative error at which an endless refinement stops; <= 0: the noise is invisible at
    /// the display exposure (invisible_relative_error).
    void set_noise_target(double rel_error) { noise_target_.store(rel_error); }
    double noise_target() const { return noise_target_.load(); }
    void set_display_exposure(double stops) { exposure_.store(stops); }
    /// The error an endless refinement of `stats` stops at (the explicit target, else the
    /// invisible one at the display exposure).
    double stop_error(const RenderStats& stats) const;
    /// Whether an endless refinement may stop after the pass that gave `stats`: a few passes
    /// first (the estimate compares the halves of the passes), then the error at stop_error.
    bool clean_enough(const RenderStats& stats) const;
    static constexpr int kMinPassesBeforeStop = 8;
    /// Whether an endless refinement may stop because the picture the viewer shows is clean:
    /// `shown_error` estimates its error (ShownNoise: the denoised picture's, where the viewer
    /// denoises), compared with the same stop_error, after the same few passes.
    bool shown_clean(double shown_error, const RenderStats& stats) const;

    /// Whether a refined frame goes to the denoiser now: the first frame of a new state and the
    /// last frame of a refinement always; otherwise when `ms_since_last` (since the last frame
    /// was sent) reaches max(2 s, 3 x the last denoise's cost): it takes the cores from the
    /// render.
    static bool denoise_due(bool new_state, bool finished, double ms_since_last, double last_denoise_ms);

private:
    double preview_fraction_ = 0.125;
    double preview_scale_ = 0.5;
    double drag_target_ms_ = 45;
    int drag_level_ = 2;
    std::atomic<double> noise_target_{0};
    std::atomic<double> exposure_{0};
};

}  // namespace dp
