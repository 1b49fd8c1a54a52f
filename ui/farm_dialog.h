#pragma once
#include <QDialog>
#include <QImage>
#include <QProcess>
#include <QString>
#include <functional>
#include <memory>
#include <thread>

class QComboBox;
class QLabel;
class QLineEdit;
class QPlainTextEdit;
class QProgressBar;
class QPushButton;
class QSpinBox;

namespace dp::ui {

class Document;

/// File > Render on Farm...: hands the saved project to `diffphoton-farm` (docs/farm.md) on a
/// Dask scheduler, or on a cluster of this machine's cores when no address is given, as a
/// process of its own; shows its progress shard by shard and its messages, cancels it (as Ctrl-C
/// would: nothing is written), and shows the merged image when it is done. Nothing here waits
/// on the process or on decoding the image. Widgets carry object names ("farmStart") for tests.
class FarmDialog : public QDialog {
    Q_OBJECT
public:
    /// `save` saves the project when it has unsaved edits (false: not saved, nothing is sent).
    FarmDialog(Document* doc, std::function<bool()> save, QWidget* parent = nullptr);
    ~FarmDialog() override;

    /// Starts the render the fields describe; false after saying why in the status line.
    bool start();
    /// Stops a running render; its process exits without writing anything.
    void cancel();
    bool running() const;
    int shardsDone() const { return done_; }
    int shardsTotal() const { return total_; }
    /// The merged image as shown, once it is done and decoded (null before).
    const QImage& preview() const { return preview_; }

Q_SIGNALS:
    /// The render ended: written (and, a moment later, shown), failed or cancelled.
    void ended(bool written);

private:
    void onOutput();
    void onFinished(int code, QProcess::ExitStatus status);
    /// Decodes the written image on a worker, then shows it.
    void showResult(const QString& path);
    void setRunning(bool on);

    Document* doc_;
    std::function<bool()> save_;
    QLineEdit *scheduler_, *output_, *partsDir_;
    QSpinBox *passes_, *shard_;
    QComboBox* mode_;
    QPushButton *start_, *cancel_;
    QProgressBar* progress_;
    QLabel *status_, *previewLabel_;
    QPlainTextEdit* log_;
    QProcess* process_ = nullptr;
    QString pending_;      ///< stderr text not yet ended by a newline
    QString lastError_;    ///< the farm's last "diffphoton-farm: ..." line
    QString writing_;      ///< the output of the render in flight
    bool cancelled_ = false;
    int done_ = 0, total_ = 0;
    QImage preview_;
    std::thread decoder_;
};

/// The diffphoton command line the farm's workers run: $DIFFPHOTON, else the one beside this
/// program, else the build tree's, else `diffphoton` on PATH.
QString diffphoton_binary();

}  // namespace dp::ui
