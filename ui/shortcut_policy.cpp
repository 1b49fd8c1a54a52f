#include "shortcut_policy.h"

#include <QAbstractSpinBox>
#include <QKeyEvent>
#include <QLineEdit>
#include <QWidget>

namespace dp::ui {

namespace {

bool is_undo_or_redo(const QKeyEvent* k) {
    const QKeyCombination c = k->keyCombination();
    return k->matches(QKeySequence::Undo) || k->matches(QKeySequence::Redo) ||
           c == QKeyCombination(Qt::ControlModifier, Qt::Key_Z) ||
           c == QKeyCombination(Qt::ControlModifier | Qt::ShiftModifier, Qt::Key_Z) ||
           c == QKeyCombination(Qt::ControlModifier, Qt::Key_Y);
}

/// A plain letter that never appears in a number as the fields read them.
bool is_command_letter(const QKeyEvent* k) {
    if (k->modifiers() & ~(Qt::ShiftModifier | Qt::KeypadModifier)) return false;
    const QString t = k->text();
    return t.size() == 1 && t[0].isLetter() && !QStringLiteral("eEnNaAiIfF").contains(t[0]);
}

}  // namespace

void ShortcutPolicy::install(QWidget* root) {
    for (QAbstractSpinBox* f : root->findChildren<QAbstractSpinBox*>()) f->installEventFilter(this);
    for (QLineEdit* f : root->findChildren<QLineEdit*>())
        if (!qobject_cast<QAbstractSpinBox*>(f->parentWidget())) f->installEventFilter(this);
}

bool ShortcutPolicy::eventFilter(QObject* watched, QEvent* event) {
    if (event->type() != QEvent::ShortcutOverride) return false;
    auto* k = static_cast<QKeyEvent*>(event);
    if (is_undo_or_redo(k) || (qobject_cast<QAbstractSpinBox*>(watched) && is_command_letter(k))) {
        // Not accepted: the field does not override the shortcut, so the window's action runs.
        event->ignore();
        return true;
    }
    return false;
}

}  // namespace dp::ui
