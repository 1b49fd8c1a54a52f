#pragma once
#include <QPointF>
#include <QSize>
#include <QVector>
#include <QWidget>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "calibration/auto_lines.h"
#include "calibration/calibration.h"
#include "calibration/chessboard.h"
#include "image/image.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QProgressDialog;
class QPushButton;
class QSpinBox;
class QStackedWidget;

namespace dp::ui {

class CameraPanel;
class Document;
class ErrorReporter;
class LensPhotosDialog;
class Viewport;

/// The camera-matching tools of the camera panel: chessboard auto-detect on the project's
/// photo, the four clicked corners of a known rectangle, or vanishing lines drawn on the photo
/// with the image of the origin and one known length (the camera's height, a ground distance
/// or a vertical length). A chessboard may hang on a wall: the ground is then chosen from the
/// camera's up or a dragged horizon, with the board's height above it; several photos of the
/// board calibrate the lens (on a worker thread), and the photo can be exported with the
/// lens' distortion taken out. Clicks and drags go through the viewport's pick tool; a result is
/// applied through CameraPanel::applyCalibration (one undo step) and its uncertainty and
/// warnings are shown in the status line. Bad input reaches the user through the error
/// reporter and changes nothing. Widgets carry object names (e.g. "rectanglePick") for tests
/// and scripting.
class CalibrationPanel : public QWidget {
    Q_OBJECT
public:
    enum class Method { Chessboard, Rectangle, Vanishing };
    /// Which plane a chessboard lies on: the ground itself, or a wall whose up comes from the
    /// camera (no roll) or from a horizon dragged on the photo.
    enum class BoardPlane { Ground, WallCameraUp, WallHorizon };

    CalibrationPanel(Document* doc, Viewport* viewport, CameraPanel* camera,
                     ErrorReporter* reporter, QWidget* parent = nullptr);
    ~CalibrationPanel() override;

    void setMethod(Method m);
    /// Rectangle corners clicked so far (render pixels).
    const QVector<QPointF>& corners() const { return corners_; }

    // The "Apply" buttons; each returns false (after reporting) on bad input.
    bool applyChessboard();
    bool applyRectangle();
    bool applyVanishing();
    /// Finds lines in the photo on a worker thread and proposes them as the X, Z and vertical
    /// lines with an origin (calibrate_from_lines), for the user to drop, add to and Apply.
    /// False (after reporting) when it cannot start; detecting() tells when it is done.
    bool detectLines();
    bool detecting() const { return detector_.joinable(); }
    /// Adds the ground (y = 0) as a real plane proxy covering what the camera sees of it.
    bool addGroundPlane();

    /// The lens from the board in the project's photo and in `photos` (file paths; the
    /// project's photo among them is skipped): detection runs on a worker thread with a
    /// progress dialog that can cancel it, then the camera of the project's photo (intrinsics,
    /// distortion, pose; the board plane chosen applies) is applied as one undo step. Returns
    /// false (after reporting) when it cannot start; lensRunning() tells when it is done.
    bool calibrateLens(const QStringList& photos);
    bool lensRunning() const { return lensWorker_.joinable(); }
    /// The dialog "Lens from several photos..." opens (created on first use).
    LensPhotosDialog* lensDialog();
    /// Writes the project's photo with the camera's lens distortion taken out (undistort_image)
    /// as .exr (linear) or .png/.jpg (sRGB, as the photo's own encoding). Returns false after
    /// reporting bad input (an unknown extension, an unreadable photo, a failed write).
    bool exportUndistortedPhoto(const QString& path);
    /// Asks for a file name, then exportUndistortedPhoto (File > Export Undistorted Photo).
    void exportUndistortedDialog();

private:
    /// What the pick tool's clicks and drags are for.
    enum class Target { None, Corners, X, Y, Z, Origin, Distance, Vertical, Horizon, BoardFoot, Drop };

