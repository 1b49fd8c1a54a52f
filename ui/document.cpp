#include "document.h"

#include <QCryptographicHash>
#include <QFile>
#include <QFileInfo>
#include <QUndoCommand>

#include "scene_check.h"

namespace dp::ui {

namespace {

/// An edit as two snapshots of the project: projects are small, and a snapshot undoes any edit.
class EditCommand : public QUndoCommand {
public:
    EditCommand(Document* doc, const QString& text, Project before, Project after, int key)
        : QUndoCommand(text),
          doc_(doc),
          before_(std::move(before)),
          after_(std::move(after)),
          key_(key) {}

    void undo() override { doc_->apply(before_); }
    void redo() override { doc_->apply(after_); }
    int id() const override { return key_ >= 0 ? 1 : -1; }
    bool mergeWith(const QUndoCommand* other) override {
        auto* o = static_cast<const EditCommand*>(other);
        if (o->key_ != key_) return false;
        after_ = o->after_;
        if (after_ == before_) setObsolete(true);  // a cancelled drag leaves no step behind
        return true;
    }

private:
    Document* doc_;
    Project before_, after_;
    int key_;
};

}  // namespace

Document::Document(QObject* parent) : QObject(parent) {
    connect(&stack_, &QUndoStack::cleanChanged, this,
            [this](bool clean) { Q_EMIT modifiedChanged(!clean); });
}

QByteArray Document::hashOnDisk(const QString& path) {
    const QFileInfo info(path);
    if (!info.exists() || !info.isFile()) return {};
    // Larger than any project file the reader takes: certainly not what was read.
    if (info.size() > (64 << 20)) return QByteArrayLiteral("too large");
    QFile f(path);
    QCryptographicHash hash(QCryptographicHash::Sha256);
    if (!f.open(QIODevice::ReadOnly) || !hash.addData(&f)) return QByteArrayLiteral("unreadable");
    return hash.result();
}

void Document::reset(const Project& project, const QString& path, bool modified) {
    stack_.clear();
    diskHash_.clear();  // the caller sets it where it read the file
    project_ = project;
    open_ = true;
    selected_ = -1;
    selectedLight_ = -1;
    setPath(path);
    if (modified) {
        // A recovered project is unsaved work: mark it so, with nothing to undo.
        stack_.resetClean();
    }
    Q_EMIT reloaded();
    Q_EMIT changed(Change::Assets);
    Q_EMIT selectionChanged(selected_);
    Q_EMIT modifiedChanged(isModified());
}

void Document::setPath(const QString& path) {
    if (path == path_) return;
    path_ = path;
    Q_EMIT pathChanged(path_);
}

void Document::edit(const QString& text, const Project& after, int mergeKey) {
    if (after == project_ && after.base_dir == project_.base_dir) return;
    stack_.push(new EditCommand(this, text, project_, after, mergeKey));
}

QString Document::editProblem(const Project& after) const {
    if (!open_) return tr("no project is open");
    const QString why = scene_problem(*assets_, after);
    // Refused already (a file that cannot be read): the edit does not make it worse.
    if (why.isEmpty() || !scene_problem(*assets_, project_).isEmpty()) return {};
    return why;
}

bool Document::tryEdit(const QString& text, const Project& after, int mergeKey) {
    if (!open_) return false;
    if (const QString why = editProblem(after); !why.isEmpty()) {
        Q_EMIT editRefused(why);
        Q_EMIT changed(Change::None);  // the fields show the project's values again
        return false;
    }
    edit(text, after, mergeKey);
    return true;
}

void Document::apply(const Project& project) {
    const Change change = classify(project_, project);
    project_ = project;
    if (selected_ >= int(project_.objects.size())) select(-1);  // e.g. an "add" undone
    if (selectedLight_ >= int(project_.lights.size())) selectLight(-1);
    Q_EMIT changed(change);
}

void Document::select(int index) {
    if (index < -1 || index >= int(project_.objects.size())) index = -1;
    if (index == selected_ && (index >= 0 || selectedLight_ < 0)) return;
    selected_ = index;
    selectedLight_ = -1;
    Q_EMIT selectionChanged(selected_);
}

void Document::selectLight(int index) {
    if (index < -1 || index >= int(project_.lights.size())) index = -1;
    if (index == selectedLight_ && (index >= 0 || selected_ < 0)) return;
    selectedLight_ = index;
    selected_ = -1;
    Q_EMIT selectionChanged(selected_);
}

}  // namespace dp::ui
