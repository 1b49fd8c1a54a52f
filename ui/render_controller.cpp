#include "render_controller.h"

#include <QMetaObject>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "display.h"
#include "render/preview.h"
#include "scene_builder.h"

namespace dp::ui {

namespace {

double ms_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

/// Copies each pass on the render thread and hands it to the UI thread with a queued call.
class RenderController::Sink : public RenderSink {
  public:
    explicit Sink(RenderController* c) : c_(c) {}

    void on_update(const RenderUpdate& update) override {
        if (update.cancelled) return;  // an edit replaced this run: its pictures are stale
        bool finished = update.finished;
        std::shared_ptr<const RenderFrame> base;
        std::shared_ptr<const Region> region;
        std::shared_ptr<const RenderScene> scene;
        bool preview;
        {
            std::lock_guard<std::mutex> lock(c_->mutex_);
            preview = c_->runPreview_;
            scene = c_->runScene_;
            if (!finished && c_->runEndless_ && !c_->runPreview_ && c_->scheduler_.clean_enough(update.stats)) {
                // Refined enough: this pass is the last; the session stops at its next check.
                c_->runReachedTarget_ = finished = true;
                c_->session_->cancel();
            }
            // While the UI has not taken the last frame, a newer one would only replace it:
            // its pictures are built once the UI is ready for them (the final one always).
            if (c_->posted_ && !finished) return;
            base = c_->base_;
            region = c_->runRegion_;
        }
        auto frame = std::make_shared<RenderFrame>();
        frame->update = update;
        frame->update.finished = finished;
        frame->update.pull_images();
        frame->update.source = nullptr;
        frame->refinedPasses = update.stats.passes;
        frame->scene = scene;
        // A final picture is shown as it is; so is one that has caught up with the refined one.
        const auto composeStart = std::chrono::steady_clock::now();
        if (base && region && !finished && (preview || update.stats.passes < base->refinedPasses))
            compose(*frame, *base, *region);
        const double composeMs = ms_since(composeStart);
        bool post = false;
        {
            std::lock_guard<std::mutex> lock(c_->mutex_);
            frame->photo = c_->photo_;
            frame->preview = c_->runPreview_;
            frame->generation = c_->runGeneration_;
            c_->latest_ = std::move(frame);
            if (c_->runFrames_++ == 0 && c_->runPreview_) {
                c_->timings_.firstQuick = ms_since(c_->runStart_);
                c_->timings_.compose = composeMs;
            }
            if (c_->runInteractive_) c_->timings_.dragFrame = ms_since(c_->dragStart_);
            post = !c_->posted_;
            c_->posted_ = true;
        }
        c_->cv_.notify_all();
        if (post) QMetaObject::invokeMethod(c_, "deliver", Qt::QueuedConnection);
    }

    void on_stopped(bool cancelled, const std::string& error) override {
        uint64_t gen;
        bool preview;
        {
            std::lock_guard<std::mutex> lock(c_->mutex_);
            gen = c_->runGeneration_;
            preview = c_->runPreview_;
            c_->runStopped_ = true;
            if (c_->runReachedTarget_) cancelled = false;  // stopped by the noise target: done
        }
        c_->cv_.notify_all();  // a worker waiting for a first pass that will not come
        if (preview && error.empty()) return;  // quick passes end by being replaced
        QMetaObject::invokeMethod(c_, "deliverStopped", Qt::QueuedConnection, Q_ARG(quint64, gen),
                                  Q_ARG(bool, !cancelled && error.empty()),
                                  Q_ARG(QString, QString::fromStdString(error)));
    }

  private:
    RenderController* c_;
};

RenderController::RenderController(std::shared_ptr<AssetLibrary> assets, QObject* parent)
    : QObject(parent),
      builder_(std::make_unique<SceneBuilder>(std::move(assets))),
      sink_(std::make_unique<Sink>(this)) {
    session_ = std::make_unique<RenderSession>(sink_.get());
    thread_ = std::thread([this] { worker(); });
}

RenderController::~RenderController() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        quit_ = true;
    }
    session_->cancel();
    cv_.notify_all();
    thread_.join();
    session_.reset();  // joins the render thread before the sink goes
}

