#pragma once
#include <QWidget>

class QComboBox;
class QFormLayout;
class QLabel;
class QPushButton;
class QSlider;
class QToolButton;

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
    enum PrincipledField { Metallic, Roughness, Ior, Specular, Transmission, Emission, NormalStrength,
                           kPrincipledFields };
    NumberField* principledField(PrincipledField f) const { return principled_[f]; }
    /// The texture slots: the base colour's (diffuse and principled), the principled material's
    /// metallic-roughness texture and normal map. A slot's button names its image and opens a
    /// file dialog to choose one; its clear button empties the slot. Each is one undo step.
    enum TextureSlot { BaseColourMap, MetallicRoughnessMap, NormalMap, kTextureSlots };
    QPushButton* textureButton(TextureSlot s) const { return textureButtons_[s]; }
    QToolButton* textureClear(TextureSlot s) const { return textureClears_[s]; }
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
    void addTextureSlots(QFormLayout* form);
    /// Sets slot `s` of the selected object's material to the image at `path` ("" clears it).
    void setTexture(TextureSlot s, const QString& path);
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
    QPushButton* textureButtons_[kTextureSlots] = {};
    QToolButton* textureClears_[kTextureSlots] = {};
    QWidget* textureRows_[kTextureSlots] = {};
    int strokeKey_ = -1;
    bool refreshing_ = false;
};

}  // namespace dp::ui
