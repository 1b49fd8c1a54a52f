#include "matte_tool.h"

#include <QPainter>
#include <QPainterPath>
#include <cmath>

namespace dp::ui {

namespace {

/// The mask as a translucent red layer, white where it is clear.
QImage tinted(const QImage& mask) {
    QImage out(mask.size(), QImage::Format_ARGB32_Premultiplied);
    for (int y = 0; y < mask.height(); ++y) {
        const uchar* in = mask.constScanLine(y);
        auto* px = reinterpret_cast<QRgb*>(out.scanLine(y));
        for (int x = 0; x < mask.width(); ++x) px[x] = in[x] >= 128 ? qRgba(110, 0, 0, 110) : qRgba(0, 0, 0, 0);
    }
    return out;
}

}  // namespace

void MatteTool::start(Mode mode, const QImage& mask) {
    mask_ = mask.convertToFormat(QImage::Format_Grayscale8);
    if (strokes_.size() != mask_.size()) {
        strokes_ = QImage(mask_.size(), QImage::Format_Grayscale8);
        strokes_.fill(0);
        cutRect_ = {};
    }
    mode_ = mode;
    active_ = true;
    polygon_.clear();
    Q_EMIT changed();
}

void MatteTool::stop() {
    if (!active_) return;
    active_ = stroking_ = false;
    polygon_.clear();
    Q_EMIT finished();
    Q_EMIT changed();
}

void MatteTool::setMode(Mode mode) {
    mode_ = mode;
    polygon_.clear();
    Q_EMIT changed();
}

void MatteTool::setMask(const QImage& mask) {
    mask_ = mask.convertToFormat(QImage::Format_Grayscale8);
    if (strokes_.size() != mask_.size()) {
        strokes_ = QImage(mask_.size(), QImage::Format_Grayscale8);
        strokes_.fill(0);
        cutRect_ = {};
    }
    Q_EMIT changed();
}

void MatteTool::setShown(bool on) {
    shown_ = on;
    Q_EMIT changed();
}

void MatteTool::dab(QPointF from, QPointF to) {
    const int value = erasing_ ? 0 : 255;
    QPen pen(QColor(value, value, value), 2 * radius_, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin);
    {
        QPainter p(&mask_);
        p.setPen(pen);
        p.drawLine(from, to);
    }
    if (!cutRect_.isEmpty()) {  // a stroke after a cut is a sure label for the next cut
        QPainter p(&strokes_);
        const int label = erasing_ ? 2 : 1;
        p.setPen(QPen(QColor(label, label, label), 2 * radius_, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
        p.drawLine(from, to);
    }
    Q_EMIT changed();
}

void MatteTool::closePolygon() {
    if (polygon_.size() >= 3) {
        QPainter p(&mask_);
        p.setPen(Qt::NoPen);
        p.setBrush(QColor(255, 255, 255));
        p.drawPolygon(polygon_);
        polygon_.clear();
        Q_EMIT strokeFinished();
    }
    polygon_.clear();
    Q_EMIT changed();
}

bool MatteTool::press(QPointF px, Qt::KeyboardModifiers modifiers) {
    if (!active_ || mask_.isNull()) return false;
    switch (mode_) {
        case Mode::Brush:
        case Mode::Erase:
            erasing_ = mode_ == Mode::Erase || (modifiers & Qt::ShiftModifier);
            stroking_ = true;
            last_ = px;
            dab(px, px);
            return true;
        case Mode::Polygon: {
            // A click near the first corner closes the polygon.
            if (polygon_.size() >= 3 && QLineF(polygon_.first(), px).length() <= std::max(4.0, radius_ / 2)) {
                closePolygon();
                return true;
            }
            polygon_ << px;
            Q_EMIT changed();
            return true;
        }
        case Mode::Cut:
            stroking_ = true;
            rectA_ = rectB_ = px;
            Q_EMIT changed();
            return true;
    }
    return false;
}

bool MatteTool::move(QPointF px) {
    cursor_ = px;
    if (!active_) return false;
    if (stroking_ && (mode_ == Mode::Brush || mode_ == Mode::Erase)) {
        dab(last_, px);
        last_ = px;
    } else if (stroking_ && mode_ == Mode::Cut) {
        rectB_ = px;
    }
    Q_EMIT changed();
    return true;
}

bool MatteTool::release(QPointF px) {
    if (!active_ || !stroking_) return active_;
    stroking_ = false;
    if (mode_ == Mode::Cut) {
        rectB_ = px;
        const QRect r = QRectF(rectA_, rectB_).normalized().toAlignedRect().intersected(mask_.rect());
        Q_EMIT changed();
        if (r.width() >= 3 && r.height() >= 3) {
            cutRect_ = r;
            strokes_.fill(0);  // a new rectangle starts a new cut
            Q_EMIT cutRequested(r);
        }
        return true;
    }
    dab(last_, px);
    Q_EMIT strokeFinished();
    return true;
}

bool MatteTool::doubleClick(QPointF) {
    if (!active_ || mode_ != Mode::Polygon) return false;
    closePolygon();
    return true;
}

bool MatteTool::key(int key) {
    if (!active_) return false;
    if ((key == Qt::Key_Return || key == Qt::Key_Enter) && mode_ == Mode::Polygon) {
        closePolygon();
        return true;
    }
    if (key == Qt::Key_Escape) {
        if (!polygon_.isEmpty()) {
            polygon_.clear();
            Q_EMIT changed();
        } else {
            stop();
        }
        return true;
    }
    return false;
}

void MatteTool::paint(QPainter& painter, const QTransform& toWidget) const {
    if ((!active_ && !shown_) || mask_.isNull()) return;
    painter.save();
    // The mask's pixels are centred on whole render coordinates: its image spans -0.5 .. w-0.5.
    painter.setTransform(QTransform::fromTranslate(-0.5, -0.5) * toWidget);
    painter.drawImage(QPointF(0, 0), tinted(mask_));
    painter.restore();
    if (!active_) return;
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing);
    QPen pen(QColor(255, 80, 80), 1.5);
    painter.setPen(pen);
    if ((mode_ == Mode::Brush || mode_ == Mode::Erase) && cursor_.x() > -1e8) {
        const QPointF c = toWidget.map(cursor_);
        const double r = radius_ * std::abs(toWidget.m11());
        painter.drawEllipse(c, r, r);
    }
    if (mode_ == Mode::Polygon && !polygon_.isEmpty()) {
        QPolygonF shown = toWidget.map(polygon_);
        if (cursor_.x() > -1e8) shown << toWidget.map(cursor_);
        painter.drawPolyline(shown);
        for (const QPointF& p : toWidget.map(polygon_)) painter.drawEllipse(p, 3, 3);
    }
    if (mode_ == Mode::Cut && (stroking_ || !cutRect_.isEmpty())) {
        pen.setStyle(Qt::DashLine);
        painter.setPen(pen);
        const QRectF r = stroking_ ? QRectF(rectA_, rectB_).normalized() : QRectF(cutRect_);
        painter.drawPolygon(toWidget.map(QPolygonF(r)));
    }
    painter.restore();
}

}  // namespace dp::ui
