#pragma once
#include <QObject>

class QWidget;

namespace dp::ui {

/// Lets the window's shortcuts through the fields that would take them as typing:
/// - Undo and redo (Ctrl+Z, Ctrl+Shift+Z, Ctrl+Y) always undo the document, also while a text or
///   number field has the focus (a half-typed value is dropped: the field shows the document's
///   value after the undo).
/// - In a number field a letter no number contains (G, R, S, X, H, ...) is not typing, so it
///   reaches the window's single-key shortcuts; digits, signs, the decimal point, e/E (exponent)
///   and the letters of "nan" and "inf" stay the field's. Text fields (a name) keep every letter.
class ShortcutPolicy : public QObject {
    Q_OBJECT
public:
    explicit ShortcutPolicy(QObject* parent = nullptr) : QObject(parent) {}
    /// Applies the policy to every number and text field under `root` (call once the panels
    /// are built; dialogs are not included: their fields keep their own keys).
    void install(QWidget* root);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;
};

}  // namespace dp::ui
