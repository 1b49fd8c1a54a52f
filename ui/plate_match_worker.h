#pragma once
// Gives the studio's refined pictures the photo's grain and softness (image/plate_match.h) on a
// thread of its own: the newest request wins, the UI never waits for it.
#include <QObject>
#include <QString>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>

#include "image/image.h"
#include "image/plate_match.h"

namespace dp {
struct RenderFrame;
}

namespace dp::ui {

/// Measures a photo's grain and softness once (per photo) and matches each picture it is given
/// to them, handing the result back on the UI thread.
class PlateMatchWorker : public QObject {
    Q_OBJECT
public:
    explicit PlateMatchWorker(QObject* parent = nullptr);
    ~PlateMatchWorker() override;
    /// Matches `source` (the picture shown for `frame`: its render, or that denoised), replacing
    /// a request not yet started.
    void request(std::shared_ptr<const RenderFrame> frame, std::shared_ptr<const Image> source);
    /// What was measured of the last photo, for people (empty before the first).
    QString summary() const;

Q_SIGNALS:
    /// `source` matched to the plate.
    void matched(std::shared_ptr<const dp::Image> source, std::shared_ptr<const dp::Image> image);

private:
    void run();

    std::thread thread_;
    mutable std::mutex mutex_;
    std::condition_variable cv_;
    std::shared_ptr<const RenderFrame> frame_;
    std::shared_ptr<const Image> source_;
    bool quit_ = false;
    QString summary_;
    // Worker thread: the figures of the photo last measured, and that photo (the frames' own).
    std::shared_ptr<const Image> photo_;
    PlateFigures figures_;
};

}  // namespace dp::ui
