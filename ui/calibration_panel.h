#pragma once
#include <QPointF>
#include <QVector>
#include <QWidget>
#include <functional>
#include <string>

#include "calibration/calibration.h"
#include "image/image.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QSpinBox;
class QStackedWidget;

namespace dp::ui {

class CameraPanel;
class Document;
class ErrorReporter;
class Viewport;

/// The camera-matching tools of the camera panel: chessboard auto-detect on the project's
/// photo, the four clicked corners of a known rectangle, or vanishing lines drawn on the photo
/// with the image of the origin and one known length (the camera's height, a ground distance
/// or a vertical length). Clicks and drags go through the viewport's pick tool; a result is
/// applied through CameraPanel::applyCalibration (one undo step) and its uncertainty and
/// warnings are shown in the status line. Bad input reaches the user through the error
/// reporter and changes nothing. Widgets carry object names (e.g. "rectanglePick") for tests
/// and scripting.
class CalibrationPanel : public QWidget {
    Q_OBJECT
public:
    enum class Method { Chessboard, Rectangle, Vanishing };

    CalibrationPanel(Document* doc, Viewport* viewport, CameraPanel* camera,
                     ErrorReporter* reporter, QWidget* parent = nullptr);

    void setMethod(Method m);
    /// Rectangle corners clicked so far (render pixels).
    const QVector<QPointF>& corners() const { return corners_; }

    // The "Apply" buttons; each returns false (after reporting) on bad input.
    bool applyChessboard();
    bool applyRectangle();
    bool applyVanishing();
    /// Adds the ground (y = 0) as a real plane proxy covering what the camera sees of it.
    bool addGroundPlane();

private:
    /// What the pick tool's clicks and drags are for.
    enum class Target { None, Corners, X, Y, Z, Origin, Distance, Vertical };

    QWidget* makeChessboardPage();
    QWidget* makeRectanglePage();
    QWidget* makeVanishingPage();
    void startPicking(Target target);
    void onPoint(QPointF px);
    void onSegment(QPointF a, QPointF b);
    void refreshMarks();
    void clearPicks();
    /// Runs `f`, reporting any error under `title`; returns false after an error.
    bool guarded(const QString& title, const std::function<void()>& f);
    /// Applies `r` as the project camera and shows its warnings.
    void apply(const QString& method, const CalibrationResult& r);
    /// The project's photo (loaded once per path) and its file name, for messages.
    const Image& photo(std::string* path = nullptr);
    /// Render pixel -> photo pixel (pixel edges scale).
    ImagePoint toPhoto(QPointF renderPx);
    /// How precisely a click lands on the photo: half a render pixel, in photo pixels.
    double clickSigma();

    Document* doc_;
    Viewport* viewport_;
    CameraPanel* camera_;
    ErrorReporter* reporter_;
    QComboBox* method_;
    QStackedWidget* pages_;
    QLabel* status_;
    // Chessboard.
    QSpinBox *cols_, *rows_;
    QDoubleSpinBox *square_, *boardFocal_;
    QComboBox* focalSource_;
    // Rectangle.
    QDoubleSpinBox *rectWidth_, *rectHeight_, *rectFocal_;
    QLabel* cornerCount_;
    // Vanishing lines.
    QDoubleSpinBox *cameraHeight_, *distance_, *vertical_, *vanFocal_;
    QCheckBox* freePrincipal_;
    QLabel* lineCount_;

    Target target_ = Target::None;
    QVector<QPointF> corners_;
    QVector<QPair<QPointF, QPointF>> lines_[3];  ///< X, Y, Z
    QVector<QPointF> origin_, distanceEnds_, verticalEnds_;
    std::string photoPath_;
    Image photo_;
};

}  // namespace dp::ui
