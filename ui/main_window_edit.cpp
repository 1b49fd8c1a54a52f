// MainWindow: object and light edits (add, duplicate, delete, hide, on ground, G / R / S) and the
// display (exposure per project, overlays).
#include <QAction>
#include <QComboBox>
#include <QLabel>
#include <QMenu>
#include <QSignalBlocker>
#include <QSlider>
#include <QStatusBar>
#include <algorithm>
#include <cmath>

#include "document.h"
#include "main_window.h"
#include "photo_geometry.h"
#include "placement.h"
#include "project_edit.h"
#include "denoise_worker.h"
#include "render_controller.h"
#include "viewport.h"

namespace dp::ui {

Camera MainWindow::placementCamera() const {
    if (viewport_->renderSize().isValid()) return viewport_->viewCamera();
    try {
        return photo_camera(doc_->assets(), doc_->project());
    } catch (const std::exception&) {
        return doc_->project().camera.build(1024, 512);  // a photo that cannot be read
    }
}

void MainWindow::addObject(Shape::Kind kind) {
    if (!doc_->isOpen()) return;
    Project p = doc_->project();
    // Sized to what the view shows, on the real surface under the view centre, clear of the
    // objects already there.
    p.objects.push_back(
        new_primitive(p, placementCamera(), kind, unique_name(p, shape_kind_name(kind))));
    doc_->edit(tr("Add %1").arg(shape_kind_name(kind)), p);
    doc_->select(int(p.objects.size()) - 1);
}

void MainWindow::createLightMenu() {
    lightMenu_ = new QMenu(tr("&Light"), this);
    lightMenu_->setObjectName("lightMenu");
    const char* names[] = {"addPointLight", "addSpotLight", "addRectLight", "addDiskLight"};
    const char* tips[] = {"A bulb shining all around", "A bulb cut to a cone, shining down",
                          "A glowing rectangle, shining down", "A glowing disk, shining down"};
    for (int k = 0; k < 4; ++k) {
        QAction* a = lightMenu_->addAction(tr(light_kind_label(VirtualLight::Kind(k))));
        a->setObjectName(names[k]);
        a->setToolTip(tr("Add a light above the view's centre: %1").arg(tr(tips[k])));
        a->setStatusTip(a->toolTip());
        connect(a, &QAction::triggered, this, [this, k] { addLight(VirtualLight::Kind(k)); });
    }
}

void MainWindow::addLight(VirtualLight::Kind kind) {
    if (!doc_->isOpen()) return;
    Project p = doc_->project();
    const std::string base = std::string(light_kind_name(kind)) + " light";
    p.lights.push_back(new_light(p, placementCamera(), kind, unique_light_name(p, base)));
    doc_->edit(tr("Add %1 light").arg(light_kind_name(kind)), p);
    doc_->selectLight(int(p.lights.size()) - 1);
}

void MainWindow::duplicateSelected() {
    Project p = doc_->project();
    if (const int light = doc_->selectedLight(); light >= 0) {
        VirtualLight copy = p.lights[size_t(light)];
        copy.name = unique_light_name(p, copy.name);
        // Beside the original: a third of its height above the surface, so both stay in view.
        copy.transform.translation.x += std::max(0.1f, (copy.transform.translation.y -
                                                        surface_below(p, copy.transform.translation)) / 3);
        p.lights.push_back(copy);
        doc_->edit(tr("Duplicate light"), p);
        doc_->selectLight(int(p.lights.size()) - 1);
        return;
    }
    const int sel = doc_->selected();
    if (sel < 0) return;
    VirtualObject copy = p.objects[size_t(sel)];
    copy.name = unique_name(p, copy.name);
    vec3 c;
    float r;
    bounding_sphere(copy, c, r);
    copy.transform.translation.x += 2.2f * r;  // beside the original, not inside it
    p.objects.push_back(copy);
    doc_->edit(tr("Duplicate object"), p);
    doc_->select(int(p.objects.size()) - 1);
}

void MainWindow::deleteSelected() {
    Project p = doc_->project();
    if (const int light = doc_->selectedLight(); light >= 0) {
        p.lights.erase(p.lights.begin() + light);
        doc_->selectLight(-1);
        doc_->edit(tr("Delete light"), p);
        return;
    }
    const int sel = doc_->selected();
    if (sel < 0) return;
    p.objects.erase(p.objects.begin() + sel);
    doc_->select(-1);
    doc_->edit(tr("Delete object"), p);
}

void MainWindow::toggleSelectedVisible() {
    const int sel = doc_->selected();
    if (sel < 0) return;
    Project p = doc_->project();
    p.objects[size_t(sel)].visible = !p.objects[size_t(sel)].visible;
    doc_->edit(p.objects[size_t(sel)].visible ? tr("Show object") : tr("Hide object"), p);
}

void MainWindow::dropSelectedToSurface() {
    const int sel = doc_->selected();
    if (sel < 0 || viewport_->transforming()) return;
    commitTypedValue();
    Project p = doc_->project();
    VirtualObject& o = p.objects[size_t(sel)];
    o.transform = dropped_to_surface(p, o);
    doc_->edit(tr("Put %1 on the ground").arg(QString::fromStdString(o.name)), p);
}

void MainWindow::startModal(GizmoMode mode) {
    if (viewport_->transforming()) return;
    if (doc_->selected() < 0 && doc_->selectedLight() < 0) {
        statusBar()->showMessage(
            tr("Select an object or a light first (click it in the viewport or the list)"), 5000);
        return;
    }
    commitTypedValue();  // a value typed into a field counts before the object moves
    if (viewport_->startModalTransform(mode))
        statusBar()->showMessage(tr("Move the mouse or type a value; X, Y or Z keeps to that "
                                    "axis; click or Enter confirms, Esc or right click cancels"),
                                 5000);
}

void MainWindow::setDisplayExposure(float stops) {
    if (!doc_->isOpen()) return;
    Project p = doc_->project();
    p.display.exposure = stops;
    doc_->edit(tr("Display exposure"), p, exposureKey_);
}

void MainWindow::setDisplayView(const QString& view) {
    if (!doc_->isOpen() || doc_->project().display.view == view.toStdString()) return;
    Project p = doc_->project();
    p.display.view = view.toStdString();
    doc_->edit(tr("View transform"), p);
}

void MainWindow::setMatchPlate(bool on) {
    if (!doc_->isOpen() || doc_->project().display.match_plate == on) return;
    Project p = doc_->project();
    p.display.match_plate = on;
    doc_->edit(on ? tr("Match plate") : tr("Unmatch plate"), p);
}

float MainWindow::displayExposure() const {
    return doc_->project().display.exposure;
}

void MainWindow::showDisplaySettings() {
    // The slider and the label follow the project (open, undo, redo).
    const float stops = doc_->project().display.exposure;
    {
        const QSignalBlocker block(exposure_);
        exposure_->setValue(int(std::lround(stops * 10)));
    }
    exposureLabel_->setText(tr("%1%2 EV").arg(stops >= 0 ? "+" : "").arg(stops, 0, 'f', 1));
    if (viewport_->exposure() != stops) viewport_->setExposure(stops);
    const DisplaySettings& display = doc_->project().display;
    {
        const QSignalBlocker block(viewBox_);
        const QString view = QString::fromStdString(display.view);
        if (viewBox_->findText(view) < 0) viewBox_->addItem(view);  // a view this machine's config lacks
        viewBox_->setCurrentText(view);
    }
    ViewSettings view;
    view.view = display.view;
    view.look = display.look;
    viewport_->setView(view);
    viewport_->setMatchPlate(display.match_plate);
    action("matchPlate")->setChecked(display.match_plate);  // setChecked does not trigger it
    renderer_->setDisplayExposure(stops);  // the noise target is judged at it
}

void MainWindow::setOverlaysVisible(bool on) {
    action("overlays")->setChecked(on);  // setChecked does not trigger the action
    viewport_->setOverlaysVisible(on);
}

void MainWindow::setDenoise(bool on) {
    QString why;
    if (on && !DenoiseWorker::available(&why)) {
        on = false;
        action("denoise")->setToolTip(tr("Denoising is not available: %1").arg(why));
        statusBar()->showMessage(tr("Denoising is not available: %1").arg(why), 8000);
    }
    const QSignalBlocker block(action("denoise"));
    action("denoise")->setChecked(on);
    renderer_->setDenoise(on);
    viewport_->setDenoise(on);
    if (!on) return;
    // What is on screen now: denoised without waiting for the next pass.
    if (const auto f = renderer_->lastFullFrame()) denoiser_->request(f);
    sinceDenoise_.start();
}

void MainWindow::setExportAppliesExposure(bool on) {
    action("exportExposure")->setChecked(on);
}

bool MainWindow::exportAppliesExposure() const {
    return action("exportExposure")->isChecked();
}

}  // namespace dp::ui
