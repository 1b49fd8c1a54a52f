#pragma once
#include <QString>
#include <QStringList>

#include <functional>

class QWidget;

namespace dp::ui {

/// How the studio tells the user about errors and asks yes/no questions. The default shows
/// message boxes; tests install one that records instead of blocking on a modal dialog.
class ErrorReporter {
public:
    virtual ~ErrorReporter() = default;
    virtual void error(QWidget* parent, const QString& title, const QString& text) = 0;
    /// Returns true for "yes".
    virtual bool ask(QWidget* parent, const QString& title, const QString& text) = 0;
    enum class SaveChoice { Save, Discard, Cancel };
    /// Save / Discard / Cancel for unsaved changes. Closing the question (Esc) is Cancel:
    /// nothing is ever discarded without the user saying so.
    virtual SaveChoice askSave(QWidget* parent, const QString& title, const QString& text) = 0;
    /// The file about to be saved changed on disk since it was read: overwrite it with this
    /// document, load the version on disk, save this one elsewhere, or do nothing (Esc).
    enum class ConflictChoice { KeepMine, TakeTheirs, SaveAs, Cancel };
    virtual ConflictChoice askConflict(QWidget* parent, const QString& title, const QString& text) = 0;
};

/// QMessageBox::critical / QMessageBox::question.
class MessageBoxReporter : public ErrorReporter {
public:
    void error(QWidget* parent, const QString& title, const QString& text) override;
    bool ask(QWidget* parent, const QString& title, const QString& text) override;
    SaveChoice askSave(QWidget* parent, const QString& title, const QString& text) override;
    ConflictChoice askConflict(QWidget* parent, const QString& title, const QString& text) override;
};

/// Records messages and answers questions with a fixed reply (tests, headless runs): "yes" is
/// Save and "no" is Discard when asked about unsaved changes.
class RecordingReporter : public ErrorReporter {
public:
    explicit RecordingReporter(bool answer = true) : answer_(answer) {}
    SaveChoice askSave(QWidget*, const QString& title, const QString& text) override {
        questions << title + ": " + text;
        return answer_ ? SaveChoice::Save : SaveChoice::Discard;
    }
    void error(QWidget*, const QString& title, const QString& text) override {
        errors << title + ": " + text;
    }
    bool ask(QWidget*, const QString& title, const QString& text) override {
        questions << title + ": " + text;
        return answer_;
    }
    ConflictChoice askConflict(QWidget*, const QString& title, const QString& text) override {
        questions << title + ": " + text;
        return conflictAnswer;
    }
    QStringList errors, questions;
    ConflictChoice conflictAnswer = ConflictChoice::Cancel;

private:
    bool answer_;
};

/// Runs `work`; an exception it throws becomes one error message under `title` (any override
/// cursor is restored first). Returns true if `work` finished.
bool run_reporting_errors(ErrorReporter* reporter, QWidget* parent, const QString& title,
                          const std::function<void()>& work);

}  // namespace dp::ui
