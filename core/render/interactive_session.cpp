#include "render/interactive_session.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>

#include "base/threads.h"
#include "render/progressive.h"
#include "scene/project_diff.h"

namespace dp {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

}  // namespace

/// One run of the renderer on one scene: the quick pass of a request, a drag frame, or the
/// full-size refinement.
struct InteractiveSession::Run {
    ViewRequest request;
    Phase phase = Phase::Quick;
    std::shared_ptr<const RenderScene> scene;
    RenderSettings settings;
    std::unique_ptr<ProgressiveRenderer> renderer;
    std::unique_ptr<tbb::task_arena> arena;
    std::shared_ptr<const EditRegion> region;
    std::optional<PixelWindow> window;  ///< a drag frame renders its edit's region only
    std::shared_ptr<const Image> photo;
    Clock::time_point begun, started;  ///< the thread took the request; the first pass began
    bool may_be_base = true;  ///< false once forget_picture() was called during it
};

InteractiveSession::InteractiveSession(std::unique_ptr<SceneBuilder> scenes, ViewSink* sink)
    : scenes_(std::move(scenes)), sink_(sink) {
    thread_ = std::thread([this] { thread_main(); });
}

InteractiveSession::~InteractiveSession() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        quit_ = true;
        cancel_.store(true);
    }
    cv_.notify_all();
    thread_.join();
}

void InteractiveSession::reset(ViewRequest request) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        // A drag's one pass is left to finish and show: cancelling it for every mouse move
        // would show nothing until the hand stops.
        if (!(request.interactive && drag_in_flight_)) cancel_.store(true);
        pending_ = std::move(request);
        pending_since_ = Clock::now();
    }
    cv_.notify_all();
}

void InteractiveSession::stop() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        pending_.reset();
        stop_ = true;
        cancel_.store(true);
    }
    cv_.notify_all();
}

void InteractiveSession::forget_picture() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        forget_ = true;
    }
    cv_.notify_all();
}

void InteractiveSession::finish_clean(uint64_t generation) {
    std::lock_guard<std::mutex> lock(mutex_);
    clean_generation_ = generation;
}

bool InteractiveSession::idle() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return !busy_ && !pending_;
}

InteractiveSession::Timings InteractiveSession::timings() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return timings_;
}

bool InteractiveSession::replaced() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return pending_.has_value() || stop_ || quit_;
}

void InteractiveSession::thread_main() {
    for (;;) {
        std::optional<ViewRequest> next;
        Clock::time_point asked;
        bool drop = false, forget = false;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            busy_ = run_ != nullptr;
            cv_.wait(lock, [&] { return quit_ || stop_ || forget_ || pending_ || run_; });
            if (quit_) return;
            std::swap(drop, stop_);
            std::swap(forget, forget_);
            if (pending_) {
                next = std::move(pending_);
                pending_.reset();
                asked = pending_since_;
                drop = true;
            }
            if (drop) {
                cancel_.store(false);
                drag_in_flight_ = false;
            }
            busy_ = next || (run_ && !drop);
        }
        if (drop) run_.reset();
        if (forget) {
            base_.reset();
            states_.clear();
            if (run_) run_->may_be_base = false;
        }
        uint64_t generation = next ? next->generation : run_ ? run_->request.generation : 0;
        try {
            if (next) start(*next, asked);
            else if (run_) step();
        } catch (const std::exception& e) {
            // What was built may be half made: the next request starts from the files.
            have_scenes_ = false;
            quick_.reset();
            full_.reset();
            run_.reset();
            sink_->on_stopped(generation, false, e.what());
        }
    }
}

