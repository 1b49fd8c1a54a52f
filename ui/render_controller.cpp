#include "render_controller.h"

#include <QMetaObject>

#include "display.h"

namespace dp::ui {

/// Hands the session's frames to the UI thread with a queued call, one at a time.
class RenderController::Sink : public ViewSink {
public:
    explicit Sink(RenderController* c) : c_(c) {}

    bool wants_frame() override {
        std::lock_guard<std::mutex> lock(c_->mutex_);
        return !c_->posted_;
    }

    void on_frame(std::shared_ptr<RenderFrame> frame) override {
        bool post;
        {
            std::lock_guard<std::mutex> lock(c_->mutex_);
            c_->latest_ = std::move(frame);
            post = !c_->posted_;
            c_->posted_ = true;
        }
        if (post) QMetaObject::invokeMethod(c_, "deliver", Qt::QueuedConnection);
    }

    void on_stopped(uint64_t generation, bool finished, const std::string& error) override {
        QMetaObject::invokeMethod(c_, "deliverStopped", Qt::QueuedConnection, Q_ARG(quint64, generation),
                                  Q_ARG(bool, finished), Q_ARG(QString, QString::fromStdString(error)));
    }

    void on_warnings(const std::vector<std::string>& warnings) override {
        QStringList list;
        for (const std::string& w : warnings) list << QString::fromStdString(w);
        QMetaObject::invokeMethod(c_, [c = c_, list] { Q_EMIT c->assetWarnings(list); }, Qt::QueuedConnection);
    }

private:
    RenderController* c_;
};

RenderController::RenderController(std::shared_ptr<AssetLibrary> assets, QObject* parent)
    : QObject(parent), sink_(std::make_unique<Sink>(this)) {
    session_ = std::make_unique<InteractiveSession>(std::make_unique<SceneBuilder>(std::move(assets)), sink_.get());
}

// The session's thread is joined before the sink it calls goes.
RenderController::~RenderController() { session_.reset(); }

void RenderController::request(const Project& project, bool interactive) {
    ViewRequest r;
    r.project = project;
    r.interactive = interactive;
    r.generation = ++requested_;
    if (!interactive) acceptFrom_ = r.generation;
    if (renderSize_.isValid()) {
        r.width = renderSize_.width();
        r.height = renderSize_.height();
    }
    r.preview_fraction = previewFraction_;
    r.preview_scale = previewScale_;
    r.drag_target_ms = dragTargetMs_;
    r.endless = endless_;
    r.display_max_width = kDisplayMaxWidth;
    finished_ = false;
    session_->reset(std::move(r));
}

void RenderController::stop() {
    // Frames of what ran are no longer the latest request's: none of them is shown.
    acceptFrom_ = ++requested_;
    finished_ = false;
    session_->stop();
}

void RenderController::forgetPicture() {
    last_.reset();
    lastFull_.reset();
    session_->forget_picture();
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