void RenderController::request(const Project& project, bool interactive) {
    Request r;
    r.project = project;
    r.interactive = interactive;
    r.generation = ++requested_;
    if (!interactive) acceptFrom_ = r.generation;
    r.size = renderSize_;
    r.previewFraction = previewFraction_;
    r.previewScale = previewScale_;
    r.dragTargetMs = dragTargetMs_;
    r.endless = endless_;
    finished_ = false;
    bool follow = false;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        pending_ = std::move(r);
        // A drag's one-pass preview is left to finish and show: cancelling it for every mouse
        // move would show nothing until the hand stops.
        follow = interactive && runInteractive_;
    }
    if (!follow) session_->cancel();  // atomic store: the pass in flight stops at its next check
    cv_.notify_all();
}

void RenderController::stop() {
    // Frames of what ran are no longer the latest request's: none of them is shown.
    acceptFrom_ = ++requested_;
    finished_ = false;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        pending_.reset();
    }
    session_->cancel();
}

void RenderController::forgetPicture() {
    last_.reset();
    lastFull_.reset();
    std::lock_guard<std::mutex> lock(mutex_);
    base_.reset();
}

bool RenderController::idle() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return !busy_ && !pending_ && !session_->running();
}

bool RenderController::superseded() {
    std::lock_guard<std::mutex> lock(mutex_);
    return pending_.has_value() || quit_;
}

void RenderController::worker() {
    for (;;) {
        Request r;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            cv_.wait(lock, [&] { return quit_ || pending_.has_value(); });
            if (quit_) return;
            r = std::move(*pending_);
            pending_.reset();
            busy_ = true;
        }
        try {
            handle(r);
        } catch (const std::exception& e) {
            haveScenes_ = false;
            quick_.reset();
            full_.reset();
            QMetaObject::invokeMethod(this, "deliverStopped", Qt::QueuedConnection,
                                      Q_ARG(quint64, r.generation), Q_ARG(bool, false),
                                      Q_ARG(QString, QString::fromUtf8(e.what())));
        }
        std::lock_guard<std::mutex> lock(mutex_);
        busy_ = false;
    }
}

