#pragma once
#include <QImage>
#include <QObject>
#include <QPointF>
#include <QPolygonF>
#include <QRectF>

class QPainter;
class QTransform;

namespace dp::ui {

/// A viewport interaction that paints a holdout's mask over the photo: a round brush adds
/// (Erase, or the brush with Shift, removes), a polygon is clicked corner by corner and closed
/// by Enter, a double click or a click on its first corner, and a rectangle dragged around an
/// occluder asks for a cut (GrabCut). The mask is one byte per render pixel, 255 where the
/// occluder is. Strokes after a cut are remembered as sure occluder or background for a
/// cut again. While active, left clicks and drags go to it; Esc ends it (the owner keeps the
/// mask as it is).
class MatteTool : public QObject {
    Q_OBJECT
public:
    enum class Mode { Brush, Erase, Polygon, Cut };
    explicit MatteTool(QObject* parent = nullptr) : QObject(parent) {}

    /// Starts painting `mask` (Format_Grayscale8, the render's size) in `mode`.
    void start(Mode mode, const QImage& mask);
    /// Ends painting (finished()); the mask stays shown until setShown(false).
    void stop();
    bool active() const { return active_; }
    Mode mode() const { return mode_; }
    void setMode(Mode mode);
    /// The mask as painted so far.
    const QImage& mask() const { return mask_; }
    /// Replaces the mask (an undo, a cut's result) without a stroke.
    void setMask(const QImage& mask);
    /// Whether the mask is drawn over the picture (tinted) while the tool is not active.
    void setShown(bool on);
    bool shown() const { return shown_; }
    /// The brush's radius in render pixels.
    void setBrushRadius(double px) { radius_ = px; }
    double brushRadius() const { return radius_; }
    /// The rectangle of the last cut (empty before one) and what strokes since have marked:
    /// 1 sure occluder, 2 sure background, 0 nothing (one byte per render pixel).
    QRect cutRect() const { return cutRect_; }
    const QImage& cutStrokes() const { return strokes_; }

    // Viewport events in render pixel coordinates; each returns true if it used the event.
    bool press(QPointF px, Qt::KeyboardModifiers modifiers);
    bool move(QPointF px);
    bool release(QPointF px);
    bool doubleClick(QPointF px);
    /// Enter closes a polygon, Esc drops the polygon being drawn (or ends the tool).
    bool key(int key);
    /// Draws the mask tinted, the brush's outline, the polygon being drawn and the cut's
    /// rectangle; `toWidget` maps render pixel coordinates to widget coordinates.
    void paint(QPainter& painter, const QTransform& toWidget) const;

Q_SIGNALS:
    /// A brush stroke ended or a polygon closed: mask() holds the result.
    void strokeFinished();
    /// A rectangle was dragged in Cut mode (render pixels).
    void cutRequested(QRect rect);
    void finished();
    /// Something to repaint.
    void changed();

private:
    void dab(QPointF from, QPointF to);
    void closePolygon();

    Mode mode_ = Mode::Brush;
    bool active_ = false, shown_ = false, stroking_ = false, erasing_ = false;
    double radius_ = 12;
    QImage mask_, strokes_;
    QPolygonF polygon_;
    QPointF last_, cursor_{-1e9, -1e9}, rectA_, rectB_;
    QRect cutRect_;
};

}  // namespace dp::ui
