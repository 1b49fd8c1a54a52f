#include "autosave.h"

#include <QDir>
#include <QFile>
#include <QSaveFile>

#include "document.h"
#include "project_edit.h"
#include "scene/project_io.h"

namespace dp::ui {

Autosave::Autosave(Document* doc, const QString& dir, int intervalMs, QObject* parent)
    : QObject(parent), doc_(doc), dir_(dir) {
    connect(doc_, &Document::changed, this, [this] { dirty_ = doc_->isModified(); });
    // Back to the saved state (undo) is not a reason to delete the recovery file: only a save
    // or an explicit discard is (MainWindow).
    connect(doc_, &Document::modifiedChanged, this, [this](bool modified) { dirty_ = modified; });
    connect(doc_, &Document::checkpointRequested, this, [this] { writeNow(); });
    connect(&timer_, &QTimer::timeout, this, [this] { writeNow(); });
    timer_.start(intervalMs);
}

QString Autosave::projectFile() const {
    return QDir(dir_).filePath(QStringLiteral("recovery.json"));
}

bool Autosave::writeNow() {
    if (!dirty_ || !doc_->isOpen()) return false;
    QDir().mkpath(dir_);
    // Written beside and renamed over, so a crash while writing keeps the previous copy.
    const QString tmp = projectFile() + QStringLiteral(".tmp");
    try {
        save_project(with_absolute_paths(doc_->project()), tmp.toStdString());
    } catch (const std::exception&) {
        return false;  // retried at the next tick
    }
    QFile::remove(projectFile());
    if (!QFile::rename(tmp, projectFile())) return false;
    QSaveFile note(QDir(dir_).filePath(QStringLiteral("recovery-origin.txt")));
    if (note.open(QIODevice::WriteOnly)) {
        note.write(doc_->path().toUtf8());
        note.commit();
    }
    dirty_ = false;
    Q_EMIT written(projectFile());
    return true;
}

void Autosave::clear() {
    QFile::remove(projectFile());
    QFile::remove(QDir(dir_).filePath(QStringLiteral("recovery-origin.txt")));
}

std::optional<Autosave::Recovered> Autosave::pending() const {
    if (!QFile::exists(projectFile())) return std::nullopt;
    Recovered r;
    try {
        r.project = load_project(projectFile().toStdString());
    } catch (const std::exception&) {
        return std::nullopt;
    }
    QFile note(QDir(dir_).filePath(QStringLiteral("recovery-origin.txt")));
    if (note.open(QIODevice::ReadOnly)) r.originalPath = QString::fromUtf8(note.readAll());
    if (!r.originalPath.isEmpty())
        r.project.base_dir = std::filesystem::path(r.originalPath.toStdString()).parent_path();
    return r;
}

}  // namespace dp::ui
