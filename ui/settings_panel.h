#pragma once
#include <QWidget>

class QSpinBox;

namespace dp::ui {

class Document;
class NumberField;

/// The project's render settings: photons per pass, passes, time budget, radius, seed.
class SettingsPanel : public QWidget {
    Q_OBJECT
public:
    explicit SettingsPanel(Document* doc, QWidget* parent = nullptr);

    QSpinBox* photonsField() const { return photons_; }
    NumberField* radiusField() const { return radius_; }
    /// The studio's noise target (a preference, not part of the project).
    void setNoiseTarget(double relError);

Q_SIGNALS:
    /// The user chose where refinement stops: relative error, 0 = invisible at the display.
    void noiseTargetChanged(double relError);

private:
    void refresh();
    void apply();

    Document* doc_;
    QSpinBox *photons_, *passes_, *seed_;
    NumberField *budget_, *radius_, *noise_;
    bool refreshing_ = false;
};

}  // namespace dp::ui
