#pragma once
#include <QWidget>

class QAction;
class QCheckBox;
class QLineEdit;
class QListWidget;

namespace dp::ui {

class Document;
class NumberField;

/// The virtual objects: a list (tick to show, untick to hide), buttons for the add / import /
/// duplicate / delete actions, the selected object's name and transform.
class ScenePanel : public QWidget {
    Q_OBJECT
public:
    ScenePanel(Document* doc, const QList<QAction*>& actions, QWidget* parent = nullptr);

    QListWidget* list() const { return list_; }
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

    Document* doc_;
    QListWidget* list_;
    QLineEdit* name_;
    NumberField* fields_[9];
    QCheckBox* uniform_;
    bool refreshing_ = false;
};

}  // namespace dp::ui
