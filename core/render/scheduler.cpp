#include "render/scheduler.h"

#include <algorithm>

namespace dp {

RenderScheduler::Pass RenderScheduler::quick_pass(const RenderSettings& project, int width, int height,
                                                  bool interactive) const {
    PreviewPolicy policy;
    policy.photon_fraction = preview_fraction_;
    policy.scale = preview_scale_;
    if (interactive) policy.max_pixels = std::min(policy.max_pixels, drag_preview_pixels(drag_level_));
    Pass pass;
    policy.size(width, height, pass.width, pass.height);
    pass.settings = policy.settings(project);
    if (interactive) {
        pass.settings.passes = 1;  // the next mouse move brings the next pass
        const double share = drag_preview_pixels(drag_level_) / drag_preview_pixels(0);
        pass.settings.photons_per_pass =
            std::max<int64_t>(2000, int64_t(double(pass.settings.photons_per_pass) * share));
    }
    return pass;
}

void RenderScheduler::drag_frame_took(double ms) {
    if (ms > 1.15 * drag_target_ms_) drag_level_ = std::min(drag_level_ + 1, kDragPreviewLevels - 1);
    if (ms > 0 && ms < 0.6 * drag_target_ms_) drag_level_ = std::max(drag_level_ - 1, 0);
}

RenderSettings RenderScheduler::refinement(const RenderSettings& project, bool endless) {
    RenderSettings s = project;
    if (endless) {
        s.passes = 1 << 30;
        s.time_budget_s = 0;
    }
    return s;
}

double RenderScheduler::stop_error(const RenderStats& stats) const {
    const double target = noise_target_.load();
    return target > 0 ? target : invisible_relative_error(stats.mean_changed_value, exposure_.load());
}

bool RenderScheduler::clean_enough(const RenderStats& stats) const {
    return shown_clean(stats.estimated_rel_error, stats);
}

bool RenderScheduler::shown_clean(double shown_error, const RenderStats& stats) const {
    if (stats.passes < kMinPassesBeforeStop || shown_error < 0) return false;
    return shown_error <= stop_error(stats);
}

bool RenderScheduler::denoise_due(bool new_state, bool finished, double ms_since_last, double last_denoise_ms) {
    if (new_state || finished) return true;
    return ms_since_last >= std::max(2000.0, 3.0 * last_denoise_ms);
}

}  // namespace dp
