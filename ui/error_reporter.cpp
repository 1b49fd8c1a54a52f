#include "error_reporter.h"

#include <QApplication>
#include <QMessageBox>

#include <exception>

namespace dp::ui {

void MessageBoxReporter::error(QWidget* parent, const QString& title, const QString& text) {
    QMessageBox::critical(parent, title, text);
}

bool MessageBoxReporter::ask(QWidget* parent, const QString& title, const QString& text) {
    return QMessageBox::question(parent, title, text, QMessageBox::Yes | QMessageBox::No,
                                 QMessageBox::Yes) == QMessageBox::Yes;
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
