#pragma once
#include <QObject>
#include <QSize>
#include <QStringList>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "assets/asset_library.h"
#include "project_edit.h"
#include "render/change_region.h"
#include "render/scheduler.h"
#include "render/session.h"

namespace dp::ui {

class SceneBuilder;

/// One progressive image as the viewport shows it.
struct RenderFrame {
    RenderUpdate update;                 ///< the render of this request's state, as export writes it
    std::shared_ptr<const Image> photo;  ///< full-resolution photo (the "photo" view)
    bool preview = false;                ///< a coarse pass at reduced size (edit in progress)
    uint64_t generation = 0;             ///< which request it answers
    /// What the viewport shows, where it differs from `update`: an edit's preview or early
    /// refinement passes laid over the last refined picture outside the region the edit can
    /// change (change_region), at the full render size (at most the display's width,
    /// kDisplayMaxWidth). Null: update's own images.
    std::shared_ptr<const Image> shownImage, shownDL;
    /// Passes behind the picture outside the edited region (update's own when not composited).
    int refinedPasses = 0;
    /// Where composited: which shown pixels are the edit's (1) and which the refined picture's
    /// (0), the refined frame's generation, and the step from shown to rendered pixels (a
    /// shown pixel is rendered pixel (x step + step / 2, y step + step / 2)).
    std::shared_ptr<const std::vector<uint8_t>> shownFromEdit;
    uint64_t baseGeneration = 0;
    int shownStep = 1;
    /// The scene it was rendered from (the denoiser's guides come from it).
    std::shared_ptr<const RenderScene> scene;

    bool composited() const { return shownImage != nullptr; }
    const Image& image() const { return shownImage ? *shownImage : update.image; }
    const Image& dL() const { return shownDL ? *shownDL : update.dL; }
};

/// Runs the renderer for the studio. Requests are handled on a worker thread that loads files,
/// builds scenes and drives the RenderSession; passes come back to the UI thread through a
/// queued call, at most one pending at a time (older ones are dropped). The UI thread never
/// waits for the renderer: request() only records the latest project and returns.
///
/// Each request first renders one quick pass at reduced size with fewer photons (so the picture
/// answers within a fraction of a second), then refines at full size, without a pass budget
/// until the noise is invisible (setEndless). While `interactive` (a drag or a slider stroke)
/// each request renders one pass at a size chosen to keep the frame rate (drag_preview_pixels),
/// and a new request never cancels that pass: it follows it, so frames keep coming however
/// fast the edits arrive. An object edit's previews and first refinement passes are laid over
/// the last refined picture only where the edit can change it. A material-only change makes new
/// versions of the built scenes (RenderScene::with_materials): no BVH is rebuilt, and the scene
/// a run or the denoiser holds is never changed under it.
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
    void setNoiseTarget(double relError) { scheduler_.set_noise_target(relError); }
    double noiseTarget() const { return scheduler_.noise_target(); }
    /// The display exposure the invisible noise target is judged at.
    void setDisplayExposure(double stops) { scheduler_.set_display_exposure(stops); }
    /// The estimated error an endless refinement of `stats` stops at (the status line says it).
    double stopError(const RenderStats& stats) const { return scheduler_.stop_error(stats); }
    /// Whether the viewer shows refined frames denoised (it asks DenoiseWorker for them).
    void setDenoise(bool on) { denoise_.store(on); }
    bool denoise() const { return denoise_.load(); }
    /// Time a drag frame should take (milliseconds): the preview size follows it.
    void setDragFrameTarget(double ms) { dragTargetMs_ = ms; }

    /// Renders `project` (cancelling what runs). `interactive`: quick passes only.
    void request(const Project& project, bool interactive = false);
    /// Stops rendering (before closing, or while the project's files are missing); returns at
    /// once, and no frame of what ran is delivered after it.
    void stop();
    bool idle() const;
    /// Drops the refined picture later edits are laid over: another project was opened, and
    /// nothing of the old picture may show through the new one.
    void forgetPicture();

    /// The latest full-size frame (what export writes).
    std::shared_ptr<const RenderFrame> lastFullFrame() const { return lastFull_; }
    uint64_t generation() const { return requested_; }
    /// Whether the latest request's full-size refinement reached its budget or noise target.
    bool finished() const { return finished_; }
    /// Where the time of the latest request went (milliseconds), for the benchmark.
    struct Timings {
        double cancel = 0;      ///< waiting for the run in flight to stop
        double buildQuick = 0;  ///< building the quick scene (0 when reused)
        double region = 0;      ///< finding the pixels the edit can change
        double firstQuick = 0;  ///< start of the quick run to its first pass
        double compose = 0;     ///< of which laying it over the refined picture
        double buildFull = 0;   ///< building the full-size scene
        double dragFrame = 0;   ///< a drag request's frame: scene, region, pass and compositing
        int dragLevel = 0;      ///< the drag preview size (drag_preview_pixels)
    };
    Timings timings() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return timings_;
    }
    /// Scenes (BVHs) built so far: material-only edits must not add to it.
    int scenesBuilt() const { return scenesBuilt_.load(); }