    QWidget* makeChessboardPage();
    QWidget* makeRectanglePage();
    QWidget* makeVanishingPage();
    void startPicking(Target target);
    void onPoint(QPointF px);
    void onSegment(QPointF a, QPointF b);
    void refreshMarks();
    /// On the UI thread once the detector is done: the proposal as the drawn lines.
    void showDetected(const AutoLinesResult& r, QSize photo, const std::string& path);
    /// Removes the drawn line nearest `px` (render pixels), within a few pixels.
    void dropLineNear(QPointF px);
    void clearPicks();
    /// Runs `f`, reporting any error under `title`; returns false after an error.
    bool guarded(const QString& title, const std::function<void()>& f);
    /// Applies `r` as the project camera and shows its warnings, then `more` (lines).
    void apply(const QString& method, const CalibrationResult& r, const QString& more = {});
    /// `r` (in the board's frame) with the ground the "Board lies on" choice makes; `ground`
    /// receives a line for the status saying which plane is the ground; `up`, if given, the up
    /// (camera coordinates) a wall's board was levelled with (left as it is for the ground).
    CalibrationResult placeGround(const CalibrationResult& r, const std::string& source,
                                  QString* ground, glm::dvec3* up = nullptr);
    /// The board's spec from the page's fields.
    ChessboardSpec boardSpec() const;
    /// On the UI thread once the lens worker is done: applies its result or reports its error.
    void finishLens();
    /// The project's photo (loaded once per path) and its file name, for messages.
    const Image& photo(std::string* path = nullptr);
    /// Render pixel -> photo pixel (pixel edges scale), and back for a photo of `photo` pixels.
    ImagePoint toPhoto(QPointF renderPx);
    QPointF toRender(ImagePoint photoPx, QSize photo) const;
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
    QDoubleSpinBox *square_, *boardFocal_, *boardHeight_;
    QComboBox *focalSource_, *boardPlane_;
    QPushButton *horizonButton_, *lensButton_, *boardFootButton_ = nullptr;
    LensPhotosDialog* lensDialog_ = nullptr;
    QProgressDialog* lensProgress_ = nullptr;
    // Rectangle.
    QDoubleSpinBox *rectWidth_, *rectHeight_, *rectFocal_;
    QLabel* cornerCount_;
    // Vanishing lines.
    QDoubleSpinBox *cameraHeight_, *distance_, *vertical_, *vanFocal_;
    QCheckBox* freePrincipal_;
    QLabel* lineCount_;
    QPushButton* detectButton_ = nullptr;
    std::thread detector_;  ///< the line detection in flight, if any

    Target target_ = Target::None;
    QVector<QPointF> corners_;
    QVector<QPair<QPointF, QPointF>> lines_[3];  ///< X, Y, Z
    QVector<QPointF> origin_, distanceEnds_, verticalEnds_;
    QVector<QPointF> horizon_;  ///< the dragged horizon's two ends (render pixels)
    /// The applied board's first inner corner (photo pixels): the origin whose height counts;
    /// and the size of the photo it was found in.
    std::optional<ImagePoint> boardOrigin_;
    QSize boardPhoto_;
    /// The last board applied on a wall: its pose in the board's frame, the up it was levelled
    /// with (camera coordinates), and the camera that made; a new board height re-levels it at
    /// once while the project's camera is still that one.
    struct BoardFit {
        CalibrationResult pose;
        glm::dvec3 up{0.0};
        std::string source;
        CameraSpec applied;
    };
    std::optional<BoardFit> boardFit_;
    int boardHeightKey_ = -1;  ///< merge key of the board height's edits while the field is held
    /// Re-levels the last wall board at the board height field's value (one undo step per stroke).
    void applyBoardHeight();
    /// The board height that puts the clicked point of the board (render pixels) on the floor.
    void boardHeightFromClick(QPointF px);
    std::string photoPath_;
    Image photo_;

    // The lens worker: detection and calibration off the UI thread.
    struct LensJob;
    std::shared_ptr<LensJob> lensJob_;
    std::thread lensWorker_;
};

}  // namespace dp::ui
