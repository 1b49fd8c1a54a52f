#pragma once
#include <QWidget>

class QAction;
class QDoubleSpinBox;
class QLineEdit;
class QListWidget;

namespace dp::ui {

class Document;

/// The virtual objects: a list (tick to show, untick to hide), buttons for the add / import /
/// duplicate / delete actions, the selected object's name and transform.
class ScenePanel : public QWidget {
    Q_OBJECT
public:
    ScenePanel(Document* doc, const QList<QAction*>& actions, QWidget* parent = nullptr);

    QListWidget* list() const { return list_; }
    /// Translation x y z, rotation x y z (degrees), scale x y z.
    QDoubleSpinBox* transformField(int i) const { return fields_[i]; }

private:
    void refresh();
    void applyTransform();
    void applyVisibility(int row, bool visible);

    Document* doc_;
    QListWidget* list_;
    QLineEdit* name_;
    QDoubleSpinBox* fields_[9];
    bool refreshing_ = false;
};

}  // namespace dp::ui