Q_SIGNALS:
    void frameReady(std::shared_ptr<const dp::ui::RenderFrame> frame);
    /// The refinement of the latest request reached its pass or time budget.
    void refinementFinished();
    /// Loading or building failed (message for the user).
    void failed(const QString& message);
    /// What loading the project's files found (NaN/Inf replaced, an LDR probe, ...); sent when
    /// the list changes, on the UI thread.
    void assetWarnings(const QStringList& warnings);

private:
    struct Request {
        Project project;
        bool interactive = false;
        uint64_t generation = 0;
        QSize size;
        double previewFraction = 0.125;
        double previewScale = 0.5;
        double dragTargetMs = 45;
        bool endless = false;
    };
    /// The pixels an edit can change, at the resolution of the run that found them.
    struct Region {
        std::vector<uint8_t> mask;
        int width = 0, height = 0;
        uint64_t baseGeneration = 0;  ///< the refined picture it is laid over
    };
    /// A full-size state that may become the refined picture edits are laid over.
    struct BaseState {
        Project project;
        std::vector<std::optional<EditedBounds>> bounds;  ///< per object
    };
    class Sink;
    void worker();
    void handle(const Request& r);
    bool superseded();
    /// The region of the edit from the refined picture's state to `p` (null: everything).
    std::shared_ptr<const Region> regionFor(const Project& p, const RenderScene& scene);
    void rememberBase(uint64_t generation, const Project& p, const RenderScene& scene);
    /// Lays `f`'s pass over `base` outside `region` (render thread).
    static void compose(RenderFrame& f, const RenderFrame& base, const Region& region);
    Q_INVOKABLE void deliver();
    Q_INVOKABLE void deliverStopped(quint64 generation, bool finished, const QString& error);

    QSize renderSize_;
    double previewFraction_ = 1.0 / 8.0;
    double previewScale_ = 0.5;
    bool endless_ = false;
    std::atomic<bool> denoise_{false};
    double dragTargetMs_ = 45;
    // The render policy (core): sizes, photons, drag steps, when to stop. Its noise target and
    // exposure are atomics; the rest is the worker thread's.
    RenderScheduler scheduler_;
    // Worker-thread state: the scenes built for `built_` (quick and full size).
    std::unique_ptr<SceneBuilder> builder_;
    Project built_;
    bool haveScenes_ = false;
    std::shared_ptr<const RenderScene> quick_, full_;
    QSize fullSize_, quickSize_;
    std::map<uint64_t, BaseState> bases_;
    // Shared with the render thread's sink, under mutex_.
    std::shared_ptr<RenderFrame> latest_;
    bool posted_ = false;
    uint64_t runGeneration_ = 0;
    bool runPreview_ = false;
    bool runInteractive_ = false;  ///< a one-pass drag preview: new requests wait for it
    bool runEndless_ = false;
    bool runReachedTarget_ = false;
    std::shared_ptr<const Region> runRegion_;
    std::shared_ptr<const RenderScene> runScene_;
    int runFrames_ = 0;
    bool runStopped_ = false;
    Timings timings_;
    std::chrono::steady_clock::time_point runStart_, dragStart_;
    std::shared_ptr<const Image> photo_;
    std::shared_ptr<const RenderFrame> base_;  ///< the refined picture (set on the UI thread)

    std::unique_ptr<Sink> sink_;
    std::unique_ptr<RenderSession> session_;
    std::thread thread_;
    mutable std::mutex mutex_;
    std::condition_variable cv_;
    std::optional<Request> pending_;
    bool quit_ = false;
    bool busy_ = false;
    std::atomic<int> scenesBuilt_{0};
    std::vector<std::string> warned_;  ///< worker thread: the warnings last sent
    uint64_t requested_ = 0;  ///< UI thread
    uint64_t acceptFrom_ = 0; ///< UI thread: previews of this request or later are shown
    bool finished_ = false;   ///< UI thread
    std::shared_ptr<const RenderFrame> last_, lastFull_;
};

}  // namespace dp::ui
