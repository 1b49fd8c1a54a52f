// MainWindow: files (new, open, save, export, import), recent files, settings, drops, close.
// The fSpy import is in main_window_fspy.cpp.
#include <QApplication>
#include <QCloseEvent>
#include <QDragEnterEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QLocale>
#include <QMenu>
#include <QMimeData>
#include <QProgressBar>
#include <QSettings>
#include <QSlider>
#include <QStatusBar>
#include <algorithm>
#include <cmath>
#include <optional>

#include "autosave.h"
#include "assets/read_files.h"
#include "base/error.h"
#include "document.h"
#include "error_reporter.h"
#include "geometry/mesh.h"
#include "image/display_transform.h"
#include "image/image_io.h"
#include "image/plate_match.h"
#include "main_window.h"
#include "panel_widgets.h"
#include "mesh_files.h"
#include "new_project_dialog.h"
#include "placement.h"
#include "project_edit.h"
#include "render/progressive.h"
#include "render/render_output.h"
#include "render_controller.h"
#include "settings_panel.h"
#include "scene/project_io.h"
#include "scene/relink.h"
#include "assets/scene_builder.h"
#include "scene_check.h"
#include "viewport.h"

namespace dp::ui {

namespace {

const QStringList kImageSuffixes = {"exr", "hdr", "png", "jpg", "jpeg", "tif", "tiff"};

}  // namespace

bool MainWindow::openProject(const QString& path) {
    Project p;
    try {
        p = load_project(path.toStdString());
    } catch (const std::exception& e) {
        error(tr("Cannot open project"), QString::fromUtf8(e.what()));
        return false;
    }
    // What the renderer would refuse (a file that cannot be read, a scene too large for ray
    // arithmetic) is refused here, before the open document is replaced. The files decoded
    // here are the ones the renderer then uses. Files that have moved are no reason to refuse:
    // the project opens, the render waits, and the Missing Files dialog offers to relink them.
    const bool moved = !missing_inputs(p).empty();
    if (!moved) {
        QApplication::setOverrideCursor(Qt::WaitCursor);
        const QString problem = scene_problem(doc_->assets(), p);
        QApplication::restoreOverrideCursor();
        if (!problem.isEmpty()) {
            error(tr("Cannot open project"), QFileInfo(path).fileName() + ": " + problem);
            return false;
        }
    }
    doc_->reset(p, QFileInfo(path).absoluteFilePath());
    doc_->setDiskHash(Document::hashOnDisk(QFileInfo(path).absoluteFilePath()));
    autosave_->clear();  // the previous document was saved, discarded or unmodified
    addRecent(QFileInfo(path).absoluteFilePath());
    if (moved) relinkFiles();
    return true;
}

bool MainWindow::saveProject() {
    if (doc_->path().isEmpty()) {
        saveAsDialog();
        return !doc_->isModified();
    }
    return saveProjectAs(doc_->path());
}

bool MainWindow::saveProjectAs(const QString& path) {
    if (!doc_->isOpen()) return false;
    commitTypedValue();
    const QString abs = QFileInfo(path).absoluteFilePath();
    if (const QString why = inputOverwriteProblem(abs, false); !why.isEmpty()) {
        error(tr("Cannot save project"), why);
        return false;
    }
    if (abs == doc_->path())
        if (const std::optional<bool> settled = settleDiskConflict(abs)) return *settled;
    Project p = doc_->project();
    const auto newBase = std::filesystem::path(abs.toStdString()).parent_path();
    // Paths stay as written when the folder does not change; elsewhere they become absolute.
    if (p.base_dir != newBase) p = with_absolute_paths(p);
    p.base_dir = newBase;
    try {
        save_project(p, abs.toStdString());
    } catch (const std::exception& e) {
        error(tr("Cannot save project"), QString::fromUtf8(e.what()));
        return false;
    }
    if (!(p == doc_->project()) || p.base_dir != doc_->project().base_dir) doc_->apply(p);
    doc_->setPath(abs);
    doc_->markSaved();
    doc_->setDiskHash(Document::hashOnDisk(abs));
    autosave_->clear();
    addRecent(abs);
    return true;
}

QString MainWindow::inputOverwriteProblem(const QString& path, bool projectFileToo) const {
    ReadSet inputs;
    inputs.add_project(doc_->project(), projectFileToo ? doc_->path().toStdString() : std::string());
    const ReadFile* in = inputs.find(path.toStdString());
    if (!in) return {};
    return tr("%1 is %2: the studio never writes over a file the project reads; choose another name")
        .arg(path, QString::fromStdString(in->what));
}

std::optional<bool> MainWindow::settleDiskConflict(const QString& path) {
    const QByteArray now = Document::hashOnDisk(path);
    // Unknown before (never read here), or gone since: nothing on disk would be lost.
    if (doc_->diskHash().isEmpty() || now.isEmpty() || now == doc_->diskHash()) return std::nullopt;
    const QString text =
        tr("%1 was changed on disk since this window opened or saved it (by another studio or "
           "program).\n\nKeep Mine: replace it with this window's project.\nTake Theirs: load the "
           "file as it is now (Undo brings this window's edits back).\nSave As: keep both.")
            .arg(QFileInfo(path).fileName());
    switch (reporter_->askConflict(this, tr("Project changed on disk"), text)) {
        case ErrorReporter::ConflictChoice::KeepMine: return std::nullopt;
        case ErrorReporter::ConflictChoice::TakeTheirs: return takeDiskVersion(path);
        case ErrorReporter::ConflictChoice::SaveAs:
            saveAsDialog();
            return doc_->path() != path && !doc_->isModified();
        case ErrorReporter::ConflictChoice::Cancel: break;
    }
    return false;
}

bool MainWindow::takeDiskVersion(const QString& path) {
    Project theirs;
    try {
        theirs = load_project(path.toStdString());
    } catch (const std::exception& e) {
        error(tr("Cannot load the project on disk"), QString::fromUtf8(e.what()));
        return false;
    }
    const QByteArray hash = Document::hashOnDisk(path);
    // One undoable step, so this window's edits are one Undo away and nothing is lost.
    doc_->edit(tr("Take the version on disk"), theirs);
    doc_->markSaved();
    doc_->setDiskHash(hash);
    autosave_->clear();
    statusBar()->showMessage(tr("Loaded %1 as it is on disk; Undo brings your edits back")
                                 .arg(QFileInfo(path).fileName()), 15000);
    return true;
}

bool MainWindow::newProject(const QString& photo, const QString& probe, bool mirrorBall) {
    std::string layer;
    try {
        // A multilayer plate (a Blender or Nuke render): the user says which layer is the photo,
        // from its headers, before the loader (which refuses a choice the file cannot make).
        const std::vector<std::string> layers = read_image_layers(photo.toStdString());
        if (layers.size() > 1) {
            QStringList names;
            for (const std::string& l : layers) names << (l.empty() ? tr("(main)") : QString::fromStdString(l));
            // Offered first: the plain layer, else the first Combined pass.
            auto first = std::find(layers.begin(), layers.end(), "");
            if (first == layers.end())
                first = std::find_if(layers.begin(), layers.end(), [](const std::string& l) { return l.ends_with("Combined"); });
            const int current = first == layers.end() ? 0 : int(first - layers.begin());
            bool ok = false;
            const QString chosen = QInputDialog::getItem(this, tr("Layer of the photo"),
                                                         tr("%1 holds several layers; which is the photo?")
                                                             .arg(QFileInfo(photo).fileName()),
                                                         names, current, false, &ok);
            if (!ok) return false;
            const int index = int(names.indexOf(chosen));
            if (index >= 0) layer = layers[size_t(index)];
        }
        ImageLoadOptions chosen_layer;
        chosen_layer.layer = layer;
        load_image(photo.toStdString(), "photograph", nullptr, chosen_layer);
        ImageLoadReport report;
        load_image(probe.toStdString(), "light probe", &report);
        if (!report.linear_source)
            throw InputError(probe.toStdString(), "light probe",
                             "not an HDR image: a light probe must be EXR or Radiance HDR, or "
                             "the sun and sky are clipped and shadows come out too weak");
    } catch (const std::exception& e) {
        error(tr("Cannot create project"), QString::fromUtf8(e.what()));
        return false;
    }
    Project p;
    p.base_dir = QFileInfo(photo).absolutePath().toStdString();
    p.photo.path = QFileInfo(photo).absoluteFilePath().toStdString();
    p.photo.layer = layer;
    p.probe.path = QFileInfo(probe).absoluteFilePath().toStdString();
    p.probe.format = mirrorBall ? ProbeSpec::Format::MirrorBall : ProbeSpec::Format::LatLong;
    p.camera.eye = vec3(0, 1.5f, 4.5f);
    p.camera.target = vec3(0, 0.3f, 0);
    p.camera.vfov_deg = 40;
    RealProxy ground;
    ground.name = "ground";
    ground.shape.kind = Shape::Kind::Plane;
    ground.shape.size = vec3(30, 1, 30);
    ground.albedo.kind = Albedo::Kind::Estimate;  // from the photo, until the user says otherwise
    p.real.push_back(ground);
    doc_->reset(p, QString(), true);
    autosave_->clear();  // the next autosave is the new project's
    return true;
}

bool MainWindow::exportImage(const QString& path) {
    commitTypedValue();
    if (!doc_->isOpen()) {
        error(tr("Nothing to export"), tr("No project is open."));
        Q_EMIT exportFinished(path, false);
        return false;
    }
    if (const QString why = inputOverwriteProblem(QFileInfo(path).absoluteFilePath(), true); !why.isEmpty()) {
        error(tr("Cannot export"), why);
        Q_EMIT exportFinished(path, false);
        return false;
    }
    std::shared_ptr<const RenderFrame> f = renderer_->lastFullFrame();
    if (f && f->generation == renderer_->generation()) return writeExport(path, *f);
    if (const QStringList missing = missingFiles(); !missing.isEmpty()) {
        error(tr("Cannot export"),
              tr("The project's files are missing (%1): relink them first (File > Relink "
                 "Files...).")
                  .arg(missing.join(", ")));
        Q_EMIT exportFinished(path, false);
        return false;
    }
    if (failedGeneration_ != 0 && failedGeneration_ == renderer_->generation()) {
        error(tr("Cannot export"), tr("The render of the project as it is now failed."));
        Q_EMIT exportFinished(path, false);
        return false;
    }
    // The picture on hand shows an earlier state: wait for the current one (onFrame writes it).
    failPendingExport(tr("a newer export replaced it"));
    pendingExport_ = path;
    exportProgress_->setVisible(true);
    statusBar()->showMessage(
        tr("Exporting %1 once the current state has rendered...").arg(QFileInfo(path).fileName()));
    if (renderer_->idle()) requestRender(false);
    return true;
}

void MainWindow::failPendingExport(const QString& why) {
    if (pendingExport_.isEmpty()) return;
    const QString path = pendingExport_;
    pendingExport_.clear();
    exportProgress_->setVisible(false);
    statusBar()->clearMessage();
    error(tr("Cannot export"), tr("%1 was not written: %2").arg(QFileInfo(path).fileName(), why));
    Q_EMIT exportFinished(path, false);
}

bool MainWindow::writeExport(const QString& path, const RenderFrame& f) {
    const QString suffix = QFileInfo(path).suffix().toLower();
    std::vector<std::string> warnings;
    try {
        // Matched to the plate as the view shows it (display.match_plate): the photo measured
        // here, under a wait cursor.
        std::optional<PlateMatch> matched;
        if (doc_->project().display.match_plate && f.scene) {
            WaitCursor wait;
            const Image& photo = f.scene->photo();
            if (photo.width() == f.update.image.width() && photo.height() == f.update.image.height())
                matched = match_plate(f.update.image, photo, f.update.alpha, f.update.dL, measure_plate(photo), 1);
        }
        if (suffix == "png" || suffix == "jpg" || suffix == "jpeg" || suffix == "tif" || suffix == "tiff") {
            Image image = matched ? matched->beauty : f.update.image;
            if (const size_t n = replace_non_finite(image))
                warnings.push_back(std::to_string(n) + " NaN/Inf values replaced by 0");
            for (size_t i = 0; i < image.size(); ++i) image[i] = glm::max(image[i], vec3(0.0f));
            // Through the viewport's view transform; the render as it is (0 EV) unless asked for
            // the display's exposure.
            ViewSettings view;
            view.view = doc_->project().display.view;
            view.look = doc_->project().display.look;
            view.exposure = exportAppliesExposure() ? doc_->project().display.exposure : 0.0f;
            ImageWriteOptions options;
            options.metadata = read_image_metadata(doc_->project().resolve(doc_->project().photo.path).string());
            options.metadata.emplace_back("diffphoton:passes", std::to_string(f.update.stats.passes));
            options.metadata.emplace_back("diffphoton:seed", std::to_string(doc_->project().render.seed));
            save_display_image(path.toStdString(), image, DisplayTransform(view), options);
        } else if (suffix == "exr") {
            RenderUpdate u = f.update;
            std::vector<ExrLayer> extra;
            if (matched) extra = {{"matched", &matched->beauty}, {"grain", &matched->grain}};
            warnings = save_render_exr(path.toStdString(), u, *f.photo, true, extra);
        } else {
            throw InputError(path.toStdString(), "export",
                             "unknown format (use .png, .jpg, .tif or .exr)");
        }
    } catch (const std::exception& e) {
        error(tr("Cannot export"), QString::fromUtf8(e.what()));
        Q_EMIT exportFinished(path, false);
        return false;
    }
    QString note = tr("Exported %1").arg(QFileInfo(path).fileName());
    for (const std::string& w : warnings) note += "  ·  " + QString::fromStdString(w);
    statusBar()->showMessage(note, 10000);
    Q_EMIT exportFinished(path, true);
    return true;
}

bool MainWindow::importMesh(const QString& path) {
    if (!doc_->isOpen()) return false;
    doc_->checkpoint();  // a mesh can be anything: the work so far is on disk before it is read
    LoadedMesh mesh;
    try {
        mesh = load_mesh(path.toStdString(), "import");
    } catch (const std::exception& e) {
        error(tr("Cannot import mesh"), QString::fromUtf8(e.what()));
        return false;
    }
    VirtualObject o;
    o.shape.kind = Shape::Kind::Mesh;
    // A file that brings its materials is drawn with them; the project's material stays for
    // triangles without one (and to switch back to).
    if (mesh.has_file_materials()) o.material_source = MaterialSource::File;
    o.shape.mesh_path = QFileInfo(path).absoluteFilePath().toStdString();
    // An FBX file's up axis applies by itself (Shape::up_axis left absent); its unit is applied
    // on load.
    const vec3 extent = mesh.bounds_hi - mesh.bounds_lo;
    const float size = std::max({extent.x, extent.y, extent.z, 1e-9f});
    Project p = doc_->project();
    o.name = unique_name(p, QFileInfo(path).baseName().toStdString());
    const Camera camera = placementCamera();
    // The file's unit (unit_scale): as the file declares it (FBX, glTF), else guessed from its
    // size. A model still far larger (or smaller) than what the view shows is brought to the
    // size of a new object in this view by its transform's scale.
    const bool declared = mesh.declared_unit_m > 0;
    const UnitGuess unit = declared ? UnitGuess{} : guess_mesh_unit(size);
    o.shape.unit_scale = unit.scale;
    const float metres = size * unit.scale;
    float scale = 1.0f;
    const VisibleGround ground = visible_ground(p, camera);
    const float fit = view_object_size(p, camera);
    const QString name = QFileInfo(path).fileName();
    QString note = declared ? tr("Imported %1: %2 m across (the file's own unit)")
                                  .arg(name)
                                  .arg(double(size), 0, 'g', 4)
                            : tr("Imported %1: %2 units across, read as %3 (%4 m)")
                                  .arg(name)
                                  .arg(double(size), 0, 'g', 4)
                                  .arg(tr(unit.unit))
                                  .arg(double(metres), 0, 'g', 3);
    const float largest = ground.valid ? ground.extent : 10.0f * fit;
    if (metres > largest || metres < 0.02f * fit) {
        scale = fit / metres;
        note += tr("; %1 than the view, scaled to %2 m")
                    .arg(metres > largest ? tr("far larger") : tr("far smaller"))
                    .arg(double(fit), 0, 'g', 3);
    }
    o.transform.scale = vec3(scale);
    place_free(p, o, view_centre_point(p, camera), &camera);
    p.objects.push_back(o);
    if (const QString why = doc_->editProblem(p); !why.isEmpty()) {
        error(tr("Cannot import mesh"), why);
        return false;
    }
    doc_->edit(tr("Import %1").arg(QFileInfo(path).fileName()), p);
    doc_->select(int(p.objects.size()) - 1);
    statusBar()->showMessage(note, 15000);
    return true;
}

bool MainWindow::maybeSave() {
    commitTypedValue();
    if (!doc_->isOpen() || !doc_->isModified()) return true;
    const QString name =
        doc_->path().isEmpty() ? tr("The new project") : QFileInfo(doc_->path()).fileName();
    switch (reporter_->askSave(this, tr("Unsaved changes"),
                               tr("%1 has unsaved changes. Save them?").arg(name))) {
        case ErrorReporter::SaveChoice::Save:
            return saveProject();  // false if the save failed or its dialog was cancelled
        case ErrorReporter::SaveChoice::Discard:
            return true;  // the caller replaces the document, and only then the recovery file
        case ErrorReporter::SaveChoice::Cancel:
            break;
    }
    return false;
}

void MainWindow::openRecent(const QString& path) {
    if (maybeSave()) openProject(path);
}

void MainWindow::openDialog() {
    if (!maybeSave()) return;
    const QString f = QFileDialog::getOpenFileName(this, tr("Open project"), QString(),
                                                   tr("diffphoton projects (*.json)"));
    if (!f.isEmpty()) openProject(f);
}

void MainWindow::saveAsDialog() {
    const QString f = QFileDialog::getSaveFileName(this, tr("Save project"), doc_->path(),
                                                   tr("diffphoton projects (*.json)"));
    if (!f.isEmpty()) saveProjectAs(f.endsWith(".json") ? f : f + ".json");
}

void MainWindow::newDialog(const QString& photo, const QString& probe) {
    if (!maybeSave()) return;
    NewProjectDialog dialog(this);
    dialog.setPhotoPath(photo);
    dialog.setProbePath(probe);
    if (dialog.exec() == QDialog::Accepted)
        newProject(dialog.photoPath(), dialog.probePath(), dialog.mirrorBall());
}

void MainWindow::exportDialog() {
    // Beside the project, named after it (the process's folder is no place a user chose).
    const QFileInfo project(doc_->path());
    const QString suggested = doc_->path().isEmpty()
                                  ? QString()
                                  : project.dir().filePath(project.completeBaseName() + QStringLiteral(".png"));
    const QString f =
        QFileDialog::getSaveFileName(this, tr("Export image"), suggested,
                                     tr("PNG (*.png);;OpenEXR with layers (*.exr);;JPEG (*.jpg);;TIFF, 16 bits (*.tif)"));
    if (!f.isEmpty()) exportImage(f);
}

void MainWindow::importDialog() {
    const QString f =
        QFileDialog::getOpenFileName(this, tr("Import mesh"), QString(), mesh_file_filter());
    if (!f.isEmpty()) importMesh(f);
}

void MainWindow::dragEnterEvent(QDragEnterEvent* e) {
    if (e->mimeData()->hasUrls()) e->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* e) {
    QStringList images;
    for (const QUrl& url : e->mimeData()->urls()) {
        const QString f = url.toLocalFile();
        const QString suffix = QFileInfo(f).suffix().toLower();
        if (suffix == "json") {
            if (maybeSave()) openProject(f);
        }
        else if (suffix == "fspy")
            importFspy(f);
        else if (is_mesh_file(f))
            importMesh(f);
        else if (kImageSuffixes.contains(suffix))
            images << f;
    }
    if (images.size() >= 2) {
        if (maybeSave()) newProject(images[0], images[1]);
    }
    else if (images.size() == 1)
        newDialog(images[0]);
}

void MainWindow::addRecent(const QString& path) {
    recent_.removeAll(path);
    recent_.prepend(path);
    while (recent_.size() > 8) recent_.removeLast();
    if (options_.useSettings) QSettings().setValue("recentFiles", recent_);
    rebuildRecentMenu();
}

void MainWindow::rebuildRecentMenu() {
    if (!recentMenu_) return;
    recentMenu_->clear();
    for (const QString& f : recent_) {
        QAction* a =
            recentMenu_->addAction(QFileInfo(f).fileName(), this, [this, f] { openRecent(f); });
        a->setToolTip(f);
    }
    recentMenu_->setEnabled(!recent_.isEmpty());
}

void MainWindow::restoreSettings() {
    QSettings s;
    restoreGeometry(s.value("geometry").toByteArray());
    restoreState(s.value("windowState").toByteArray());
    recent_ = s.value("recentFiles").toStringList();
    const double noise = s.value("noiseTarget", 0.0).toDouble();
    settingsPanel_->setNoiseTarget(noise);
    renderer_->setNoiseTarget(noise);
    rebuildRecentMenu();
}

void MainWindow::checkRecovery() {
    if (!options_.checkRecovery) return;
    std::vector<Autosave::Orphan> orphans = autosave_->claimOrphans();
    for (size_t i = 0; i < orphans.size(); ++i) {
        Autosave::Orphan& o = orphans[i];
        const QString where =
            o.recovered.originalPath.isEmpty() ? tr("an unsaved project") : o.recovered.originalPath;
        const QString more = i + 1 < orphans.size()
                                 ? tr(" (%1 more left by other studios)").arg(orphans.size() - i - 1)
                                 : QString();
        if (!reporter_->ask(this, tr("Recover unsaved work?"),
                            tr("A studio did not close cleanly. Recover its copy of %1, autosaved "
                               "%2?%3")
                                .arg(where, QLocale().toString(o.written, QLocale::ShortFormat), more))) {
            Autosave::discard(o);
            continue;
        }
        doc_->reset(o.recovered.project, o.recovered.originalPath, true);
        doc_->setDiskHash(o.recovered.diskHash);
        autosave_->adopt(o);  // if the copy cannot be made this window's, it is offered again
        if (!missingFiles().isEmpty()) relinkFiles();
        if (i + 1 < orphans.size())
            statusBar()->showMessage(tr("%1 more unsaved copies are offered when the next studio starts")
                                         .arg(orphans.size() - i - 1), 15000);
        break;  // one document per window: the others are released for the next start
    }
}

void MainWindow::updateTitle() {
    const QString name =
        doc_->path().isEmpty() ? tr("Untitled") : QFileInfo(doc_->path()).fileName();
    setWindowTitle(doc_->isOpen() ? tr("%1[*] - diffphoton studio").arg(name)
                                  : tr("diffphoton studio"));
    setWindowModified(doc_->isModified());
}

void MainWindow::closeEvent(QCloseEvent* e) {
    if (!maybeSave()) {
        e->ignore();
        return;
    }
    if (options_.useSettings) {
        QSettings s;
        s.setValue("geometry", saveGeometry());
        s.setValue("windowState", saveState());
    }
    renderer_->stop();
    autosave_->clear();  // saved, discarded or unmodified: nothing left to recover
    e->accept();
}

}  // namespace dp::ui
