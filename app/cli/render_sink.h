#pragma once
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>

#include "progress.h"
#include "render/session.h"

namespace dp::cli {

/// Receives a session's passes: keeps the latest update for writing, reports progress, and
/// lets the main thread wait for the end of the run.
class CliSink : public RenderSink {
public:
    explicit CliSink(Progress& progress) : progress_(progress) {}

    void on_update(const RenderUpdate& update) override;
    void on_stopped(bool cancelled, const std::string& error) override;

    /// Waits up to `timeout` for on_stopped; true once the run has stopped.
    bool wait_stopped(std::chrono::milliseconds timeout);

    /// The last update received (empty if no pass completed). Call after the run stopped.
    std::optional<RenderUpdate> take_last();
    bool cancelled() const { return cancelled_; }
    const std::string& error() const { return error_; }

private:
    Progress& progress_;
    std::mutex mutex_;
    std::condition_variable stopped_cv_;
    std::optional<RenderUpdate> last_;
    bool stopped_ = false;
    bool cancelled_ = false;
    std::string error_;
};

}  // namespace dp::cli
