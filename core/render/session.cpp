#include "render/session.h"

#include <tbb/task_arena.h>

#include <chrono>

#include "base/threads.h"

namespace dp {

namespace {

std::unique_ptr<PassRenderer> make_differential(std::shared_ptr<const RenderScene> scene, const RenderSettings& rs) {
    return std::make_unique<ProgressiveRenderer>(std::move(scene), rs);
}

}  // namespace

void RenderUpdate::pull_images(bool with_variance) {
    if (!source) return;
    image = source->image();
    dL = source->dL_layer();
    alpha = source->alpha_layer();
    if (with_variance) variance = source->variance_layer();
}

RenderSession::RenderSession(RenderSink* sink) : sink_(sink), factory_(make_differential) {}

void RenderSession::set_renderer_factory(RendererFactory factory) {
    std::lock_guard<std::mutex> lock(mutex_);
    factory_ = factory ? std::move(factory) : RendererFactory(make_differential);
}

RenderSession::~RenderSession() {
    cancel();
    wait();
}

void RenderSession::cancel() { cancel_.store(true); }

void RenderSession::wait() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (thread_.joinable()) thread_.join();
}

void RenderSession::start(std::shared_ptr<const RenderScene> scene, const RenderSettings& settings) {
    std::lock_guard<std::mutex> lock(mutex_);
    cancel_.store(true);
    if (thread_.joinable()) thread_.join();
    cancel_.store(false);
    running_.store(true);
    thread_ = std::thread([this, scene = std::move(scene), settings, factory = factory_]() mutable {
        run(std::move(scene), settings, factory);
    });
}

void RenderSession::run(std::shared_ptr<const RenderScene> scene, const RenderSettings& rs,
                        const RendererFactory& factory) {
    bool cancelled = false;
    std::string error;
    {
        std::lock_guard<std::mutex> lock(failure_mutex_);
        failure_ = nullptr;
    }
    try {
        const int threads = worker_threads(rs.threads);
        tbb::task_arena arena(threads);
        arena.execute([&] {
            std::unique_ptr<PassRenderer> owned = factory(scene, rs);
            PassRenderer& renderer = *owned;
            auto t0 = std::chrono::steady_clock::now();
            auto update = [&](bool finished) {
                RenderUpdate u;
                u.stats = renderer.stats();
                u.target_passes = rs.time_budget_s > 0 ? 0 : rs.passes;
                u.time_budget_s = rs.time_budget_s;
                u.finished = finished;
                u.cancelled = cancelled;
                u.source = &renderer;
                if (sink_) sink_->on_update(u);
            };
            for (;;) {
                if (cancel_.load() || !renderer.render_pass(&cancel_)) {
                    cancelled = true;
                    // One last update, so a sink can still pull what the finished passes made.
                    if (renderer.passes() > 0) update(true);
                    break;
                }
                const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                const bool finished = rs.time_budget_s > 0 ? elapsed >= rs.time_budget_s : renderer.passes() >= rs.passes;
                update(finished);
                if (finished) break;
            }
        });
    } catch (const std::exception& e) {
        error = e.what();
        std::lock_guard<std::mutex> lock(failure_mutex_);
        failure_ = std::current_exception();
    }
    running_.store(false);
    if (sink_) sink_->on_stopped(cancelled, error);
}

}  // namespace dp
