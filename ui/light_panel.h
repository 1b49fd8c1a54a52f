#pragma once
#include <QWidget>

class QCheckBox;
class QComboBox;
class QFormLayout;
class QLabel;
class QPushButton;
class QSlider;

namespace dp::ui {

class Document;
class NumberField;

/// The selected light: kind, colour (colour picker), power in watts (a field and a slider spread
/// over the decades), a spot's cone angle and soft edge, an area light's size and whether the
/// camera sees its face. Only the rows of the light's kind show. Typed values and picks are one
/// undo step each; a slider stroke is one step and renders quick passes until released.
class LightPanel : public QWidget {
    Q_OBJECT
public:
    explicit LightPanel(Document* doc, QWidget* parent = nullptr);

    QComboBox* kindBox() const { return kind_; }
    QPushButton* colourButton() const { return colour_; }
    NumberField* powerField() const { return power_; }
    /// Power on a log scale: slider value v is 10^(v / 100 - 1) W (0.1 W to 10 MW).
    QSlider* powerSlider() const { return powerSlider_; }
    NumberField* spotAngleField() const { return angle_; }
    QSlider* spotAngleSlider() const { return angleSlider_; }
    /// The spot's soft edge in percent of the cone.
    QSlider* spotBlendSlider() const { return blend_; }
    /// Rectangle: width (x) and depth (z); disk: the diameter is sizeField(0).
    NumberField* sizeField(int i) const { return size_[i]; }
    QCheckBox* visibleBox() const { return visible_; }
    /// Sets the colour as the colour dialog would (sRGB), as one undo step.
    void setColour(const QColor& colour);

    /// The slider position of a power (W), and the power of a slider position (three
    /// significant digits, so a dragged power reads cleanly).
    static int powerToSlider(double watts);
    static double sliderToPower(int position);

Q_SIGNALS:
    void strokeStarted();
    void strokeFinished();

private:
    void refresh();
    /// A slider in a row of its own widget (so the row can be hidden), with `beside` after it.
    QSlider* addSliderRow(const QString& label, const QString& tip, int lo, int hi, QWidget* beside);
    void sliderMoved(QSlider* moved);
    /// A typed value: through Document::tryEdit, as every typed value is.
    void fieldEdited(NumberField* field);
    /// Applies `change` to a copy of the selected light and records it.
    template <class F>
    void editLight(const QString& text, F change, int mergeKey = -1, bool typed = false);

    Document* doc_;
    QFormLayout* form_;
    QComboBox* kind_;
    QPushButton* colour_;
    NumberField *power_, *angle_;
    NumberField* size_[2];
    QSlider *powerSlider_, *angleSlider_, *blend_;
    QLabel* blendValue_;
    QCheckBox* visible_;
    int strokeKey_ = -1;
    bool refreshing_ = false;
};

}  // namespace dp::ui
