#pragma once
#include <QObject>
#include <QString>
#include <QTimer>
#include <optional>

#include "scene/project.h"

namespace dp::ui {

class Document;

/// Writes unsaved work to a recovery file every few seconds, so a crash loses little. The file
/// holds the project with absolute paths, next to a note of where it was saved last; a clean
/// close removes both. The window removes them (clear) only once nothing unsaved is lost: after
/// a save, an explicit Discard, or a close or replacement of a document without unsaved
/// changes. checkpoint requests (Document::checkpoint) write at once.
class Autosave : public QObject {
    Q_OBJECT
public:
    Autosave(Document* doc, const QString& dir, int intervalMs, QObject* parent = nullptr);

    QString projectFile() const;
    /// Writes now if the document has unsaved changes since the last write; true if written.
    bool writeNow();
    /// Removes the recovery files (after a save or a clean close).
    void clear();

    struct Recovered {
        Project project;
        QString originalPath;  ///< where the project was saved before ("" if never)
    };
    /// What a previous run left behind, if anything readable.
    std::optional<Recovered> pending() const;

Q_SIGNALS:
    void written(const QString& file);

private:
    Document* doc_;
    QString dir_;
    QTimer timer_;
    bool dirty_ = false;
};

}  // namespace dp::ui
