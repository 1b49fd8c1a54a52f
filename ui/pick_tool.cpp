#include "pick_tool.h"

#include <QLineF>
#include <QPainter>
#include <QTransform>

namespace dp::ui {

void PickTool::start(Kind kind, int count, const QString& prompt) {
    kind_ = kind;
    count_ = count;
    done_ = 0;
    prompt_ = prompt;
    dragging_ = false;
    active_ = true;
    Q_EMIT changed();
}

void PickTool::stop() {
    if (!active_) return;
    active_ = dragging_ = false;
    Q_EMIT finished(false);
    Q_EMIT changed();
}

void PickTool::cancel() {
    if (!active_) return;
    active_ = dragging_ = false;
    Q_EMIT finished(true);
    Q_EMIT changed();
}

void PickTool::setMarks(const QVector<Mark>& marks) {
    marks_ = marks;
    Q_EMIT changed();
}

void PickTool::picked() {
    ++done_;
    if (count_ > 0 && done_ >= count_) stop();
}

bool PickTool::press(QPointF px) {
    if (!active_) return false;
    if (kind_ == Kind::Point) {
        Q_EMIT pointPicked(px);
        picked();
    } else {
        dragging_ = true;
        dragA_ = dragB_ = px;
    }
    Q_EMIT changed();
    return true;
}

bool PickTool::move(QPointF px) {
    if (!active_ || !dragging_) return active_;
    dragB_ = px;
    Q_EMIT changed();
    return true;
}

bool PickTool::release(QPointF px) {
    if (!active_ || !dragging_) return active_;
    dragging_ = false;
    dragB_ = px;
    // A click without a drag draws nothing: a segment needs two distinct ends.
    if (QLineF(dragA_, dragB_).length() >= 2.0) {
        Q_EMIT segmentDrawn(dragA_, dragB_);
        picked();
    }
    Q_EMIT changed();
    return true;
}

void PickTool::paint(QPainter& p, const QTransform& t) const {
    p.save();
    p.setRenderHint(QPainter::Antialiasing, true);
    auto drawSegment = [&](QPointF a, QPointF b, const QColor& c) {
        p.setPen(QPen(QColor(0, 0, 0, 160), 4));
        p.drawLine(t.map(a), t.map(b));
        p.setPen(QPen(c, 2));
        p.drawLine(t.map(a), t.map(b));
        for (QPointF e : {a, b}) p.drawEllipse(t.map(e), 3, 3);
    };
    for (const Mark& m : marks_) {
        if (m.segment) {
            drawSegment(m.a, m.b, m.colour);
        } else {
            const QPointF c = t.map(m.a);
            p.setPen(QPen(QColor(0, 0, 0, 160), 4));
            p.drawEllipse(c, 6, 6);
            p.setPen(QPen(m.colour, 2));
            p.drawEllipse(c, 6, 6);
            p.drawLine(c - QPointF(9, 0), c + QPointF(9, 0));
            p.drawLine(c - QPointF(0, 9), c + QPointF(0, 9));
        }
        if (!m.label.isEmpty()) {
            p.setPen(m.colour);
            p.drawText(t.map(m.segment ? m.b : m.a) + QPointF(8, -8), m.label);
        }
    }
    if (active_ && dragging_) drawSegment(dragA_, dragB_, QColor(255, 255, 255));
    if (active_ && !prompt_.isEmpty()) {
        const QRectF box(10, 10, 520, 26);
        p.resetTransform();
        p.fillRect(box, QColor(0, 0, 0, 170));
        p.setPen(QColor(255, 230, 120));
        p.drawText(box.adjusted(8, 0, -8, 0), Qt::AlignVCenter | Qt::AlignLeft,
                   prompt_ + tr("  (Esc cancels)"));
    }
    p.restore();
}

}  // namespace dp::ui
