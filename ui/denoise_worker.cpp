#include "denoise_worker.h"

#include <QMetaObject>
#include <chrono>

#include "image/denoise.h"
#include "image/noise_blend.h"
#include "render_controller.h"

namespace dp::ui {

DenoiseWorker::DenoiseWorker(QObject* parent) : QObject(parent) {
    thread_ = std::thread([this] { run(); });
}

DenoiseWorker::~DenoiseWorker() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        quit_ = true;
        cancel_.store(true);
    }
    cv_.notify_all();
    thread_.join();
}

bool DenoiseWorker::available(QString* why) {
    std::string reason;
    const bool ok = denoiser_available(&reason);
    if (why) *why = QString::fromStdString(reason);
    return ok;
}

void DenoiseWorker::request(std::shared_ptr<const RenderFrame> frame) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        pending_ = std::move(frame);
    }
    cv_.notify_all();
}

void DenoiseWorker::dropStale() {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_.reset();
    stale_ = true;
    cancel_.store(true);
}

double DenoiseWorker::lastMs() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return lastMs_;
}

void DenoiseWorker::setPaused(bool paused) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        paused_ = paused;
        cancel_.store(paused);
    }
    cv_.notify_all();
}

Image DenoiseWorker::denoise_now(const RenderFrame& f, const DenoiseAovs& aovs, const std::atomic<bool>* cancel) {
    if (!f.scene || f.update.image.empty() || !denoiser_available()) return {};
    const Image& photo = f.scene->photo();
    if (photo.width() != f.update.image.width() || aovs.albedo.width() != photo.width()) return {};
    Image d = denoise_augmented(photo, f.update.image, f.update.alpha, f.update.dL, aovs.albedo, aovs.normal,
                                DenoiseQuality::Interactive, cancel);
    // Refined far enough, the raw pixels stand where the filter would only blur them.
    const Image& v = f.update.variance;
    if (v.width() == d.width() && v.height() == d.height()) d = blend_by_noise(f.update.image, d, v);
    return d;
}

Image DenoiseWorker::compose_denoised(const RenderFrame& f, const Image& denoised, const Image* denoisedBase) {
    if (!f.composited() || !f.shown_from_edit) return denoised;
    const Image& shown = f.image();
    const int OW = shown.width(), OH = shown.height(), step = std::max(1, f.shown_step);
    const std::vector<uint8_t>& fromEdit = *f.shown_from_edit;
    if (fromEdit.size() != shown.size() || denoised.empty()) return {};
    // The full render's size: the refined picture's (a quick pass is rendered smaller and its
    // denoised pixels are resampled into the edit's region, as its raw ones were).
    const bool base = denoisedBase && denoisedBase->width() >= OW * step && denoisedBase->height() >= OH * step;
    const int W = base ? denoisedBase->width() : std::max(denoised.width(), OW * step);
    const int H = base ? denoisedBase->height() : std::max(denoised.height(), OH * step);
    const bool same = denoised.width() == W && denoised.height() == H;
    if (same && (OW * step > W || OH * step > H)) return {};
    const float sx = float(denoised.width()) / float(W), sy = float(denoised.height()) / float(H);
    Image out(OW, OH);
    for (int oy = 0; oy < OH; ++oy)
        for (int ox = 0; ox < OW; ++ox) {
            const size_t o = size_t(oy) * OW + ox;
            const int x = ox * step + step / 2, y = oy * step + step / 2;
            const size_t i = size_t(y) * W + size_t(x);
            if (!fromEdit[o]) out[o] = base ? (*denoisedBase)[i] : shown[o];
            else if (same) out[o] = denoised[i];
            else out[o] = denoised.bilinear((float(x) + 0.5f) * sx - 0.5f, (float(y) + 0.5f) * sy - 0.5f);
        }
    return out;
}

void DenoiseWorker::run() {
    for (;;) {
        std::shared_ptr<const RenderFrame> frame;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            cv_.wait(lock, [&] { return quit_ || (pending_ && !paused_); });
            if (quit_) return;
            frame = std::move(pending_);
            cancel_.store(false);
            stale_ = false;
        }
        if (!frame->scene) continue;
        const auto t0 = std::chrono::steady_clock::now();
        try {
            // The guides are one ray per pixel: once per scene, not per pass; an edit stops them.
            if (aovScene_ != frame->scene) {
                aovScene_.reset();
                aovs_ = denoise_aovs(*frame->scene, &cancel_);
                aovScene_ = frame->scene;
            }
            Image result = denoise_now(*frame, aovs_, &cancel_);
            if (result.empty()) continue;
            // The frame's own render, denoised: its state's picture, whose noise is judged
            // against earlier ones of the state (composited frames show it in the edit's pixels).
            const auto own = std::make_shared<const Image>(std::move(result));
            const double error = noise_.add(frame->generation, frame->update.stats.passes, own, frame->scene->photo(),
                                            frame->update.alpha, frame->update.image);
            std::shared_ptr<const Image> image = own;
            if (frame->composited()) {
                // The edit's pixels denoised; the rest is the refined picture's, denoised
                // where its denoised image is the last one made.
                const bool base = lastWhole_ && lastWholeGeneration_ == frame->base_generation;
                image = std::make_shared<const Image>(compose_denoised(*frame, *own, base ? lastWhole_.get() : nullptr));
                if (image->empty()) continue;
            } else if (!frame->preview) {
                lastWhole_ = own;
                lastWholeGeneration_ = frame->generation;
            }
            {
                std::lock_guard<std::mutex> lock(mutex_);
                lastMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            }
            QMetaObject::invokeMethod(
                this, [this, frame, image] { Q_EMIT denoised(frame, image); }, Qt::QueuedConnection);
            if (error >= 0)
                QMetaObject::invokeMethod(
                    this, [this, g = frame->generation, p = frame->update.stats.passes, error] {
                        Q_EMIT shownError(g, p, error);
                    },
                    Qt::QueuedConnection);
        } catch (const std::exception&) {
            // Stopped by a drag, or failed: the raw picture stays on screen; a stopped frame
            // is asked for again when the drag ends.
            std::lock_guard<std::mutex> lock(mutex_);
            if (cancel_.load() && !pending_ && !stale_) pending_ = frame;
        }
    }
}

}  // namespace dp::ui
