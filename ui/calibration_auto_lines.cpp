// The camera panel's Detect Lines: the photo's own lines proposed as vanishing lines
// (core/calibration/auto_lines), found on a worker thread, then reviewed by the user as drawn
// lines (dropped, added to) before Apply.
#include <QApplication>
#include <QLabel>
#include <QPointer>
#include <QPushButton>
#include <QStringList>
#include <cmath>

#include "assets/asset_library.h"
#include "base/error.h"
#include "calibration_panel.h"
#include "document.h"
#include "number_field.h"
#include "pick_tool.h"
#include "viewport.h"

namespace dp::ui {

bool CalibrationPanel::detectLines() {
    if (target_ != Target::None) viewport_->pickTool()->stop();
    std::shared_ptr<AssetLibrary> assets;
    Project project;
    AutoLinesOptions options;
    const bool ok = guarded(tr("Line detection failed"), [&] {
        if (detector_.joinable()) throw InputError("", "", "the lines are already being looked for");
        if (!viewport_->renderSize().isValid()) throw InputError("", "", "no photo is shown in the viewport");
        assets = doc_->assetLibrary();
        project = doc_->project();
        if (vanFocal_->value() > 0) options.focal_px = vanFocal_->value();
        options.camera_height = cameraHeight_->value();
    });
    if (!ok) return false;
    QPointer<CalibrationPanel> self(this);
    detectButton_->setEnabled(false);
    status_->setText(tr("Looking for the photo's lines…"));
    // Decoding the photo and finding its lines take their time: off the UI thread.
    detector_ = std::thread([=] {
        AutoLinesResult r;
        QSize size;
        const std::string path = project.resolve(project.photo.path).string();
        try {
            const std::shared_ptr<const Image> photo = assets->photo(project);
            size = QSize(photo->width(), photo->height());
            r = calibrate_from_lines(*photo, options, "the photo's lines");
        } catch (const std::exception& e) {
            r.failure = e.what();
        }
        QMetaObject::invokeMethod(qApp, [self, r = std::move(r), size, path] {
            if (!self) return;
            self->detector_.join();
            self->detectButton_->setEnabled(true);
            self->showDetected(r, size, path);
        }, Qt::QueuedConnection);
    });
    return true;
}

void CalibrationPanel::showDetected(const AutoLinesResult& r, QSize photo, const std::string& path) {
    const Project& p = doc_->project();
    // Another photo opened while it ran: the lines are not this photo's.
    if (p.resolve(p.photo.path).string() != path || !viewport_->renderSize().isValid()) {
        status_->clear();
        return;
    }
    QStringList text;
    for (const std::string& note : r.proposal.notes) text << QString::fromStdString(note);
    if (photo.isValid() && (!r.proposal.axis[0].empty() || !r.proposal.axis[1].empty() || !r.proposal.axis[2].empty())) {
        for (int a = 0; a < 3; ++a) {
            lines_[a].clear();
            for (const LineSegment& s : r.proposal.axis[a])
                lines_[a].push_back({toRender(s.a, photo), toRender(s.b, photo)});
        }
        origin_ = {toRender(r.origin, photo)};
        text << tr("Review the lines: Drop lines removes wrong ones, X, Z and Vertical add more; Apply matches "
                   "the camera.");
    }
    if (r.camera) {
        text << tr("They give a horizontal field of view of %1°.").arg(r.camera->intrinsics.hfov_deg(), 0, 'f', 1);
    } else if (!r.failure.empty()) {
        text << tr("No camera yet: %1").arg(QString::fromStdString(r.failure));
    }
    status_->setText(text.join("\n"));
    refreshMarks();
}

void CalibrationPanel::dropLineNear(QPointF px) {
    // The distance from a click to a segment, in render pixels.
    auto distance = [](QPointF p, QPointF a, QPointF b) {
        const QPointF ab = b - a;
        const double len2 = QPointF::dotProduct(ab, ab);
        const double t = len2 > 0 ? std::clamp(QPointF::dotProduct(p - a, ab) / len2, 0.0, 1.0) : 0.0;
        const QPointF d = p - (a + t * ab);
        return std::hypot(d.x(), d.y());
    };
    int best_axis = -1, best_index = -1;
    double best = 6.0;  // a click this close picks a line
    for (int a = 0; a < 3; ++a)
        for (int i = 0; i < lines_[a].size(); ++i) {
            const double d = distance(px, lines_[a][i].first, lines_[a][i].second);
            if (d < best) best = d, best_axis = a, best_index = i;
        }
    if (best_axis >= 0) lines_[best_axis].remove(best_index);
    refreshMarks();
}

}  // namespace dp::ui
