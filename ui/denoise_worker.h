#pragma once
// Denoises the studio's refined frames on a thread of its own, so that neither the UI nor the
// renderer waits for it: the newest frame wins, older requests are dropped.
#include <QObject>
#include <atomic>
#include <cstdint>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>

#include "image/image.h"
#include "render/denoise_aovs.h"
#include "render/shown_noise.h"

namespace dp {
struct RenderFrame;
}

namespace dp::ui {


/// Runs Open Image Denoise (image/denoise.h) on the change of the frames it is given, guided by
/// the albedo and normal of their scene (computed once per scene), and hands each result back
/// on the UI thread. Where the library is missing, available() says so and nothing runs.
class DenoiseWorker : public QObject {
    Q_OBJECT
public:
    explicit DenoiseWorker(QObject* parent = nullptr);
    ~DenoiseWorker() override;

    /// Whether the denoiser can run; `why` says how to get it where not.
    static bool available(QString* why = nullptr);
    /// Denoises `frame` (replacing a request not yet started).
    void request(std::shared_ptr<const RenderFrame> frame);
    /// While paused (a drag) nothing runs and a denoise in flight is stopped: the drag's
    /// previews need the cores. The last request runs once unpaused.
    void setPaused(bool paused);
    /// Drops the request waiting and stops the denoise in flight: an edit made them stale.
    void dropStale();
    /// Milliseconds the last denoise took (0 before the first).
    double lastMs() const;
    /// The denoised augmented image of `frame` at its size, at the interactive quality;
    /// empty where the denoiser is missing or the frame has no scene.
    static Image denoise_now(const RenderFrame& frame, const DenoiseAovs& aovs,
                             const std::atomic<bool>* cancel = nullptr);

    /// What the viewport shows denoised for `frame`: `denoised` (the frame's own render,
    /// denoised) as it is, or for a frame laid over the refined picture, the same composite at
    /// the shown size: the edit's pixels from `denoised` (resampled where it is a quick pass's,
    /// rendered smaller), the others from `denoisedBase` (the refined frame's denoised image, if
    /// given) or the frame's own shown pixels.
    static Image compose_denoised(const RenderFrame& frame, const Image& denoised, const Image* denoisedBase);

Q_SIGNALS:
    /// The denoised augmented image of `frame`, at its size.
    void denoised(std::shared_ptr<const dp::RenderFrame> frame, std::shared_ptr<const dp::Image> image);
    /// The estimated relative error of the denoised picture of a refined frame (request
    /// `generation` after `passes` passes), over the pixels the objects change (ShownNoise);
    /// sent after its `denoised`, once an earlier picture of the state allows it.
    void shownError(quint64 generation, int passes, double error);

private:
    void run();

    std::thread thread_;
    mutable std::mutex mutex_;
    std::condition_variable cv_;
    std::shared_ptr<const RenderFrame> pending_;
    bool quit_ = false, paused_ = false;
    bool stale_ = false;  ///< dropStale() stopped the denoise in flight: it is not asked again
    std::atomic<bool> cancel_{false};
    double lastMs_ = 0;
    std::shared_ptr<const RenderScene> aovScene_;  ///< worker thread: the scene `aovs_` belongs to
    DenoiseAovs aovs_;
    /// Worker thread: the last refined (not composited) frame's denoised image, laid under
    /// the denoised edits of later frames.
    std::shared_ptr<const Image> lastWhole_;
    uint64_t lastWholeGeneration_ = 0;
    ShownNoise noise_;  ///< worker thread
};

}  // namespace dp::ui