void RenderController::handle(const Request& r) {
    // The run in flight was told to stop by request(), unless it is a drag's one pass, which
    // finishes and shows first. The new quick scene is built while it winds down, and waited
    // for only before the scenes it reads are touched.
    bool followDrag = false;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        followDrag = r.interactive && runInteractive_;
    }
    if (!followDrag) session_->cancel();
    auto t0 = std::chrono::steady_clock::now();
    if (followDrag) {
        session_->wait();
        t0 = std::chrono::steady_clock::now();
        std::lock_guard<std::mutex> lock(mutex_);
        if (quit_ || (pending_ && !pending_->interactive)) return;  // the drag ended: refine at once
    }
    const auto requestStart = t0;
    Timings timings;
    const Project& p = r.project;
    Change change = haveScenes_ ? classify(built_, p) : Change::Assets;
    if (change >= Change::Scene) {
        builder_->load(p);
        if (builder_->warnings() != warned_) {
            warned_ = builder_->warnings();
            QStringList list;
            for (const std::string& w : warned_) list << QString::fromStdString(w);
            QMetaObject::invokeMethod(this, [this, list] { Q_EMIT assetWarnings(list); }, Qt::QueuedConnection);
        }
    }

    const Image& photo = *builder_->photo();
    QSize full = r.size.isValid() ? r.size : QSize(photo.width(), photo.height());
    if (full != fullSize_) change = std::max(change, Change::Scene);
    scheduler_.set_preview(r.previewFraction, r.previewScale);
    scheduler_.set_drag_target(r.dragTargetMs);
    const RenderScheduler::Pass quickPass = scheduler_.quick_pass(p.render, full.width(), full.height(), r.interactive);
    const QSize quick(quickPass.width, quickPass.height);
    const RenderSettings& quickSettings = quickPass.settings;
    // A full-size scene of another state would be refined wrongly; a quick one of another size
    // is simply rebuilt.
    if (change >= Change::Scene) full_.reset();

    if (change >= Change::Scene || quick != quickSize_) {
        t0 = std::chrono::steady_clock::now();
        quick_ = builder_->build(p, quick.width(), quick.height());
        timings.buildQuick = ms_since(t0);
        ++scenesBuilt_;
        fullSize_ = full;
        quickSize_ = quick;
    } else if (change == Change::Material) {
        // New versions sharing the BVHs: the run in flight keeps reading its own.
        quick_ = quick_->with_materials(p);
        if (full_) full_ = full_->with_materials(p);
    }
    built_ = p;
    haveScenes_ = true;
    t0 = std::chrono::steady_clock::now();
    std::shared_ptr<const Region> region = regionFor(p, *quick_);
    timings.region = ms_since(t0);

    auto run = [&](std::shared_ptr<const RenderScene> scene, const RenderSettings& settings, bool preview) {
        session_->cancel();
        t0 = std::chrono::steady_clock::now();
        session_->wait();
        if (preview) timings.cancel += ms_since(t0);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            runGeneration_ = r.generation;
            runPreview_ = preview;
            runInteractive_ = preview && r.interactive;
            runEndless_ = !preview && r.endless;
            runReachedTarget_ = false;
            runRegion_ = region;
            runScene_ = scene;
            runFrames_ = 0;
            runStopped_ = false;
            photo_ = builder_->photo();
            if (preview) {
                const double lastDrag = timings_.dragFrame;
                timings_ = timings;
                timings_.dragFrame = lastDrag;
                timings_.dragLevel = scheduler_.drag_level();
            }
            runStart_ = std::chrono::steady_clock::now();
            dragStart_ = requestStart;
        }
        session_->start(std::move(scene), settings);
    };

    if (r.interactive) {
        // The last drag frame's time picks this one's size: a size step per frame keeps the
        // frames within the target as the machine's load and the edit's cost change.
        double last;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            last = runInteractive_ ? timings_.dragFrame : 0;
        }
        scheduler_.drag_frame_took(last);  // the next frame's size
        run(quick_, quickSettings, true);
        return;
    }
    run(quick_, quickSettings, true);
    {
        // The quick pass shows the edit at once; the full-size scene is built meanwhile.
        std::unique_lock<std::mutex> lock(mutex_);
        cv_.wait(lock,
                 [&] { return runFrames_ > 0 || runStopped_ || pending_.has_value() || quit_; });
        if (runFrames_ == 0) return;  // superseded, or the quick run failed (already reported)
    }
    if (superseded()) return;
    if (!full_) {
        t0 = std::chrono::steady_clock::now();
        full_ = builder_->build(p, full.width(), full.height());
        ++scenesBuilt_;
        std::lock_guard<std::mutex> lock(mutex_);
        timings_.buildFull = ms_since(t0);
    }
    if (superseded()) return;
    rememberBase(r.generation, p, *full_);
    // Endless: no budget; the sink stops the run once it is clean (RenderScheduler::clean_enough).
    const RenderSettings fullSettings = RenderScheduler::refinement(p.render, r.endless);
    run(full_, fullSettings, false);
}

void RenderController::rememberBase(uint64_t generation, const Project& p, const RenderScene& scene) {
    BaseState b;
    b.project = p;
    for (size_t i = 0; i < p.objects.size(); ++i) {
        EditedBounds e;
        if (scene.object_bounds(int(i), e.center, e.radius)) b.bounds.push_back(e);
        else b.bounds.push_back(std::nullopt);
    }
    uint64_t keepFrom;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        keepFrom = base_ ? base_->generation : 0;
    }
    bases_[generation] = std::move(b);
    // The refined picture's state, and the latest few that may replace it.
    for (auto it = bases_.begin(); it != bases_.end();) {
        const bool recent = std::distance(it, bases_.end()) <= 8;
        it = it->first == keepFrom || (it->first > keepFrom && recent) ? std::next(it) : bases_.erase(it);
    }
}

std::shared_ptr<const RenderController::Region> RenderController::regionFor(const Project& p,
                                                                              const RenderScene& scene) {
    uint64_t baseGeneration;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!base_) return nullptr;
        baseGeneration = base_->generation;
    }
    auto it = bases_.find(baseGeneration);
    if (it == bases_.end()) return nullptr;
    const BaseState& base = it->second;
    std::vector<int> edited;
    if (!edited_objects(base.project, p, edited)) return nullptr;
    std::vector<EditedBounds> spheres;
    for (int i : edited) {
        if (size_t(i) < base.bounds.size() && base.bounds[size_t(i)]) spheres.push_back(*base.bounds[size_t(i)]);
        EditedBounds now;
        if (size_t(i) < p.objects.size() && scene.object_bounds(i, now.center, now.radius)) spheres.push_back(now);
    }
    auto region = std::make_shared<Region>();
    // About 25,000 rays whatever the preview's size: the region's edge is widened anyway.
    const int W = scene.photo().width(), H = scene.photo().height();
    const int step = std::max(1, int(std::ceil(std::sqrt(double(W) * H / 25000.0))));
    region->width = (W + step - 1) / step;
    region->height = (H + step - 1) / step;
    region->baseGeneration = baseGeneration;
    region->mask = change_region(scene, spheres, kChangeReach, step);
    // A pixel of the mask stands for several of the full picture: the edge of the region is
    // widened by one, so soft shadows are not cut at it.
    dilate_mask(region->mask, region->width, region->height, 1);
    return region;
}

