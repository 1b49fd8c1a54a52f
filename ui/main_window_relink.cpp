// MainWindow: files that have moved. The render waits while any is missing; the Missing Files
// dialog relinks them.
#include <QLabel>
#include <QToolButton>

#include "denoise_worker.h"
#include "document.h"
#include "main_window.h"
#include "missing_files_dialog.h"
#include "render_controller.h"
#include "scene/relink.h"

namespace dp::ui {

MissingFilesDialog* MainWindow::relinkDialog() const {
    return relinkDialog_;
}

QStringList MainWindow::missingFiles() const {
    QStringList fields;
    if (!doc_->isOpen()) return fields;
    for (const InputFile& f : missing_inputs(doc_->project()))
        fields << QString::fromStdString(f.ref.field);
    return fields;
}

void MainWindow::relinkFiles() {
    if (!doc_->isOpen()) return;
    // One at a time; one closed a moment ago may still wait for its deletion.
    if (relinkDialog_ && relinkDialog_->isVisible()) {
        relinkDialog_->raise();
        relinkDialog_->activateWindow();
        return;
    }
    auto* dialog = new MissingFilesDialog(doc_->project(), this);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    relinkDialog_ = dialog;
    connect(dialog, &QDialog::accepted, this, [this, dialog] {
        // The window was blocked while the dialog showed: the project is still the one listed.
        doc_->edit(tr("Relink files"), dialog->relinked(doc_->project()));
        showMissingFiles();
    });
    // Another project replaces the one listed: its rows would name the wrong files.
    connect(doc_, &Document::reloaded, dialog, &QDialog::reject);
    dialog->open();
}

bool MainWindow::showMissingFiles() {
    const std::vector<InputFile> missing =
        doc_->isOpen() ? missing_inputs(doc_->project()) : std::vector<InputFile>{};
    missing_->setVisible(!missing.empty());
    if (missing.empty()) return false;
    QStringList lines;
    for (const InputFile& f : missing)
        lines << QString::fromStdString(f.ref.what + ": " + f.resolved.string());
    const int n = int(missing.size());
    missing_->setText(n == 1 ? tr("⚠ 1 missing file") : tr("⚠ %1 missing files").arg(n));
    missing_->setToolTip(lines.join("\n") + "\n" + tr("Click to relink them"));
    status_->setText(
        (n == 1 ? tr("Waiting for 1 missing file") : tr("Waiting for %1 missing files").arg(n)) +
        tr(": File > Relink Files..."));
    return true;
}

namespace {

/// The paths the project stores, in for_each_input's order.
std::vector<std::string> stored_paths(const Project& project) {
    std::vector<std::string> paths;
    for_each_input(project,
                   [&](const InputRef&, const std::string& path) { paths.push_back(path); });
    return paths;
}

}  // namespace

bool MainWindow::requestRender(bool interactive) {
    if (!doc_->isOpen()) return false;
    std::vector<std::string> paths = stored_paths(doc_->project());
    if (showMissingFiles()) {
        // Nothing of the project as it is can be rendered; what runs is of an earlier state.
        renderer_->stop();
        // Gone from paths that rendered a moment ago: moved or deleted behind the studio's back,
        // and the dialog is offered (once: an undo back to old paths only shows the status).
        const bool vanished = !waiting_ && paths == renderedPaths_;
        waiting_ = true;
        if (vanished) relinkFiles();
        return false;
    }
    waiting_ = false;
    renderedPaths_ = std::move(paths);
    // A denoise of the state before the edit would only take the cores from its quick pass.
    denoiser_->dropStale();
    renderer_->request(doc_->project(), interactive);
    return true;
}

}  // namespace dp::ui
