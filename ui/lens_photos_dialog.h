#pragma once
#include <QDialog>
#include <QStringList>

class QLabel;
class QLineEdit;
class QListWidget;

namespace dp::ui {

/// The photos of the chessboard that calibrate the lens besides the project's photo: a list
/// filled with Add files... (a file dialog), a typed path and Enter (or Add), or files dropped
/// on it; Remove takes out the selected ones. Calibrate accepts the dialog. It is shown
/// window-modal without blocking (open()), so it keeps its list between uses. Widgets carry
/// object names ("lensPhotoList", "lensPhotoPath", "lensPhotoAdd", "lensPhotoBrowse",
/// "lensPhotoRemove") for tests.
class LensPhotosDialog : public QDialog {
    Q_OBJECT
public:
    explicit LensPhotosDialog(QWidget* parent = nullptr);

    QStringList photos() const;
    /// Appends `paths` to the list, each once.
    void addPhotos(const QStringList& paths);

protected:
    /// Enter in the path field adds the path, and only that: it must not also press Calibrate.
    bool eventFilter(QObject* watched, QEvent* e) override;
    void dragEnterEvent(QDragEnterEvent*) override;
    void dropEvent(QDropEvent*) override;

private:
    void addTyped();
    void updateCount();

    QListWidget* list_;
    QLineEdit* path_;
    QLabel* count_;
};

}  // namespace dp::ui
