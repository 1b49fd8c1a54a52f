#pragma once
#include <QDialog>
#include <QStringList>
#include <functional>
#include <vector>

#include "scene/project.h"
#include "scene/relink.h"

class QLabel;
class QPushButton;

namespace dp::ui {

/// Lists the files a project reads (photo, probe, meshes, textures): what each is, the path the
/// project stores and whether it is there. A missing file is looked for by its name in the
/// project's folder and its subfolders (two levels down), and in the folder of every file
/// located by hand, so locating one file of a moved folder finds the others. Locate... picks a
/// file for any row. Accepting changes nothing by itself: relinked() says what to apply.
class MissingFilesDialog : public QDialog {
    Q_OBJECT
  public:
    /// Picks a file: (parent, caption, folder to start in, the file name looked for) -> the
    /// chosen path, or an empty string when cancelled.
    using Chooser = std::function<QString(QWidget* parent, const QString& caption,
                                          const QString& folder, const QString& name)>;

    explicit MissingFilesDialog(const Project& project, QWidget* parent = nullptr);

    /// Replaces the file dialog Locate... opens (tests, or a caller with its own dialog).
    void setChooser(Chooser chooser) { chooser_ = std::move(chooser); }

    int rowCount() const { return int(rows_.size()); }
    /// The project field the row stands for ("photo.path", "objects[2].shape.path", ...).
    QString field(int row) const;
    /// What the file is, for people ("photo", "mesh of \"teapot\"").
    QString what(int row) const;
    /// The path as the project stores it.
    QString storedPath(int row) const;
    /// The file the row is relinked to (found or located), empty where none is.
    QString newPath(int row) const;
    /// The row's file is missing and nothing was found or located for it yet.
    bool isMissing(int row) const;
    /// Rows whose files are still missing.
    int missingCount() const;
    QPushButton* locateButton(int row) const;

    /// What Locate... does with the chosen file: the row takes `file`, then the rows still missing
    /// are looked for in its folder. False, with the reason shown, for a path that is no file.
    bool locate(int row, const QString& file);

    /// `project` with every row's new path, stored as projects store paths (relative inside
    /// the project's folder, absolute elsewhere: path_for_project). Unchanged rows stay as written.
    Project relinked(const Project& project) const;

  private:
    struct Row {
        InputFile file;
        QString newPath;  ///< absolute; empty: as stored
        bool byHand = false;
        QLabel* status = nullptr;
        QPushButton* locate = nullptr;
    };
    /// Looks for every row still missing in the folders searched (relinked folders first).
    void search();
    void showRow(Row& row);
    void showSummary();
    void chooseFor(int row);

    std::filesystem::path baseDir_;
    std::vector<Row> rows_;
    std::vector<std::filesystem::path> folders_;  ///< searched, in this order
    Chooser chooser_;
    QLabel *summary_ = nullptr, *note_ = nullptr;
};

}  // namespace dp::ui