void InteractiveSession::start(const ViewRequest& r, Clock::time_point asked) {
    const auto t_begin = Clock::now();
    auto t0 = t_begin;
    Timings timings;
    timings.cancel = ms_since(asked);
    const Project& p = r.project;
    Change change = have_scenes_ ? classify(built_, p) : Change::Assets;
    if (change >= Change::Scene) {
        scenes_->load(p);
        if (scenes_->warnings() != warned_) {
            warned_ = scenes_->warnings();
            sink_->on_warnings(warned_);
        }
    }
    const Image& photo = *scenes_->photo();
    const int W = r.width > 0 ? r.width : photo.width(), H = r.height > 0 ? r.height : photo.height();
    if (W != full_w_ || H != full_h_) change = std::max(change, Change::Scene);
    scheduler_.set_preview(r.preview_fraction, r.preview_scale);
    scheduler_.set_drag_target(r.drag_target_ms);
    // A drag frame's size steps from the last drag frame's time (none before the first).
    if (r.interactive) scheduler_.drag_frame_took(last_drag_ms_);
    else last_drag_ms_ = 0;
    const RenderScheduler::Pass quick = scheduler_.quick_pass(p.render, W, H, r.interactive);
    // A full-size scene of another state would be refined wrongly; a quick one of another size
    // is simply rebuilt.
    if (change >= Change::Scene) full_.reset();
    if (change >= Change::Scene || quick.width != quick_w_ || quick.height != quick_h_) {
        t0 = Clock::now();
        quick_ = scenes_->build(p, quick.width, quick.height);
        timings.buildQuick = ms_since(t0);
        ++scenes_built_;
        full_w_ = W;
        full_h_ = H;
        quick_w_ = quick.width;
        quick_h_ = quick.height;
    } else if (change == Change::Material) {
        // New versions sharing the BVHs: frames and the denoiser keep reading their own.
        quick_ = quick_->with_materials(p);
        if (full_) full_ = full_->with_materials(p);
    }
    built_ = p;
    have_scenes_ = true;

    auto run = std::make_unique<Run>();
    run->request = r;
    run->phase = r.interactive ? Phase::Drag : Phase::Quick;
    run->scene = quick_;
    run->settings = quick.settings;
    run->photo = scenes_->photo();
    t0 = Clock::now();
    if (base_) run->region = states_.region(base_->generation, p, *quick_);
    timings.region = ms_since(t0);
    // Only the region is shown of a quick pass laid over the refined picture: only it is rendered.
    if (run->region) frame_the_region(*run, r.interactive && change == Change::Material);
    {
        std::lock_guard<std::mutex> lock(mutex_);
        timings.dragFrame = timings_.dragFrame;
        timings.dragLevel = scheduler_.drag_level();
        timings_ = timings;
        drag_in_flight_ = r.interactive;
    }
    run->begun = t_begin;
    run_ = std::move(run);
    step();  // the quick pass at once: a newer request cancels it, nothing else delays it
}

void InteractiveSession::frame_the_region(Run& run, bool material) {
    const EditRegion& region = *run.region;
    int cx0 = region.width, cy0 = region.height, cx1 = -1, cy1 = -1;
    for (int y = 0; y < region.height; ++y)
        for (int x = 0; x < region.width; ++x)
            if (region.mask[size_t(y) * region.width + x]) {
                cx0 = std::min(cx0, x);
                cy0 = std::min(cy0, y);
                cx1 = std::max(cx1, x);
                cy1 = std::max(cy1, y);
            }
    if (cx1 < 0) return;
    // The region's cells in a w x h render's pixels, one pixel wider for the upsampling.
    auto window_at = [&](int w, int h) {
        PixelWindow win;
        win.x0 = std::max(0, int(std::floor(double(cx0) * w / region.width)) - 1);
        win.y0 = std::max(0, int(std::floor(double(cy0) * h / region.height)) - 1);
        win.x1 = std::min(w, int(std::ceil(double(cx1 + 1) * w / region.width)) + 1);
        win.y1 = std::min(h, int(std::ceil(double(cy1 + 1) * h / region.height)) + 1);
        return win;
    };
    // A material stroke changes no geometry: the full-size scene (a new version with the
    // stroke's material) shows the object sharp where its region is small enough.
    if (material && full_) {
        const PixelWindow full = window_at(full_w_, full_h_);
        if (double(full.area()) <= 2.0 * drag_preview_pixels(scheduler_.drag_level())) {
            run.scene = full_;
            run.window = full;
            return;
        }
    }
    run.window = window_at(quick_w_, quick_h_);
}

