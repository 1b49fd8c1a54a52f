// File > Render on Farm...: diffphoton-farm as a process of its own (docs/farm.md).
#include "farm_dialog.h"

#include <QApplication>
#include <QComboBox>
#include <QCoreApplication>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QPointer>
#include <QProgressBar>
#include <QPushButton>
#include <QRegularExpression>
#include <QSpinBox>
#include <QStandardPaths>
#include <QTimer>
#include <QVBoxLayout>
#include <csignal>

#include "base/deps_path.h"
#include "display.h"
#include "document.h"
#include "image/image_io.h"

namespace dp::ui {

QString diffphoton_binary() {
    const QString env = qEnvironmentVariable("DIFFPHOTON");
    if (!env.isEmpty()) return env;
    const QString beside = QCoreApplication::applicationDirPath() + "/diffphoton";
    if (QFileInfo(beside).isExecutable()) return beside;
    for (const auto& p : tree_candidates("build/app/diffphoton"))
        if (QFileInfo(QString::fromStdString(p.string())).isExecutable()) return QString::fromStdString(p.string());
    return QStringLiteral("diffphoton");
}

namespace {

/// The farm package's folder in the repository, for a studio run from a build (an installed
/// package needs none); empty where there is none.
QString farm_package_parent() {
    for (const auto& p : tree_candidates("farm/diffphoton_farm/__main__.py"))
        if (QFileInfo::exists(QString::fromStdString(p.string())))
            return QString::fromStdString(p.parent_path().parent_path().string());
    return {};
}

}  // namespace

FarmDialog::FarmDialog(Document* doc, std::function<bool()> save, QWidget* parent)
    : QDialog(parent), doc_(doc), save_(std::move(save)) {
    setWindowTitle(tr("Render on Farm"));
    setObjectName("farmDialog");
    auto* layout = new QVBoxLayout(this);
    auto* form = new QFormLayout;
    scheduler_ = new QLineEdit;
    scheduler_->setObjectName("farmScheduler");
    scheduler_->setPlaceholderText(tr("tcp://host:8786 (empty: this machine's cores)"));
    form->addRow(tr("Scheduler"), scheduler_);
    passes_ = new QSpinBox;
    passes_->setObjectName("farmPasses");
    passes_->setRange(1, 1 << 30);
    passes_->setValue(std::max(256, doc_->project().render.passes));
    form->addRow(tr("Passes"), passes_);
    shard_ = new QSpinBox;
    shard_->setObjectName("farmShard");
    shard_->setRange(1, 1 << 30);
    shard_->setValue(16);
    shard_->setToolTip(tr("Passes a shard: each shard is a process that starts in about half a second, so a shard "
                          "should take far longer than that (docs/farm.md)"));
    form->addRow(tr("Passes a shard"), shard_);
    mode_ = new QComboBox;
    mode_->setObjectName("farmMode");
    mode_->addItems({tr("Shared folder (workers read the project where it is)"),
                     tr("Bundle (the project and its files sent to the workers)")});
    form->addRow(tr("Files"), mode_);
    partsDir_ = new QLineEdit;
    partsDir_->setObjectName("farmPartsDir");
    partsDir_->setPlaceholderText(tr("optional: a shared folder the workers write shards to"));
    form->addRow(tr("Shards folder"), partsDir_);
    output_ = new QLineEdit;
    output_->setObjectName("farmOutput");
    const QFileInfo project(doc_->path());
    output_->setText(project.absoluteDir().filePath(project.completeBaseName() + "-farm.exr"));
    auto* browse = new QPushButton(tr("Browse..."));
    connect(browse, &QPushButton::clicked, this, [this] {
        const QString path = QFileDialog::getSaveFileName(this, tr("Merged image"), output_->text(), tr("EXR (*.exr)"));
        if (!path.isEmpty()) output_->setText(path);
    });
    auto* outRow = new QHBoxLayout;
    outRow->addWidget(output_, 1);
    outRow->addWidget(browse);
    form->addRow(tr("Merged image"), outRow);
    layout->addLayout(form);
    auto* buttons = new QHBoxLayout;
    start_ = new QPushButton(tr("Render"));
    start_->setObjectName("farmStart");
    cancel_ = new QPushButton(tr("Cancel render"));
    cancel_->setObjectName("farmCancel");
    cancel_->setEnabled(false);
    connect(start_, &QPushButton::clicked, this, [this] { start(); });
    connect(cancel_, &QPushButton::clicked, this, [this] { cancel(); });
    buttons->addWidget(start_);
    buttons->addWidget(cancel_);
    layout->addLayout(buttons);
    progress_ = new QProgressBar;
    progress_->setObjectName("farmProgress");
    progress_->setFormat(tr("%v of %m shards"));
    progress_->setValue(0);
    layout->addWidget(progress_);
    status_ = new QLabel;
    status_->setObjectName("farmStatus");
    status_->setWordWrap(true);
    layout->addWidget(status_);
    log_ = new QPlainTextEdit;
    log_->setObjectName("farmLog");
    log_->setReadOnly(true);
    log_->setMaximumBlockCount(2000);
    layout->addWidget(log_, 1);
    previewLabel_ = new QLabel;
    previewLabel_->setObjectName("farmPreview");
    previewLabel_->setAlignment(Qt::AlignCenter);
    layout->addWidget(previewLabel_, 2);
    resize(560, 640);
}

FarmDialog::~FarmDialog() {
    if (running()) {
        process_->disconnect(this);
        ::kill(pid_t(process_->processId()), SIGINT);
        if (!process_->waitForFinished(10000)) process_->kill();
    }
    if (decoder_.joinable()) decoder_.join();
}

bool FarmDialog::running() const { return process_ && process_->state() != QProcess::NotRunning; }

void FarmDialog::setRunning(bool on) {
    start_->setEnabled(!on);
    cancel_->setEnabled(on);
}

bool FarmDialog::start() {
    if (running()) return false;
    // The farm reads the project from its file: what is sent is what is saved.
    if (doc_->path().isEmpty() || doc_->isModified()) {
        if (!save_ || !save_() || doc_->path().isEmpty()) {
            status_->setText(tr("Save the project first: the farm renders the project file."));
            return false;
        }
    }
    QStringList args{"-m", "diffphoton_farm", "render", doc_->path(), "--passes", QString::number(passes_->value()),
                     "--shard", QString::number(shard_->value()), "--binary", diffphoton_binary(),
                     "-o", output_->text()};
    if (!scheduler_->text().trimmed().isEmpty()) args << "--scheduler" << scheduler_->text().trimmed();
    if (mode_->currentIndex() == 1) args << "--bundle";
    if (!partsDir_->text().trimmed().isEmpty()) args << "--parts-dir" << partsDir_->text().trimmed();
    const QString python = QStandardPaths::findExecutable("python3");
    if (python.isEmpty()) {
        status_->setText(tr("No python3 on PATH: the farm runner is a Python program (scripts/install-deps.sh)."));
        return false;
    }
    delete process_;
    process_ = new QProcess(this);
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    if (const QString farm = farm_package_parent(); !farm.isEmpty()) {
        const QString old = env.value("PYTHONPATH");
        env.insert("PYTHONPATH", old.isEmpty() ? farm : farm + ":" + old);
    }
    process_->setProcessEnvironment(env);
    process_->setProcessChannelMode(QProcess::MergedChannels);
    connect(process_, &QProcess::readyRead, this, [this] { onOutput(); });
    connect(process_, &QProcess::finished, this, [this](int code, QProcess::ExitStatus s) { onFinished(code, s); });
    connect(process_, &QProcess::errorOccurred, this, [this](QProcess::ProcessError e) {
        if (e == QProcess::FailedToStart) onFinished(-1, QProcess::CrashExit);
    });
    cancelled_ = false;
    done_ = 0;
    total_ = (passes_->value() + shard_->value() - 1) / shard_->value();
    progress_->setRange(0, total_);
    progress_->setValue(0);
    preview_ = QImage();
    previewLabel_->clear();
    lastError_.clear();
    writing_ = output_->text();
    log_->appendPlainText(python + " " + args.join(' '));
    status_->setText(tr("Starting: %1 shards of %2 passes...").arg(total_).arg(shard_->value()));
    setRunning(true);
    process_->start(python, args);
    return true;
}

void FarmDialog::cancel() {
    if (!running()) return;
    cancelled_ = true;
    status_->setText(tr("Cancelling..."));
    // As Ctrl-C: the farm closes its cluster and writes nothing; killed if it does not stop.
    ::kill(pid_t(process_->processId()), SIGINT);
    QPointer<QProcess> p(process_);
    QTimer::singleShot(10000, this, [p] {
        if (p && p->state() != QProcess::NotRunning) p->kill();
    });
}

void FarmDialog::onOutput() {
    pending_ += QString::fromUtf8(process_->readAll());
    static const QRegularExpression bar(QStringLiteral("shards (\\d+)/(\\d+) .* ([0-9.]+)s"));
    int end;
    while ((end = pending_.indexOf('\n')) >= 0) {
        const QString line = pending_.left(end).trimmed();
        pending_.remove(0, end + 1);
        const QRegularExpressionMatch m = bar.match(line);
        if (m.hasMatch()) {
            done_ = m.captured(1).toInt();
            total_ = m.captured(2).toInt();
            progress_->setRange(0, total_);
            progress_->setValue(done_);
            status_->setText(tr("%1 of %2 shards rendered, %3 s").arg(done_).arg(total_).arg(m.captured(3)));
            continue;
        }
        if (line.startsWith("diffphoton-farm:")) lastError_ = line;
        if (!line.isEmpty()) log_->appendPlainText(line);
    }
}

void FarmDialog::onFinished(int code, QProcess::ExitStatus status) {
    onOutput();
    setRunning(false);
    if (code == 0 && status == QProcess::NormalExit) {
        status_->setText(tr("Written: %1. Decoding it to show...").arg(writing_));
        showResult(writing_);
        return;
    }
    if (cancelled_)
        status_->setText(tr("Cancelled: nothing was written."));
    else if (code == -1)
        status_->setText(tr("The farm runner did not start: %1").arg(process_->errorString()));
    else
        status_->setText(lastError_.isEmpty() ? tr("The farm runner stopped (exit code %1).").arg(code) : lastError_);
    Q_EMIT ended(false);
}

void FarmDialog::showResult(const QString& path) {
    if (decoder_.joinable()) decoder_.join();
    const float exposure = doc_->project().display.exposure;
    QPointer<FarmDialog> self(this);
    decoder_ = std::thread([self, path, exposure] {
        QImage shown;
        QString error;
        try {
            shown = to_display(load_image(path.toStdString(), "--output"), exposure, 1024);
        } catch (const std::exception& e) {
            error = QString::fromUtf8(e.what());
        }
        QMetaObject::invokeMethod(qApp, [self, shown, error, path] {
            if (!self) return;
            self->decoder_.join();
            if (!error.isEmpty()) {
                self->status_->setText(tr("Written: %1, but it cannot be shown: %2").arg(path, error));
            } else {
                self->preview_ = shown;
                self->previewLabel_->setPixmap(QPixmap::fromImage(
                    shown.scaled(self->previewLabel_->size().expandedTo(QSize(64, 64)), Qt::KeepAspectRatio,
                                 Qt::SmoothTransformation)));
                self->status_->setText(tr("Done: %1").arg(path));
            }
            Q_EMIT self->ended(true);
        }, Qt::QueuedConnection);
    });
}

}  // namespace dp::ui
