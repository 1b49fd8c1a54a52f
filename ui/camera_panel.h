#pragma once
#include <QWidget>

#include "scene/project.h"

class QCheckBox;
class QGroupBox;
class QLabel;

namespace dp::ui {

class Document;
class NumberField;

/// Camera matching. Shows and edits the project camera (look-at: eye, target, field of view;
/// intrinsics: read only) and the overlays that show the match against the photo: the ground
/// grid and the real proxies. The calibration tools (chessboard, known rectangle, vanishing
/// lines) plug into the "Calibrate" group: each produces a CameraSpec and its reprojection
/// error, applied here through one undoable edit (applyCalibration).
class CameraPanel : public QWidget {
    Q_OBJECT
public:
    explicit CameraPanel(Document* doc, QWidget* parent = nullptr);

    QCheckBox* gridBox() const { return grid_; }
    QCheckBox* proxiesBox() const { return proxies_; }
    QCheckBox* outlinesBox() const { return outlines_; }

    /// Puts the calibration tools into the "Calibrate" group, above the error figure.
    void setCalibrationTools(QWidget* tools);
    QLabel* errorLabel() const { return error_; }
    /// Eye x y z, target x y z, vertical field of view.
    NumberField* field(int i) const { return fields_[i]; }

    /// Applies a camera found by a calibration tool and shows its reprojection error (pixels).
    /// The unsaved work is checkpointed first; a camera the core would refuse is not applied
    /// (Document::tryEdit) and false is returned.
    bool applyCalibration(const QString& method, const CameraSpec& camera,
                          double reprojectionErrorPx);

Q_SIGNALS:
    void overlaysChanged();

private:
    void refresh();
    void apply();

    Document* doc_;
    NumberField* fields_[7];  ///< eye xyz, target xyz, vertical field of view
    QLabel *model_, *error_;
    QCheckBox *grid_, *proxies_, *outlines_;
    QGroupBox* calibrate_;
    bool refreshing_ = false;
};

}  // namespace dp::ui
