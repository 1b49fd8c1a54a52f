#pragma once
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "assets/scene_builder.h"
#include "render/edit_region.h"
#include "render/scheduler.h"
#include "render/view_frame.h"

namespace dp {

/// What an interactive session renders next: the latest state of a project being edited.
struct ViewRequest {
    Project project;
    uint64_t generation = 0;   ///< increasing: frames and stops name the request they answer
    bool interactive = false;  ///< a drag or slider stroke: one quick pass, nothing refined
    int width = 0, height = 0; ///< full render size (0: the photo's)
    double preview_fraction = 0.125;  ///< photons of the quick pass, as a fraction
    double preview_scale = 0.5;       ///< size of the quick pass, relative to the full render
    double drag_target_ms = 45;       ///< time a drag frame should take
    bool endless = false;             ///< refine until clean (RenderScheduler::clean_enough)
    int display_max_width = 4096;     ///< composited frames are at most this wide
};

/// Receives an interactive session's pictures on its render thread. Implementations return
/// quickly and never call back into the session (hand the frame on to another thread).
class ViewSink {
public:
    virtual ~ViewSink() = default;
    /// False while the viewer has not taken the last frame: the session then skips building
    /// pictures nobody would see (a run's last frame is always sent).
    virtual bool wants_frame() { return true; }
    virtual void on_frame(std::shared_ptr<RenderFrame> frame) = 0;
    /// A request's refinement reached its budget or was clean (`finished`), or failed (`error`:
    /// loading, building or rendering). Not called for runs replaced by a newer request.
    virtual void on_stopped(uint64_t generation, bool finished, const std::string& error) = 0;
    /// What loading the project's files found (NaN/Inf replaced, an LDR probe, ...), when it
    /// changes.
    virtual void on_warnings(const std::vector<std::string>& warnings) {}
};

/// Renders a project being edited, as Cycles' Session does for a viewport: one long-lived
/// thread owns the scenes and the renderer; reset() records a delayed reset that the thread
/// picks up at its next check (the pass in flight stops there). Each request is answered first
/// by one quick pass at reduced size with fewer photons (RenderScheduler::quick_pass), laid over
/// the last refined picture only where the edit can change it (EditedStates, compose_over);
/// then the full-size scene is built and refined, to the project's budget or until clean. A
/// drag's request is one quick pass at a size the scheduler steps to keep the frame rate, and a
/// newer drag request follows that pass rather than cancelling it, so frames keep coming however
/// fast the mouse moves. A material-only edit makes new scene versions sharing the BVHs
/// (RenderScene::with_materials): a scene a frame holds never changes under it.
class InteractiveSession {
public:
    /// `scenes` loads the project's files and builds scenes (its library may be shared).
    InteractiveSession(std::unique_ptr<SceneBuilder> scenes, ViewSink* sink);
    ~InteractiveSession();
    InteractiveSession(const InteractiveSession&) = delete;
    InteractiveSession& operator=(const InteractiveSession&) = delete;

    /// Renders `request` instead of what runs; returns at once.
    void reset(ViewRequest request);
    /// Stops rendering and drops what was asked; returns at once.
    void stop();
    /// Drops the refined picture later edits are laid over (another project was opened: nothing
    /// of the old picture may show through the new one).
    void forget_picture();
    /// Ends the refinement of request `generation` after its next pass, as clean (the viewer
    /// judged the picture it shows clean: RenderScheduler::shown_clean). Nothing if another
    /// request runs by then.
    void finish_clean(uint64_t generation);
    /// No request waiting and nothing rendering.
    bool idle() const;

    /// The render policy. Its noise target and exposure may be set from any thread.
    RenderScheduler& scheduler() { return scheduler_; }
    const RenderScheduler& scheduler() const { return scheduler_; }

    /// Where the time of the latest request went (milliseconds), for the benchmark.
    struct Timings {
        double cancel = 0;      ///< from reset() to the thread taking the request
        double buildQuick = 0;  ///< building the quick scene (0 when reused)
        double region = 0;      ///< finding the pixels the edit can change
        double firstQuick = 0;  ///< start of the quick pass to its picture
        double compose = 0;     ///< of which laying it over the refined picture
        double buildFull = 0;   ///< building the full-size scene
        double dragFrame = 0;   ///< a drag request's frame: scene, region, pass and compositing
        int dragLevel = 0;      ///< the drag preview size (drag_preview_pixels)
    };
    Timings timings() const;
    /// Scenes (BVHs) built so far: material-only edits must not add to it.
    int scenes_built() const { return scenes_built_.load(); }

private:
    enum class Phase { Quick, Drag, Full };
    struct Run;
    void thread_main();
    void start(const ViewRequest& r, std::chrono::steady_clock::time_point asked);
    void step();
    void start_full();
    /// A quick pass or drag frame laid over the refined picture renders only the pixels its
    /// region covers (a material stroke's at full size where its region is small enough).
    void frame_the_region(Run& run, bool material);
    bool replaced() const;

    std::unique_ptr<SceneBuilder> scenes_;
    ViewSink* sink_;
    RenderScheduler scheduler_;
    // Render-thread state.
    Project built_;
    bool have_scenes_ = false;
    std::shared_ptr<const RenderScene> quick_, full_;
    int full_w_ = 0, full_h_ = 0, quick_w_ = 0, quick_h_ = 0;
    EditedStates states_;
    std::shared_ptr<const RenderFrame> base_;  ///< the refined picture edits are laid over
    std::unique_ptr<Run> run_;
    std::vector<std::string> warned_;
    double last_drag_ms_ = 0;

    std::thread thread_;
    mutable std::mutex mutex_;
    std::condition_variable cv_;
    std::optional<ViewRequest> pending_;
    std::chrono::steady_clock::time_point pending_since_;
    std::atomic<bool> cancel_{false};
    bool quit_ = false, stop_ = false, forget_ = false, busy_ = false;
    uint64_t clean_generation_ = 0;  ///< finish_clean()'s request
    bool drag_in_flight_ = false;  ///< a drag's one pass runs: newer drag requests follow it
    Timings timings_;
    std::atomic<int> scenes_built_{0};
};

}  // namespace dp
