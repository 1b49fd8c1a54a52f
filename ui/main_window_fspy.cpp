// MainWindow: importing fSpy's camera (File > Import fSpy..., or a .fspy dropped on the window).
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QStatusBar>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "assets/asset_library.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "calibration/fspy.h"
#include "document.h"
#include "main_window.h"

namespace dp::ui {

namespace {

namespace fs = std::filesystem;

bool same_bytes(const fs::path& file, const std::vector<uint8_t>& bytes) {
    std::error_code ec;
    if (fs::file_size(file, ec) != bytes.size() || ec) return false;
    std::ifstream in(file, std::ios::binary);
    return std::equal(bytes.begin(), bytes.end(), std::istreambuf_iterator<char>(in),
                      [](uint8_t a, char b) { return a == uint8_t(b); });
}

/// Writes the fSpy file's embedded photo into `folder` as <fSpy file's name><extension>, or
/// finds it there already; a different file of that name is kept (the photo gets "-2", "-3"...).
QString write_embedded_photo(const FspyImport& f, const QString& fspy, const QString& folder) {
    const std::string source = fspy.toStdString();
    if (f.from_json_export)
        throw InputError(source, "",
                         "fSpy's exported camera parameters hold no photo: open the photo's "
                         "project first, or import the .fspy project");
    if (f.image.empty()) throw InputError(source, "", "the fSpy project holds no photo");
    if (f.image_extension.empty())
        throw InputError(source, "", "the fSpy project's photo is in an unknown format");
    const fs::path dir = folder.toStdString();
    const std::string stem = QFileInfo(fspy).completeBaseName().toStdString();
    for (int n = 1; n < 1000; ++n) {
        const fs::path file = dir / (stem + (n > 1 ? "-" + std::to_string(n) : "") + f.image_extension);
        std::error_code ec;
        if (fs::exists(file, ec)) {
            if (same_bytes(file, f.image)) return QString::fromStdString(file.string());
            continue;
        }
        try {
            write_file_atomically(file.string(), std::string(f.image.begin(), f.image.end()));
        } catch (const std::runtime_error& e) {
            throw InputError(file.string(), "", e.what());
        }
        return QString::fromStdString(file.string());
    }
    throw InputError(source, "", "no free name for its photo in " + dir.string());
}

}  // namespace

bool MainWindow::importFspy(const QString& path, const QString& probe) {
    FspyImport f;
    try {
        f = read_fspy(path.toStdString());
    } catch (const std::exception& e) {
        error(tr("Cannot import fSpy camera"), QString::fromUtf8(e.what()));
        return false;
    }
    if (!doc_->isOpen()) {
        // A new project on the fSpy photo: written next to the .fspy, as there is no project
        // folder yet. Without a probe the New Project dialog asks for one.
        QString photo;
        try {
            photo = write_embedded_photo(f, path, QFileInfo(path).absolutePath());
        } catch (const std::exception& e) {
            error(tr("Cannot import fSpy camera"), QString::fromUtf8(e.what()));
            return false;
        }
        if (probe.isEmpty())
            newDialog(photo);
        else
            newProject(photo, probe);
        if (!doc_->isOpen()) return false;
    }
    doc_->checkpoint();
    Project p = doc_->project();
    const fs::path own = p.resolve(p.photo.path);
    std::error_code ec;
    CalibrationResult r = f.result;
    try {
        if (p.photo.path.empty() || !fs::is_regular_file(own, ec)) {
            // The project has no photo (any more): the fSpy one, next to the project.
            QString folder = doc_->path().isEmpty() ? QString::fromStdString(p.base_dir.string())
                                                    : QFileInfo(doc_->path()).absolutePath();
            if (folder.isEmpty()) folder = QFileInfo(path).absolutePath();
            const QString photo = write_embedded_photo(f, path, folder);
            p.photo.path = QFileInfo(photo).absoluteFilePath().toStdString();
        } else {
            int width = 0, height = 0;
            doc_->assets().photo_size(p, width, height);
            r = scaled_to(r, width, height, own.string(), "photo.path");
        }
    } catch (const std::exception& e) {
        error(tr("Cannot import fSpy camera"), QString::fromUtf8(e.what()));
        return false;
    }
    p.camera = r.camera_spec();
    if (!doc_->tryEdit(tr("Import fSpy camera (%1)").arg(QFileInfo(path).fileName()), p))
        return false;
    QString note = tr("Imported the camera of %1: horizontal field of view %2°")
                       .arg(QFileInfo(path).fileName())
                       .arg(r.intrinsics.hfov_deg(), 0, 'f', 1);
    for (const std::string& w : r.warnings) note += "  ·  " + QString::fromStdString(w);
    statusBar()->showMessage(note, 15000);
    return true;
}

void MainWindow::importFspyDialog() {
    const QString f = QFileDialog::getOpenFileName(
        this, tr("Import fSpy camera"), QString(),
        tr("fSpy projects (*.fspy);;fSpy camera parameters (*.json);;All files (*)"));
    if (!f.isEmpty()) importFspy(f);
}

}  // namespace dp::ui
