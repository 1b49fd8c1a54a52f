#include "render_controller.h"

#include <QMetaObject>
#include <algorithm>
#include <cmath>

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
        {
            // While the UI has not taken the last frame, a newer one would only replace it:
            // its pictures are built once the UI is ready for them (the final one always).
            std::lock_guard<std::mutex> lock(c_->mutex_);
            if (c_->posted_ && !update.finished) return;
        }
        auto frame = std::make_shared<RenderFrame>();
        frame->update = update;
        frame->update.pull_images();
        frame->update.source = nullptr;
        bool post = false;
        {
            std::lock_guard<std::mutex> lock(c_->mutex_);
            frame->photo = c_->photo_;
            frame->preview = c_->runPreview_;
            frame->generation = c_->runGeneration_;
            c_->latest_ = std::move(frame);
            if (c_->runFrames_++ == 0 && c_->runPreview_)
                c_->timings_.firstQuick = ms_since(c_->runStart_);
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
    r.size = renderSize_;
    r.previewFraction = previewFraction_;
    r.previewScale = previewScale_;
    finished_ = false;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        pending_ = std::move(r);
    }
    session_->cancel();  // atomic store: the pass in flight stops at its next check
    cv_.notify_all();
}

void RenderController::stop() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        pending_.reset();
    }
    session_->cancel();
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
    // The run in flight was told to stop by request(); the new quick scene is built while it
    // winds down, and waited for only before the scenes it reads are touched.
    session_->cancel();
    auto t0 = std::chrono::steady_clock::now();
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
    PreviewPolicy policy;
    policy.photon_fraction = r.previewFraction;
    policy.scale = r.previewScale;
    int quick_w = 0, quick_h = 0;
    policy.size(full.width(), full.height(), quick_w, quick_h);
    const QSize quick(quick_w, quick_h);
    const RenderSettings quickSettings = policy.settings(p.render);

    if (change >= Change::Scene) {
        full_.reset();
        t0 = std::chrono::steady_clock::now();
        quick_ = builder_->build(p, quick.width(), quick.height());
        timings.buildQuick = ms_since(t0);
        ++scenesBuilt_;
        fullSize_ = full;
    } else if (change == Change::Material) {
        t0 = std::chrono::steady_clock::now();
        session_->wait();
        timings.cancel = ms_since(t0);
        quick_->update_materials(p);
        if (full_) full_->update_materials(p);
    }
    built_ = p;
    haveScenes_ = true;

    auto run = [&](std::shared_ptr<RenderScene> scene, const RenderSettings& settings, bool preview) {
        session_->cancel();
        t0 = std::chrono::steady_clock::now();
        session_->wait();
        if (preview) timings.cancel += ms_since(t0);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            runGeneration_ = r.generation;
            runPreview_ = preview;
            runFrames_ = 0;
            runStopped_ = false;
            photo_ = builder_->photo();
            if (preview) timings_ = timings;
            runStart_ = std::chrono::steady_clock::now();
        }
        session_->start(std::move(scene), settings);
    };

    run(quick_, quickSettings, true);
    if (r.interactive) return;
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
    run(full_, p.render, false);
}

void RenderController::deliver() {
    std::shared_ptr<RenderFrame> frame;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        frame = std::move(latest_);
        posted_ = false;
    }
    if (!frame || frame->generation != requested_) return;
    last_ = frame;
    if (!frame->preview) lastFull_ = frame;
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
