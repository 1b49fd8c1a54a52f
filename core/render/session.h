#pragma once
#include <atomic>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "image/image.h"
#include "render/progressive.h"

namespace dp {

/// Where a run stands after a pass. The pictures are built only when a sink pulls them
/// (pull_images(), during on_update): a full-size image per pass is work a CLI render does not
/// need and a viewer needs only as often as it paints.
struct RenderUpdate {
    RenderStats stats;
    int target_passes = 0;    ///< 0 when rendering to a time budget
    double time_budget_s = 0; ///< 0 when rendering a number of passes
    bool finished = false;    ///< last update of this run (budget reached, or cancelled)
    bool cancelled = false;   ///< the run was cancelled after this update's passes

    Image image;  ///< augmented photo (linear), after pull_images()
    Image dL;     ///< signed change of the real surfaces' radiance, after pull_images()
    Image alpha;  ///< virtual-object coverage, after pull_images()
    Image variance;  ///< the renderer's variance_layer(), after pull_images() (may be empty)
    /// Builds image, dL, alpha and (unless `with_variance` is false: a picture no denoiser
    /// will see) variance from the renderer. Only during RenderSink::on_update.
    void pull_images(bool with_variance = true);
    bool has_images() const { return !image.empty(); }

    const PassRenderer* source = nullptr;  ///< valid only during on_update
};

/// Receives progress from the render thread. Implementations must return quickly and never
/// call back into the session from on_update (pull what they need, copy it and hand it on).
class RenderSink {
public:
    virtual ~RenderSink() = default;
    virtual void on_update(const RenderUpdate& update) = 0;
    /// Called once when a run stops for good (finished, cancelled or failed).
    virtual void on_stopped(bool cancelled, const std::string& error) {}
};

/// Owns the render thread: start, cancel, reset and wait, as a viewer needs.
class RenderSession {
public:
    explicit RenderSession(RenderSink* sink);
    ~RenderSession();
    RenderSession(const RenderSession&) = delete;
    RenderSession& operator=(const RenderSession&) = delete;

    /// Starts rendering `scene` with `settings` (cancelling any run); settings.threads <= 0
    /// uses all cores.
    void start(std::shared_ptr<const RenderScene> scene, const RenderSettings& settings);
    /// Asks the render thread to stop at the next check; returns at once.
    void cancel();
    /// Blocks until the current run has finished its budget or was cancelled.
    void wait();
    /// Restarts refinement from pass zero on a (possibly edited) scene.
    void reset(std::shared_ptr<const RenderScene> scene, const RenderSettings& settings) {
        start(std::move(scene), settings);
    }
    bool running() const { return running_.load(); }
    /// Chooses the renderer of later runs (default: differential photon mapping). Takes effect
    /// at the next start().
    void set_renderer_factory(RendererFactory factory);
    /// The exception that ended the last run (null if it finished or was cancelled), for a
    /// caller that reports failures by kind (out of memory, bad input) rather than by text.
    /// Read after wait().
    std::exception_ptr failure() const {
        std::lock_guard<std::mutex> lock(failure_mutex_);
        return failure_;
    }

private:
    void run(std::shared_ptr<const RenderScene> scene, const RenderSettings& settings, const RendererFactory& factory);

    RenderSink* sink_;
    RendererFactory factory_;
    std::thread thread_;
    std::atomic<bool> cancel_{false};
    std::atomic<bool> running_{false};
    std::mutex mutex_;
    mutable std::mutex failure_mutex_;
    std::exception_ptr failure_;
};

}  // namespace dp
