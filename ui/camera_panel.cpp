#include "camera_panel.h"

#include <QCheckBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QVBoxLayout>

#include "document.h"
#include "number_field.h"

namespace dp::ui {

CameraPanel::CameraPanel(Document* doc, QWidget* parent) : QWidget(parent), doc_(doc) {
    auto* layout = new QVBoxLayout(this);
    auto* form = new QFormLayout;
    model_ = new QLabel;
    form->addRow(tr("Model"), model_);
    const char* rows[] = {"Eye", "Target"};
    for (int r = 0; r < 2; ++r) {
        auto* row = new QHBoxLayout;
        for (int c = 0; c < 3; ++c) {
            auto* f = new NumberField;
            f->setRange(-1e4, 1e4);
            f->setDecimals(3);
            f->setSingleStep(0.05);
            f->setKeyboardTracking(false);
            f->setButtonSymbols(QAbstractSpinBox::NoButtons);  // three to a row in a side panel
            f->setMinimumWidth(50);
            f->setToolTip(r == 0 ? tr("Camera position (world units)")
                                 : tr("Point the camera looks at (world units)"));
            fields_[r * 3 + c] = f;
            row->addWidget(f);
        }
        form->addRow(tr(rows[r]), row);
    }
    fields_[6] = new NumberField;
    fields_[6]->setRange(1, 170);
    fields_[6]->setDecimals(2);
    fields_[6]->setKeyboardTracking(false);
    fields_[6]->setToolTip(tr("Vertical field of view in degrees"));
    form->addRow(tr("Field of view"), fields_[6]);
    for (NumberField* f : fields_)
        connect(f, &NumberField::valueChanged, this, [this] { apply(); });
    layout->addLayout(form);

    auto* show = new QGroupBox(tr("Show over the photo"));
    auto* showLayout = new QVBoxLayout(show);
    grid_ = new QCheckBox(tr("Ground grid (0.5 m)"));
    grid_->setToolTip(
        tr("The y = 0 plane as the camera sees it: it should lie on the photo's floor"));
    proxies_ = new QCheckBox(tr("Real proxies (wireframe)"));
    proxies_->setToolTip(tr("The real geometry standing in for the photo's surfaces"));
    outlines_ = new QCheckBox(tr("Object outlines"));
    outlines_->setToolTip(tr("Bounding spheres of the virtual objects and the gizmo"));
    for (QCheckBox* b : {grid_, proxies_, outlines_}) {
        b->setChecked(true);
        showLayout->addWidget(b);
        connect(b, &QCheckBox::toggled, this, [this] { Q_EMIT overlaysChanged(); });
    }
    layout->addWidget(show);

    calibrate_ = new QGroupBox(tr("Calibrate"));
    calibrate_->setToolTip(tr("Camera calibration from the photo"));
    auto* calLayout = new QVBoxLayout(calibrate_);
    error_ = new QLabel(tr("Reprojection error: -"));
    error_->setToolTip(tr("RMS distance in pixels between the detected and reprojected points"));
    calLayout->addWidget(error_);
    layout->addWidget(calibrate_);
    layout->addStretch(1);

    connect(doc_, &Document::changed, this, [this] { refresh(); });
    refresh();
}

void CameraPanel::refresh() {
    refreshing_ = true;
    const CameraSpec& c = doc_->project().camera;
    const bool lookAt = c.model == CameraSpec::Model::LookAt;
    model_->setText(lookAt ? tr("look-at") : tr("intrinsics + pose (from calibration)"));
    const float values[7] = {c.eye.x,    c.eye.y,    c.eye.z,   c.target.x,
                             c.target.y, c.target.z, c.vfov_deg};
    for (int i = 0; i < 7; ++i) {
        fields_[i]->setEnabled(lookAt);
        fields_[i]->setValue(values[i]);
    }
    refreshing_ = false;
}

void CameraPanel::apply() {
    if (refreshing_) return;
    Project p = doc_->project();
    if (p.camera.model != CameraSpec::Model::LookAt) return;
    for (int i = 0; i < 3; ++i) {
        p.camera.eye[i] = float(fields_[i]->value());
        p.camera.target[i] = float(fields_[3 + i]->value());
    }
    p.camera.vfov_deg = float(fields_[6]->value());
    doc_->tryEdit(tr("Adjust camera"), p);
}

void CameraPanel::setCalibrationTools(QWidget* tools) {
    auto* box = static_cast<QVBoxLayout*>(calibrate_->layout());
    box->insertWidget(0, tools);
}

bool CameraPanel::applyCalibration(const QString& method, const CameraSpec& camera,
                                   double reprojectionErrorPx) {
    doc_->checkpoint();
    Project p = doc_->project();
    p.camera = camera;
    if (!doc_->tryEdit(tr("Calibrate camera (%1)").arg(method), p)) return false;
    error_->setText(tr("Reprojection error: %1 px").arg(reprojectionErrorPx, 0, 'f', 2));
    return true;
}

}  // namespace dp::ui
