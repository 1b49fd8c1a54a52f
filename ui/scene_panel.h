#pragma once
#include <QWidget>

class QAction;
class QCheckBox;
class QLineEdit;
class QListWidget;
class QMenu;
class QToolButton;

namespace dp::ui {

class Document;
class NumberField;

/// The virtual objects and lights: a list (objects first, tick to show, untick to hide; then the
/// lights, with their kind's icon), buttons for the add / import / duplicate / delete actions and
/// the Add Light menu, the selected object's or light's name and transform.
class ScenePanel : public QWidget {
    Q_OBJECT
public:
    ScenePanel(Document* doc, const QList<QAction*>& actions, QMenu* lightMenu = nullptr,
               QWidget* parent = nullptr);

    /// Row i < objects.size() is object i, the rows after it the lights in order.
    QListWidget* list() const { return list_; }
    /// The row of light `i` in the list.
    int lightRow(int i) const;
    /// The selected object's or light's name.
    QLineEdit* nameField() const { return name_; }
    /// Opens the Add Light menu (null without one).
    QToolButton* addLightButton() const { return addLight_; }
    /// Translation x y z, rotation x y z (degrees), scale x y z.
    NumberField* transformField(int i) const { return fields_[i]; }
    /// The uniform-scale lock beside the scale fields: when ticked, a scale field scales all
    /// three components by the same factor.
    QCheckBox* uniformScaleBox() const { return uniform_; }

  private:
    void refresh();
    /// Applies field `index` alone: the other components keep their exact values (the fields
    /// show them rounded, and clamped to their ranges); with the uniform lock a scale field
    /// scales all three. A new scale keeps the object's lowest point where it was.
    void applyTransform(int index);
    void applyVisibility(int row, bool visible);
    /// The transform fields applied to the selected light: no snapping and no resting on the
    /// ground (a lamp hangs where it is put).
    void applyLightTransform(int index);
    void rename();

    Document* doc_;
    QListWidget* list_;
    QLineEdit* name_;
    NumberField* fields_[9];
    QCheckBox* uniform_;
    QToolButton* addLight_ = nullptr;
    bool refreshing_ = false;
};

}  // namespace dp::ui
