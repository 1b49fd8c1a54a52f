#pragma once
#include <QByteArray>
#include <QObject>
#include <QString>
#include <QUndoStack>

#include "project_edit.h"
#include "assets/asset_library.h"
#include "scene/project.h"

namespace dp::ui {

/// The open project: its file, its undo history and the selection (one object or one light).
/// Every edit goes through edit(), so it can be undone and the renderer hears about it.
class Document : public QObject {
    Q_OBJECT
public:
    explicit Document(QObject* parent = nullptr);

    const Project& project() const { return project_; }
    /// The files the project names, decoded once and shared by the renderer and every panel.
    AssetLibrary& assets() const { return *assets_; }
    const std::shared_ptr<AssetLibrary>& assetLibrary() const { return assets_; }
    const QString& path() const { return path_; }
    QUndoStack* undoStack() { return &stack_; }
    bool isModified() const { return !stack_.isClean(); }
    bool isOpen() const { return open_; }
    /// A hash of what the project file held when this document last read or wrote it (empty:
    /// never read or written), so a save can tell that another studio or program changed it.
    const QByteArray& diskHash() const { return diskHash_; }
    void setDiskHash(const QByteArray& hash) { diskHash_ = hash; }
    /// The hash diskHash compares with: of the file at `path` as it is now; empty when there is
    /// no regular file there, a fixed non-empty value when it cannot be read.
    static QByteArray hashOnDisk(const QString& path);

    /// Replaces the whole project (open, new, recover): clears the undo history.
    void reset(const Project& project, const QString& path, bool modified = false);
    void setPath(const QString& path);
    void markSaved() { stack_.setClean(); }

    /// Records an edit as one undo step. Consecutive edits with the same non-negative
    /// `mergeKey` (a drag, a slider stroke) fold into one step.
    void edit(const QString& text, const Project& after, int mergeKey = -1);
    /// edit() for a value the user typed: `after` is first put through the core's checks
    /// (scene_problem). A project the core would refuse is not applied: editRefused() says why
    /// and the views show the project as it stays. A project that was refused already (a file
    /// that cannot be read) does not hold up edits that do not make it worse. Returns whether
    /// the edit was applied.
    bool tryEdit(const QString& text, const Project& after, int mergeKey = -1);
    /// Why tryEdit would refuse `after` (empty: it would apply it).
    QString editProblem(const Project& after) const;
    /// Before an operation that might not come back (a mesh import, a calibration): asks for
    /// the unsaved work to be written to the recovery file now (the autosave listens).
    void checkpoint() { Q_EMIT checkpointRequested(); }
    /// A merge key no earlier edit used: one per drag or slider stroke.
    int newMergeKey() { return nextKey_++; }

    /// The selected object (-1: none, or a light is selected).
    int selected() const { return selected_; }
    /// Selects object `index` (-1: none); the light selection is cleared.
    void select(int index);
    /// The selected light, an index into project().lights (-1: none, or an object is selected).
    int selectedLight() const { return selectedLight_; }
    /// Selects light `index` (-1: none); the object selection is cleared.
    void selectLight(int index);

    /// Sets the project without recording (used by the undo commands).
    void apply(const Project& project);

Q_SIGNALS:
    /// The project changed; `change` says how much the renderer must redo.
    void changed(dp::Change change);
    /// A new project was opened or created (the views reload everything).
    void reloaded();
    void pathChanged(const QString& path);
    /// The object or light selection changed; `index` is the selected object (-1 for none or a
    /// light: selectedLight says which).
    void selectionChanged(int index);
    void modifiedChanged(bool modified);
    /// A typed edit was refused; `reason` is the core's message.
    void editRefused(const QString& reason);
    void checkpointRequested();

private:
    std::shared_ptr<AssetLibrary> assets_ = std::make_shared<AssetLibrary>();
    Project project_;
    QString path_;
    QByteArray diskHash_;
    QUndoStack stack_;
    int selected_ = -1;
    int selectedLight_ = -1;
    int nextKey_ = 1;
    bool open_ = false;
};

}  // namespace dp::ui