void InteractiveSession::step() {
    Run& r = *run_;
    if (!r.renderer) {
        r.arena = std::make_unique<tbb::task_arena>(worker_threads(r.settings.threads));
        r.renderer = std::make_unique<ProgressiveRenderer>(r.scene, r.settings);
        if (r.window) r.renderer->set_window(*r.window);
        r.started = Clock::now();
    }
    bool rendered = false;
    r.arena->execute([&] { rendered = r.renderer->render_pass(&cancel_); });
    if (!rendered) return;  // replaced or stopped: the loop takes what comes next
    const RenderStats stats = r.renderer->stats();
    const bool full = r.phase == Phase::Full;
    const double elapsed_s = std::chrono::duration<double>(Clock::now() - r.started).count();
    bool finished = r.phase == Phase::Drag;
    if (full) {
        finished = r.settings.time_budget_s > 0 ? elapsed_s >= r.settings.time_budget_s : stats.passes >= r.settings.passes;
        // Endless refinement has no budget: it stops once clean, by the renderer's estimate or
        // by the viewer's of what it shows.
        bool shown_clean;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            shown_clean = clean_generation_ == r.request.generation;
        }
        finished = finished || (r.request.endless && (shown_clean || scheduler_.clean_enough(stats)));
    }
    // While the viewer has not taken the last frame a newer one would only replace it; a
    // quick pass and a run's last frame are always sent.
    if (!full || finished || sink_->wants_frame()) {
        auto frame = std::make_shared<RenderFrame>();
        RenderUpdate& u = frame->update;
        u.stats = stats;
        u.target_passes = r.settings.time_budget_s > 0 ? 0 : r.settings.passes;
        u.time_budget_s = r.settings.time_budget_s;
        u.finished = finished;
        u.source = r.renderer.get();
        u.pull_images(r.phase != Phase::Drag);  // drag frames are never denoised
        u.source = nullptr;
        frame->photo = r.photo;
        frame->preview = !full;
        frame->drag = r.phase == Phase::Drag;
        frame->generation = r.request.generation;
        frame->refined_passes = stats.passes;
        frame->scene = r.scene;
        // A final picture is shown as it is; so is one that has caught up with the refined one.
        const auto t0 = Clock::now();
        if (base_ && r.region && !(full && finished) && (!full || stats.passes < base_->refined_passes))
            compose_over(*frame, *base_, *r.region, r.request.display_max_width);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (r.phase == Phase::Quick) {
                timings_.firstQuick = ms_since(r.started);
                timings_.compose = ms_since(t0);
            }
            if (r.phase == Phase::Drag) timings_.dragFrame = last_drag_ms_ = ms_since(r.begun);
        }
        if (full && !frame->composited() && r.may_be_base) base_ = frame;
        sink_->on_frame(std::move(frame));
    }
    if (r.phase == Phase::Quick) return start_full();
    if (!finished) return;
    if (full) sink_->on_stopped(r.request.generation, true, {});
    run_.reset();
    std::lock_guard<std::mutex> lock(mutex_);
    drag_in_flight_ = false;
}

void InteractiveSession::start_full() {
    // The quick pass shows the edit; the full-size scene is built unless a newer edit came.
    if (replaced()) return;
    Run& quick = *run_;
    const Project& p = quick.request.project;
    if (!full_) {
        const auto t0 = Clock::now();
        full_ = scenes_->build(p, full_w_, full_h_);
        ++scenes_built_;
        std::lock_guard<std::mutex> lock(mutex_);
        timings_.buildFull = ms_since(t0);
    }
    if (replaced()) return;
    states_.remember(quick.request.generation, p, *full_, base_ ? base_->generation : 0);
    auto run = std::make_unique<Run>();
    run->request = quick.request;
    run->phase = Phase::Full;
    run->scene = full_;
    // Endless: no budget; step() stops the run once it is clean (RenderScheduler::clean_enough).
    run->settings = RenderScheduler::refinement(p.render, quick.request.endless);
    run->region = quick.region;
    run->photo = quick.photo;
    run->begun = quick.begun;
    run->may_be_base = quick.may_be_base;
    run_ = std::move(run);
}

}  // namespace dp
