#pragma once
#include <QPointF>
#include <QVector>
#include <QWidget>
#include <functional>

class QCheckBox;
class QDoubleSpinBox;
class QLabel;

namespace dp::ui {

class Document;
class ErrorReporter;
class Viewport;

/// Aligns the light probe with the photo: the sun cue (click a point of an object and the tip
/// of its shadow: the probe turns about the vertical so its brightest region lies where the
/// shadow says the sun is) and the grey card (drag over a card of known reflectance: the probe
/// intensity is scaled so the card's shading matches the photo, and with "Match colour too" its
/// white balance so the card's colour does), and the sun's strength from a shadow (click a
/// sunlit and a shadowed patch of one surface: a clipped sun is scaled back until the probe
/// gives them the photo's contrast). Each is one undo step.
class ProbeAlignPanel : public QWidget {
    Q_OBJECT
public:
    ProbeAlignPanel(Document* doc, Viewport* viewport, ErrorReporter* reporter,
                    QWidget* parent = nullptr);

    /// Turns the probe from a cue: object point and shadow tip in render pixels.
    bool alignSun(QPointF object, QPointF shadowTip);
    /// Scales the probe intensity from a grey card: opposite corners in render pixels. With
    /// colourBox() ticked, the white balance is matched in the same edit.
    bool matchGreyCard(QPointF a, QPointF b);
    QCheckBox* colourBox() const { return colour_; }
    /// Scales the probe's sun (probe.sun_scale) from a sunlit and a shadowed patch of one real
    /// surface, in render pixels.
    bool restoreSun(QPointF lit, QPointF shadow);

private:
    enum class Target { None, Sun, Card, SunStrength };
    void startPicking(Target target);
    bool guarded(const QString& title, const std::function<void()>& f);

    Document* doc_;
    Viewport* viewport_;
    ErrorReporter* reporter_;
    QDoubleSpinBox *height_, *reflectance_;
    QCheckBox *base_, *colour_;
    QLabel* status_;
    Target target_ = Target::None;
    QVector<QPointF> points_;
};

}  // namespace dp::ui
