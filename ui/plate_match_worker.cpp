#include "plate_match_worker.h"

#include "render/view_frame.h"

namespace dp::ui {

PlateMatchWorker::PlateMatchWorker(QObject* parent) : QObject(parent) {
    thread_ = std::thread([this] { run(); });
}

PlateMatchWorker::~PlateMatchWorker() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        quit_ = true;
    }
    cv_.notify_all();
    thread_.join();
}

void PlateMatchWorker::request(std::shared_ptr<const RenderFrame> frame, std::shared_ptr<const Image> source) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        frame_ = std::move(frame);
        source_ = std::move(source);
    }
    cv_.notify_all();
}

QString PlateMatchWorker::summary() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return summary_;
}

void PlateMatchWorker::run() {
    for (;;) {
        std::shared_ptr<const RenderFrame> frame;
        std::shared_ptr<const Image> source;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            cv_.wait(lock, [&] { return quit_ || frame_; });
            if (quit_) return;
            frame = std::move(frame_);
            source = std::move(source_);
        }
        const RenderUpdate& u = frame->update;
        const Image& photo = frame->scene ? frame->scene->photo() : *frame->photo;
        if (!source || photo.width() != source->width() || photo.height() != source->height() ||
            u.alpha.width() != source->width() || u.dL.width() != source->width())
            continue;  // a quick pass at another size: not matched
        try {
            // Measured once per photo: the library's decoded photo outlives the scenes that
            // edits rebuild (each holds its own copy), so it is the key.
            const std::shared_ptr<const Image> key = frame->photo;
            if (!key || key != photo_) {
                figures_ = measure_plate(photo);
                photo_ = key;
                std::lock_guard<std::mutex> lock(mutex_);
                summary_ = QString::fromStdString(figures_.summary());
            }
            auto image = std::make_shared<const Image>(match_plate(*source, photo, u.alpha, u.dL, figures_, 1).beauty);
            QMetaObject::invokeMethod(
                this, [this, source, image] { Q_EMIT matched(source, image); }, Qt::QueuedConnection);
        } catch (const std::exception&) {
            // Out of memory for the layers: the unmatched picture stays on screen.
        }
    }
}

}  // namespace dp::ui
