#pragma once
#include <QDialog>

class QComboBox;
class QLineEdit;

namespace dp::ui {

/// Asks for the photograph and the light probe of a new project (browse or drop files on it).
class NewProjectDialog : public QDialog {
    Q_OBJECT
public:
    explicit NewProjectDialog(QWidget* parent = nullptr);

    QString photoPath() const;
    QString probePath() const;
    bool mirrorBall() const;
    void setPhotoPath(const QString& path);
    void setProbePath(const QString& path);

protected:
    void dragEnterEvent(QDragEnterEvent*) override;
    void dropEvent(QDropEvent*) override;

private:
    QLineEdit *photo_, *probe_;
    QComboBox* format_;
};

}  // namespace dp::ui
