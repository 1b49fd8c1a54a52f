#pragma once
#include <QColor>
#include <QObject>
#include <QPointF>
#include <QString>
#include <QVector>

class QPainter;
class QTransform;

namespace dp::ui {

/// A viewport interaction for the calibration and proxy tools: while active, left clicks pick
/// points (or left drags draw segments) on the photo instead of selecting objects, and Esc
/// cancels. Points are in render pixel coordinates (pixel centres at integers). The tool only
/// reports picks; whoever started it keeps them and hands back the marks to draw.
class PickTool : public QObject {
    Q_OBJECT
public:
    enum class Kind { Point, Segment };
    /// A point (a == b, segment false) or a segment drawn over the photo.
    struct Mark {
        QPointF a, b;
        bool segment = false;
        QColor colour{255, 200, 0};
        QString label;
    };

    explicit PickTool(QObject* parent = nullptr) : QObject(parent) {}

    /// Starts picking; `count` picks end it (0: until stop() or Esc). `prompt` is shown in the
    /// viewport while it runs.
    void start(Kind kind, int count = 0, const QString& prompt = {});
    /// Ends picking normally (finished(false)).
    void stop();
    /// Ends picking with Esc (finished(true)): the owner drops this run's picks.
    void cancel();
    bool active() const { return active_; }
    Kind kind() const { return kind_; }

    /// Marks drawn over the photo while and after picking.
    void setMarks(const QVector<Mark>& marks);
    const QVector<Mark>& marks() const { return marks_; }

    // Viewport events in render pixel coordinates; each returns true if it used the event.
    bool press(QPointF px);
    bool move(QPointF px);
    bool release(QPointF px);
    /// Draws the marks, the segment being dragged and the prompt; `toWidget` maps render
    /// pixel coordinates to widget coordinates.
    void paint(QPainter& painter, const QTransform& toWidget) const;

Q_SIGNALS:
    void pointPicked(QPointF px);
    void segmentDrawn(QPointF a, QPointF b);
    void finished(bool cancelled);
    /// Something to repaint.
    void changed();

private:
    void picked();

    Kind kind_ = Kind::Point;
    bool active_ = false, dragging_ = false;
    int count_ = 0, done_ = 0;
    QString prompt_;
    QPointF dragA_, dragB_;
    QVector<Mark> marks_;
};

}  // namespace dp::ui
