#pragma once
#include <QWidget>

class QComboBox;
class QFormLayout;
class QLabel;
class QPushButton;
class QSlider;

namespace dp {
struct PrincipledMaterial;
}

namespace dp::ui {

class Document;
class NumberField;

/// The selected object's material: kind, diffuse colour (colour picker; the principled base
/// colour too), mirror reflectance, glass index of refraction and tint, the principled
/// material's numbers (shown for it only); for a mesh, whether its file's own materials are used
/// (with a note saying what this material then covers). Sliders are live: a stroke is one undo
/// step and renders quick passes until released.
class MaterialPanel : public QWidget {
    Q_OBJECT
public:
    explicit MaterialPanel(Document* doc, QWidget* parent = nullptr);

    QSlider* iorSlider() const { return ior_; }
    QComboBox* sourceBox() const { return source_; }
    QComboBox* kindBox() const { return kind_; }
    /// "Preset...": picking one makes the material that principled preset (material_presets),
    /// as one undo step, and the box goes back to its prompt.
    QComboBox* presetBox() const { return preset_; }
    /// The principled material's fields, in PrincipledField order.
    enum PrincipledField { Metallic, Roughness, Ior, Specular, Transmission, Emission, kPrincipledFields };
    NumberField* principledField(PrincipledField f) const { return principled_[f]; }
    QLabel* sourceNote() const { return sourceNote_; }
    /// Sets the diffuse colour as the colour dialog would (sRGB).
    void setDiffuseColour(const QColor& colour);

Q_SIGNALS:
    void strokeStarted();
    void strokeFinished();

private:
    void refresh();
    QSlider* addSlider(QFormLayout* form, const QString& label, const QString& tip, int lo, int hi,
                       QLabel** value);
    void sliderMoved(QSlider* moved);
    void pickColour(bool tint);
    void addPrincipledFields(QFormLayout* form);
    /// A typed principled value: through Document::tryEdit, as every typed value is.
    void principledEdited(PrincipledField f, double value);

    Document* doc_;
    QFormLayout* form_;
    QComboBox *kind_, *source_, *preset_;
    QLabel* sourceNote_;
    QPushButton *colour_, *tint_;
    QSlider *reflectance_, *ior_;
    QLabel *reflectanceValue_, *iorValue_;
    NumberField* principled_[kPrincipledFields] = {};
    int strokeKey_ = -1;
    bool refreshing_ = false;
};

}  // namespace dp::ui