void RenderController::compose(RenderFrame& f, const RenderFrame& base, const Region& region) {
    const Image& bi = base.image();
    const Image& bd = base.dL();
    const int W = bi.width(), H = bi.height();
    const Image& pi = f.update.image;
    const Image& pd = f.update.dL;
    if (W == 0 || bd.width() != W || pi.empty() || region.mask.empty()) return;
    const int w = pi.width(), h = pi.height();
    // What is shown, not what is exported: at most the display's width (a 12 MP photo is
    // laid over at a fraction of its pixels), sampling the refined picture's pixels.
    const int step = W > kDisplayMaxWidth ? (W + kDisplayMaxWidth - 1) / kDisplayMaxWidth : 1;
    const int OW = W / step, OH = H / step;
    auto image = std::make_shared<Image>(OW, OH);
    auto dL = std::make_shared<Image>(OW, OH);
    auto fromEdit = std::make_shared<std::vector<uint8_t>>(size_t(OW) * OH, 0);
    // The mask is looked up at its own scale: a full-size pass uses its preview's region.
    const float sx = float(w) / float(W), sy = float(h) / float(H);
    const float mx = float(region.width) / float(W), my = float(region.height) / float(H);
    tbb::parallel_for(0, OH, [&](int oy) {
        const int y = oy * step + step / 2;
        const int ry = std::min(region.height - 1, int((float(y) + 0.5f) * my));
        for (int ox = 0; ox < OW; ++ox) {
            const int x = ox * step + step / 2;
            const size_t i = size_t(y) * W + x, o = size_t(oy) * OW + ox;
            const int rx = std::min(region.width - 1, int((float(x) + 0.5f) * mx));
            (*fromEdit)[o] = region.mask[size_t(ry) * region.width + rx];
            if (!(*fromEdit)[o]) {
                (*image)[o] = bi[i];
                (*dL)[o] = bd[i];
            } else if (w == W && h == H) {
                (*image)[o] = pi[i];
                (*dL)[o] = pd[i];
            } else {
                const float px = (float(x) + 0.5f) * sx - 0.5f, py = (float(y) + 0.5f) * sy - 0.5f;
                (*image)[o] = pi.bilinear(px, py);
                (*dL)[o] = pd.bilinear(px, py);
            }
        }
    });
    f.shownImage = std::move(image);
    f.shownDL = std::move(dL);
    f.shownFromEdit = std::move(fromEdit);
    f.baseGeneration = base.generation;
    f.shownStep = step;
    f.refinedPasses = base.refinedPasses;
}

void RenderController::deliver() {
    std::shared_ptr<RenderFrame> frame;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        frame = std::move(latest_);
        posted_ = false;
    }
    if (!frame) return;
    // A drag's preview of an earlier move is still the newest picture there is: shown, as long
    // as no edit since then asked for more than previews. Anything else shows only the latest.
    const bool current = frame->generation == requested_ ||
                         (frame->preview && frame->generation >= acceptFrom_ &&
                          (!last_ || frame->generation >= last_->generation));
    if (!current) return;
    last_ = frame;
    if (!frame->preview) lastFull_ = frame;
    if (!frame->preview && !frame->composited()) {
        // A refined picture of its own: later edits are laid over it.
        std::lock_guard<std::mutex> lock(mutex_);
        base_ = frame;
    }
    Q_EMIT frameReady(frame);
}

void RenderController::deliverStopped(quint64 generation, bool finished, const QString& error) {
    if (generation != requested_) return;
    if (!error.isEmpty()) {
        Q_EMIT failed(error);
        return;
    }
    if (finished) {
        finished_ = true;
        Q_EMIT refinementFinished();
    }
}

}  // namespace dp::ui
