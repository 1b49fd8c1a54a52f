#include "autosave.h"

#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSaveFile>
#include <QUuid>

#include "document.h"
#include "project_edit.h"
#include "scene/project_io.h"

namespace dp::ui {

namespace {

constexpr auto kPrefix = "recovery";

/// The note beside a copy: where the project was saved and what its file held. Copies written
/// before copies were per studio (`recovery.json`) have a bare path in `recovery-origin.txt`.
QString notePath(const QString& base) {
    return QFileInfo(base).fileName() == kPrefix ? QFileInfo(base).dir().filePath("recovery-origin.txt")
                                                 : base + ".origin";
}

void readNote(const QString& base, Autosave::Recovered& r) {
    QFile note(notePath(base));
    if (!note.open(QIODevice::ReadOnly)) return;
    const QByteArray bytes = note.read(1 << 20);
    const QJsonObject o = QJsonDocument::fromJson(bytes).object();
    if (o.isEmpty()) {
        r.originalPath = QString::fromUtf8(bytes);
        return;
    }
    r.originalPath = o.value("path").toString();
    r.diskHash = QByteArray::fromHex(o.value("disk_hash").toString().toLatin1());
}

std::optional<Autosave::Recovered> readCopy(const QString& base) {
    if (!QFile::exists(base + ".json")) return std::nullopt;
    Autosave::Recovered r;
    try {
        r.project = load_project((base + ".json").toStdString());
    } catch (const std::exception&) {
        return std::nullopt;
    }
    readNote(base, r);
    if (!r.originalPath.isEmpty())
        r.project.base_dir = std::filesystem::path(r.originalPath.toStdString()).parent_path();
    return r;
}

void removeCopy(const QString& base) {
    QFile::remove(base + ".json");
    QFile::remove(notePath(base));
}

}  // namespace

Autosave::Autosave(Document* doc, const QString& dir, int intervalMs, QObject* parent)
    : QObject(parent),
      doc_(doc),
      dir_(dir),
      id_(QString::number(QCoreApplication::applicationPid()) + "-" +
          QUuid::createUuid().toString(QUuid::Id128).left(8)) {
    QDir().mkpath(dir_);
    // Held while this studio runs: a copy whose lock is free belongs to a studio that is gone.
    lock_ = std::make_unique<QLockFile>(filePath(".lock"));
    lock_->setStaleLockTime(0);  // a long-running studio's lock never turns stale by age
    lock_->tryLock(0);
    connect(doc_, &Document::changed, this, [this] { dirty_ = doc_->isModified(); });
    // Back to the saved state (undo) is not a reason to delete the recovery file: only a save
    // or an explicit discard is (MainWindow).
    connect(doc_, &Document::modifiedChanged, this, [this](bool modified) { dirty_ = modified; });
    connect(doc_, &Document::checkpointRequested, this, [this] { writeNow(); });
    connect(&timer_, &QTimer::timeout, this, [this] { writeNow(); });
    timer_.start(intervalMs);
}

Autosave::~Autosave() = default;  // the lock's destructor releases and removes it

QString Autosave::filePath(const QString& suffix) const {
    return QDir(dir_).filePath(QString("%1-%2%3").arg(kPrefix, id_, suffix));
}

QString Autosave::projectFile() const { return filePath(".json"); }

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
    QSaveFile note(filePath(".origin"));
    if (note.open(QIODevice::WriteOnly)) {
        QJsonObject o;
        o["path"] = doc_->path();
        o["disk_hash"] = QString::fromLatin1(doc_->diskHash().toHex());
        note.write(QJsonDocument(o).toJson(QJsonDocument::Compact));
        note.commit();
    }
    dirty_ = false;
    Q_EMIT written(projectFile());
    return true;
}

void Autosave::clear() { removeCopy(filePath("")); }

std::optional<Autosave::Recovered> Autosave::ownCopy() const { return readCopy(filePath("")); }

std::vector<Autosave::Orphan> Autosave::claimOrphans() const {
    std::vector<Orphan> found;
    const QDir dir(dir_);
    const QStringList copies =
        dir.entryList({QString(kPrefix) + "*.json"}, QDir::Files, QDir::Time);  // newest first
    for (const QString& name : copies) {
        const QString base = dir.filePath(name.chopped(5));
        if (base == filePath("")) continue;
        auto lock = std::make_unique<QLockFile>(base + ".lock");
        lock->setStaleLockTime(0);
        // Fails while the studio that owns the copy runs (it holds the lock), or while another
        // starting studio is offering it.
        if (!lock->tryLock(0)) continue;
        std::optional<Recovered> r = readCopy(base);
        if (!r) continue;  // unreadable: left as it is (the lock is released here)
        found.push_back({std::move(*r), base + ".json",
                         QFileInfo(base + ".json").lastModified(), std::move(lock)});
    }
    // Locks of studios that were killed with nothing unsaved: taken and so removed.
    for (const QString& name : dir.entryList({QString(kPrefix) + "-*.lock"}, QDir::Files)) {
        const QString base = dir.filePath(name.chopped(5));
        if (base == filePath("") || QFile::exists(base + ".json")) continue;
        QLockFile stale(base + ".lock");
        stale.setStaleLockTime(0);
        if (stale.tryLock(0)) stale.unlock();
    }
    return found;
}

bool Autosave::adopt(Orphan& orphan) {
    dirty_ = true;
    if (!writeNow()) return false;
    discard(orphan);
    return true;
}

void Autosave::discard(Orphan& orphan) {
    removeCopy(orphan.file.chopped(5));
    if (orphan.lock) orphan.lock->unlock();
}

}  // namespace dp::ui
