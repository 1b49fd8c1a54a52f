#pragma once
#include <QObject>
#include <QSize>
#include <QStringList>
#include <atomic>
#include <memory>
#include <mutex>

#include "assets/asset_library.h"
#include "render/interactive_session.h"
#include "render/view_frame.h"

namespace dp::ui {

using dp::RenderFrame;

/// The studio's adapter over the core's InteractiveSession: an edit becomes a request (reset),
/// and the session's frames come to the UI thread through a queued call, at most one pending at
/// a time (older ones are dropped). The UI thread never waits for the renderer: request() only
/// records the latest project and returns. The render policy (quick pass, drag sizes, when to
/// stop) is the session's RenderScheduler; this class only adds what Qt needs.
class RenderController : public QObject {
    Q_OBJECT
public:
    /// `assets`: the library scenes are loaded through (shared with the document's panels).
    explicit RenderController(std::shared_ptr<AssetLibrary> assets = std::make_shared<AssetLibrary>(),
                              QObject* parent = nullptr);
    ~RenderController() override;

    /// Size of the full render (default: the photo's).
    void setRenderSize(QSize size) { renderSize_ = size; }
    QSize renderSize() const { return renderSize_; }
    /// Photons of the quick pass as a fraction of the project's (default 1/8).
    void setPreviewFraction(double f) { previewFraction_ = f; }
    /// Size of the quick pass relative to the full render (default 1/2, and at most 100k pixels).
    void setPreviewScale(double s) { previewScale_ = s; }
    /// Refinement without a pass budget, until the noise target is met (true), or to the
    /// project's passes or time budget (false, as `diffphoton render`).
    void setEndless(bool endless) { endless_ = endless; }
    /// Relative error (RenderStats::estimated_rel_error) at which endless refinement stops;
    /// <= 0: invisible at the display exposure (invisible_relative_error).
    void setNoiseTarget(double relError) { session_->scheduler().set_noise_target(relError); }
    double noiseTarget() const { return session_->scheduler().noise_target(); }
    /// The display exposure the invisible noise target is judged at.
    void setDisplayExposure(double stops) { session_->scheduler().set_display_exposure(stops); }
    /// The estimated error an endless refinement of `stats` stops at (the status line says it).
    double stopError(const RenderStats& stats) const { return session_->scheduler().stop_error(stats); }
    /// Whether the picture the viewer shows, estimated `shownError` after the frame with
    /// `stats`, is clean enough for an endless refinement to stop (RenderScheduler::shown_clean).
    bool shownClean(double shownError, const RenderStats& stats) const {
        return session_->scheduler().shown_clean(shownError, stats);
    }
    /// Ends the latest request's endless refinement after its next pass, as clean.
    void finishClean() { session_->finish_clean(requested_); }
    /// Whether the viewer shows refined frames denoised (it asks DenoiseWorker for them).
    void setDenoise(bool on) { denoise_ = on; }
    bool denoise() const { return denoise_; }
    /// Time a drag frame should take (milliseconds): the preview size follows it.
    void setDragFrameTarget(double ms) { dragTargetMs_ = ms; }

    /// Renders `project` (cancelling what runs). `interactive`: quick passes only.
    void request(const Project& project, bool interactive = false);
    /// Stops rendering (before closing, or while the project's files are missing); returns at
    /// once, and no frame of what ran is delivered after it.
    void stop();
    bool idle() const { return session_->idle(); }
    /// Drops the refined picture later edits are laid over: another project was opened, and
    /// nothing of the old picture may show through the new one.
    void forgetPicture();

    /// The latest full-size frame (what export writes).
    std::shared_ptr<const RenderFrame> lastFullFrame() const { return lastFull_; }
    uint64_t generation() const { return requested_; }
    /// Whether the latest request's full-size refinement reached its budget or noise target.
    bool finished() const { return finished_; }
    using Timings = InteractiveSession::Timings;
    /// Where the time of the latest request went, for the benchmark.
    Timings timings() const { return session_->timings(); }
    /// Scenes (BVHs) built so far: material-only edits must not add to it.
    int scenesBuilt() const { return session_->scenes_built(); }

Q_SIGNALS:
    void frameReady(std::shared_ptr<const dp::RenderFrame> frame);
    /// The refinement of the latest request reached its pass or time budget, or is clean.
    void refinementFinished();
    /// Loading or building failed (message for the user).
    void failed(const QString& message);
    /// What loading the project's files found (NaN/Inf replaced, an LDR probe, ...); sent when
    /// the list changes, on the UI thread.
    void assetWarnings(const QStringList& warnings);

private:
    class Sink;
    Q_INVOKABLE void deliver();
    Q_INVOKABLE void deliverStopped(quint64 generation, bool finished, const QString& error);

    QSize renderSize_;
    double previewFraction_ = 1.0 / 8.0;
    double previewScale_ = 0.5;
    bool endless_ = false;
    bool denoise_ = false;
    double dragTargetMs_ = 45;

    std::unique_ptr<Sink> sink_;
    std::unique_ptr<InteractiveSession> session_;
    // The frame waiting for the UI thread (render thread writes, UI thread takes).
    std::mutex mutex_;
    std::shared_ptr<RenderFrame> latest_;
    bool posted_ = false;
    // UI thread.
    uint64_t requested_ = 0;
    uint64_t acceptFrom_ = 0;  ///< previews of this request or later are shown
    bool finished_ = false;
    std::shared_ptr<const RenderFrame> last_, lastFull_;
};

}  // namespace dp::ui
