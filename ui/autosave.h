#pragma once
#include <QByteArray>
#include <QDateTime>
#include <QLockFile>
#include <QObject>
#include <QString>
#include <QTimer>
#include <memory>
#include <optional>
#include <vector>

#include "scene/project.h"

namespace dp::ui {

class Document;

/// Writes unsaved work to a recovery file every few seconds, so a crash loses little. Each
/// studio (each Autosave) has its own copy in the shared folder, `recovery-<id>.json`, next to
/// a note of where the project was saved last and a lock the studio holds while it runs: two
/// studios never overwrite or delete each other's copy, and a copy whose lock is stale (its
/// studio was killed or crashed) is what the next start offers (orphans). The window removes
/// its own copy (clear) only once nothing unsaved is lost: after a save, an explicit Discard, or
/// a close or replacement of a document without unsaved changes. checkpoint requests
/// (Document::checkpoint) write at once.
class Autosave : public QObject {
    Q_OBJECT
public:
    Autosave(Document* doc, const QString& dir, int intervalMs, QObject* parent = nullptr);
    ~Autosave() override;

    /// This studio's recovery file.
    QString projectFile() const;
    /// Writes now if the document has unsaved changes since the last write; true if written.
    bool writeNow();
    /// Removes this studio's recovery copy (after a save or a clean close); other studios'
    /// copies stay.
    void clear();

    struct Recovered {
        Project project;
        QString originalPath;  ///< where the project was saved before ("" if never)
        /// The project file's contents hash when the studio read or wrote it (Document::diskHash;
        /// empty if unknown), so a save of the recovered work can tell whether the file changed.
        QByteArray diskHash;
    };
    /// This studio's copy as it is on disk, if there is one (what a crash now would leave).
    std::optional<Recovered> ownCopy() const;

    /// A copy left by a studio that stopped without a clean quit. Its lock is held while this
    /// object lives, so no other studio offers it at the same time.
    struct Orphan {
        Recovered recovered;
        QString file;
        QDateTime written;
        std::unique_ptr<QLockFile> lock;
    };
    /// Claims every readable copy whose studio is no longer running, newest first. Copies of
    /// running studios (this one included) are never listed; unreadable ones are left alone.
    std::vector<Orphan> claimOrphans() const;
    /// Makes `orphan` this studio's copy: the document (already reset to it) is written to this
    /// studio's file, and only then is the orphan removed. False, keeping the orphan, if the
    /// write fails.
    bool adopt(Orphan& orphan);
    /// Deletes a claimed copy the user declined.
    static void discard(Orphan& orphan);

Q_SIGNALS:
    void written(const QString& file);

private:
    QString filePath(const QString& suffix) const;

    Document* doc_;
    QString dir_;
    QString id_;
    std::unique_ptr<QLockFile> lock_;
    QTimer timer_;
    bool dirty_ = false;
};

}  // namespace dp::ui
