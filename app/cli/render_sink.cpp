#include "render_sink.h"

namespace dp::cli {

void CliSink::on_update(const RenderUpdate& update) {
    ProgressState s;
    s.unit = "pass";
    s.done = update.stats.passes;
    s.total = update.target_passes;
    s.budget_s = update.time_budget_s;
    if (update.stats.photons_emitted > 0 || update.stats.samples_per_pixel == 0) {
        s.rate_name = "photons/s";
        s.rate = update.stats.photons_per_second;
    } else {  // path-traced methods: camera samples per pixel and second
        s.rate_name = "spp/s";
        s.rate = update.stats.seconds > 0 ? double(update.stats.samples_per_pixel) / update.stats.seconds : 0;
    }
    if (update.stats.estimated_rel_error >= 0) s.estimated_error = update.stats.estimated_rel_error;
    if (!update.cancelled) progress_.update(s);
    if (!update.finished) return;  // the pictures of the last pass are all a render writes
    RenderUpdate last = update;
    last.pull_images();
    last.source = nullptr;
    std::lock_guard<std::mutex> lock(mutex_);
    last_ = std::move(last);
}

void CliSink::on_stopped(bool cancelled, const std::string& error) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopped_ = true;
        cancelled_ = cancelled;
        error_ = error;
    }
    stopped_cv_.notify_all();
}

bool CliSink::wait_stopped(std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return stopped_cv_.wait_for(lock, timeout, [&] { return stopped_; });
}

std::optional<RenderUpdate> CliSink::take_last() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::move(last_);
}

}  // namespace dp::cli
