#include "error_reporter.h"

#include <QApplication>
#include <QMessageBox>
#include <QPushButton>

#include <exception>

namespace dp::ui {

void MessageBoxReporter::error(QWidget* parent, const QString& title, const QString& text) {
    QMessageBox::critical(parent, title, text);
}

bool MessageBoxReporter::ask(QWidget* parent, const QString& title, const QString& text) {
    return QMessageBox::question(parent, title, text, QMessageBox::Yes | QMessageBox::No,
                                 QMessageBox::Yes) == QMessageBox::Yes;
}

ErrorReporter::SaveChoice MessageBoxReporter::askSave(QWidget* parent, const QString& title,
                                                      const QString& text) {
    QMessageBox box(QMessageBox::Warning, title, text,
                    QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, parent);
    box.setObjectName("unsavedChanges");
    box.setDefaultButton(QMessageBox::Save);
    box.setEscapeButton(QMessageBox::Cancel);
    box.exec();
    if (box.clickedButton() == box.button(QMessageBox::Save)) return SaveChoice::Save;
    if (box.clickedButton() == box.button(QMessageBox::Discard)) return SaveChoice::Discard;
    return SaveChoice::Cancel;
}

ErrorReporter::ConflictChoice MessageBoxReporter::askConflict(QWidget* parent, const QString& title,
                                                              const QString& text) {
    QMessageBox box(QMessageBox::Warning, title, text, QMessageBox::NoButton, parent);
    box.setObjectName("changedOnDisk");
    QPushButton* keep = box.addButton(QObject::tr("Keep Mine"), QMessageBox::DestructiveRole);
    QPushButton* take = box.addButton(QObject::tr("Take Theirs"), QMessageBox::ResetRole);
    QPushButton* saveAs = box.addButton(QObject::tr("Save As..."), QMessageBox::AcceptRole);
    QPushButton* cancel = box.addButton(QMessageBox::Cancel);
    // Neither copy is lost by the default: Save As keeps both.
    box.setDefaultButton(saveAs);
    box.setEscapeButton(cancel);
    box.exec();
    if (box.clickedButton() == keep) return ConflictChoice::KeepMine;
    if (box.clickedButton() == take) return ConflictChoice::TakeTheirs;
    if (box.clickedButton() == saveAs) return ConflictChoice::SaveAs;
    return ConflictChoice::Cancel;
}

bool run_reporting_errors(ErrorReporter* reporter, QWidget* parent, const QString& title,
                          const std::function<void()>& work) {
    try {
        work();
        return true;
    } catch (const std::exception& e) {
        QApplication::restoreOverrideCursor();
        reporter->error(parent, title, QString::fromStdString(e.what()));
        return false;
    }
}

}  // namespace dp::ui
