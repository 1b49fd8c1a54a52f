#include "main_window.h"
#include "farm_dialog.h"

#include <QAction>
#include <QActionGroup>
#include <QAbstractSpinBox>
#include <QApplication>
#include <QCheckBox>
#include <QDockWidget>
#include <QHBoxLayout>
#include <QButtonGroup>
#include <QKeySequence>
#include <QComboBox>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QProgressBar>
#include <QScrollArea>
#include <QScrollBar>
#include <QSettings>
#include <QSlider>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTabWidget>
#include <QToolBar>
#include <QToolButton>
#include <QUndoStack>
#include <QVBoxLayout>
#include <cmath>

#include "autosave.h"
#include "calibration_panel.h"
#include "camera_panel.h"
#include "document.h"
#include "error_reporter.h"
#include "light_panel.h"
#include "material_panel.h"
#include "probe_align_panel.h"
#include "probe_panel.h"
#include "holdout_panel.h"
#include "scene_view.h"
#include "proxy_panel.h"
#include "project_edit.h"
#include "denoise_worker.h"
#include "render_controller.h"
#include "scene_panel.h"
#include "render/scheduler.h"
#include "settings_panel.h"
#include "shortcut_policy.h"
#include "number_field.h"
#include "viewport.h"

namespace dp::ui {

namespace {

/// The platform's key for `standard` and `fallback`, once each: without a desktop environment
/// some standard keys (Save As, Quit) are unbound, and a key listed twice would be ambiguous.
QList<QKeySequence> keys(QKeySequence::StandardKey standard, const QString& fallback) {
    QList<QKeySequence> list = QKeySequence::keyBindings(standard);
    const QKeySequence extra(fallback);
    if (!list.contains(extra)) list << extra;
    return list;
}

}  // namespace

MainWindow::MainWindow(const StudioOptions& options, QWidget* parent)
    : QMainWindow(parent), options_(options) {
    if (options_.reporter) {
        reporter_ = options_.reporter;
    } else {
        ownReporter_ = std::make_unique<MessageBoxReporter>();
        reporter_ = ownReporter_.get();
    }
    setAcceptDrops(true);
    doc_ = new Document(this);
    renderer_ = new RenderController(doc_->assetLibrary(), this);
    renderer_->setRenderSize(options_.renderSize);
    renderer_->setPreviewFraction(options_.previewFraction);
    renderer_->setPreviewScale(options_.previewScale);
    renderer_->setEndless(options_.endless);
    denoiser_ = new DenoiseWorker(this);
    viewport_ = new Viewport(doc_, this);
    setCentralWidget(viewport_);
    status_ = new QLabel(tr("No project"));
    status_->setObjectName("renderStatus");
    status_->setToolTip(tr("Passes done, photon rate and an estimate of the remaining noise"));
    statusBar()->addWidget(status_, 1);
    // Asset warnings stay visible beside the status until the project's files are fixed.
    warnings_ = new QToolButton;
    warnings_->setObjectName("assetWarnings");
    warnings_->setAutoRaise(true);
    warnings_->setVisible(false);
    statusBar()->addPermanentWidget(warnings_);
    // Likewise the files the project cannot find, until they are relinked.
    missing_ = new QToolButton;
    missing_->setObjectName("missingFiles");
    missing_->setAutoRaise(true);
    missing_->setVisible(false);
    statusBar()->addPermanentWidget(missing_);
    connect(missing_, &QToolButton::clicked, this, [this] { relinkFiles(); });
    exportProgress_ = new QProgressBar;
    exportProgress_->setObjectName("exportProgress");
    exportProgress_->setRange(0, 0);  // busy: the pass takes as long as it takes
    exportProgress_->setMaximumWidth(120);
    exportProgress_->setToolTip(tr("The export waits for the render of the current state"));
    exportProgress_->setVisible(false);
    statusBar()->addPermanentWidget(exportProgress_);
    connect(warnings_, &QToolButton::clicked, this, [this] {
        auto* box = new QMessageBox(QMessageBox::Warning, tr("Asset warnings"), warnings_->toolTip(),
                                    QMessageBox::Close, this);
        box->setAttribute(Qt::WA_DeleteOnClose);
        box->open();  // not modal to the render: the picture keeps refining behind it
    });

    createActions();
    createDocks();
    createMenus();
    createToolbar();
    connectRenderer();
    connect(denoiser_, &DenoiseWorker::denoised, viewport_,
            [this](std::shared_ptr<const RenderFrame> f, std::shared_ptr<const Image> image) {
                viewport_->setDenoised(std::move(f), std::move(image));
            });
    connect(denoiser_, &DenoiseWorker::shownError, this, [this](quint64 generation, int, double error) {
        onShownError(generation, error);
    });
    if (options_.denoise) {
        // On where the library is there; quietly off (its tooltip says why) where not.
        QString why;
        if (DenoiseWorker::available(&why))
            setDenoise(true);
        else
            action("denoise")->setToolTip(tr("Denoising is not available: %1").arg(why));
    }

    QString dir = options_.recoveryDir;
    if (dir.isEmpty())
        dir = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + "/recovery";
    autosave_ = new Autosave(doc_, dir, options_.autosaveMs, this);

    // Typed values the checks refuse: the field keeps its value, the status bar says why.
    auto refused = [this](const QString& why) { statusBar()->showMessage(why, 15000); };
    connect(doc_, &Document::editRefused, this,
            [refused](const QString& why) { refused(QObject::tr("Not applied: %1").arg(why)); });
    for (NumberField* f : findChildren<NumberField*>())
        connect(f, &NumberField::refused, this,
                [refused](const QString& why) { refused(QObject::tr("Not applied: %1").arg(why)); });
    shortcutPolicy_ = new ShortcutPolicy(this);
    shortcutPolicy_->install(this);

    connect(doc_, &Document::pathChanged, this, [this] { updateTitle(); });
    connect(doc_, &Document::modifiedChanged, this, [this] { updateTitle(); });
    resize(1400, 860);
    if (options_.useSettings) restoreSettings();
    updateTitle();
}

MainWindow::~MainWindow() {
    renderer_->stop();
}

FarmDialog* MainWindow::farmDialog() {
    if (!farmDialog_) farmDialog_ = new FarmDialog(doc_, [this] { return saveProject(); }, this);
    return farmDialog_;
}

QAction* MainWindow::action(const QString& name) const {
    return findChild<QAction*>(name);
}

void MainWindow::createActions() {
    auto make = [this](const QString& name, const QString& text, const QKeySequence& key,
                       const QString& tip, auto slot) {
        auto* a = new QAction(text, this);
        a->setObjectName(name);
        if (!key.isEmpty()) a->setShortcut(key);
        a->setToolTip(tip);
        a->setStatusTip(tip);
        connect(a, &QAction::triggered, this, slot);
        addAction(a);
        return a;
    };
    make("new", tr("&New Project..."), QKeySequence::New,
         tr("Start from a photograph and a light probe"), [this] { newDialog(); });
    make("open", tr("&Open..."), QKeySequence::Open, tr("Open a project file"),
         [this] { openDialog(); });
    make("save", tr("&Save"), QKeySequence::Save, tr("Save the project"),
         [this] { saveProject(); });
    make("saveAs", tr("Save &As..."), {}, tr("Save the project under a new name"),
         [this] { saveAsDialog(); })
        ->setShortcuts(keys(QKeySequence::SaveAs, tr("Ctrl+Shift+S")));
    make("relink", tr("Relin&k Files..."), {},
         tr("Point the project at its photo, probe, meshes or textures where they are now"),
         [this] { relinkFiles(); });
    make("export", tr("&Export Image..."), QKeySequence(tr("Ctrl+E")),
         tr("Write the render as PNG, or EXR with layers"), [this] { exportDialog(); });
    make("renderOnFarm", tr("Render on &Farm..."), {},
         tr("Render the saved project's final image across machines with diffphoton-farm (Dask)"), [this] {
             FarmDialog* d = farmDialog();
             d->show();
             d->raise();
         });
    make("importFspy", tr("Import &fSpy..."), {},
         tr("Take the camera from an fSpy project (.fspy) or fSpy's exported camera parameters"),
         [this] { importFspyDialog(); });
    make("exportUndistorted", tr("Export &Undistorted Photo..."), {},
         tr("Write the photo with the camera's lens distortion taken out"),
         [this] { calibrationPanel_->exportUndistortedDialog(); });
    make("quit", tr("&Quit"), {}, tr("Close the studio"), [this] { close(); })
        ->setShortcuts(keys(QKeySequence::Quit, tr("Ctrl+Q")));
    QAction* undo = doc_->undoStack()->createUndoAction(this, tr("&Undo"));
    undo->setObjectName("undo");
    undo->setShortcut(QKeySequence(tr("Ctrl+Z")));
    undo->setToolTip(tr("Undo the last edit"));
    QAction* redo = doc_->undoStack()->createRedoAction(this, tr("&Redo"));
    redo->setObjectName("redo");
    redo->setShortcuts({QKeySequence(tr("Ctrl+Shift+Z")), QKeySequence(tr("Ctrl+Y"))});
    redo->setToolTip(tr("Redo the edit last undone"));
    addAction(undo);
    addAction(redo);
    make("addSphere", tr("Sphere"), {}, tr("Add a sphere resting on the ground"),
         [this] { addObject(Shape::Kind::Sphere); });
    make("addBox", tr("Box"), {}, tr("Add a box resting on the ground"),
         [this] { addObject(Shape::Kind::Box); });
    make("addPlane", tr("Plane"), {}, tr("Add an upright card"),
         [this] { addObject(Shape::Kind::Plane); });
    make("import", tr("Import..."), QKeySequence(tr("Ctrl+I")),
         tr("Import an OBJ, PLY or glTF mesh"), [this] { importDialog(); });
    make("duplicate", tr("Duplicate"), QKeySequence(tr("Shift+D")),
         tr("Duplicate the selected object or light"), [this] { duplicateSelected(); });
    make("delete", tr("Delete"), QKeySequence(tr("X")), tr("Delete the selected object or light"),
         [this] {
             if (!viewport_->transforming()) deleteSelected();
         })
        ->setShortcuts({QKeySequence(tr("X")), QKeySequence(QKeySequence::Delete)});
    const char* ops[] = {"grab", "rotate", "scale"};
    const char* opNames[] = {"&Grab (Move)", "&Rotate", "&Scale"};
    const char* opKeys[] = {"G", "R", "S"};
    for (int i = 0; i < 3; ++i)
        make(ops[i], tr(opNames[i]), QKeySequence(tr(opKeys[i])),
             tr("The selected object follows the mouse until a click (Esc cancels)"),
             [this, i] { startModal(GizmoMode(i)); });
    make("keyMap", tr("&Keyboard Shortcuts"), QKeySequence(tr("F1")),
         tr("Every key the studio answers to"), [this] { showKeyMap(); });
    make("hide", tr("Hide/Show"), QKeySequence(tr("Shift+H")),
         tr("Hide or show the selected object"), [this] { toggleSelectedVisible(); });
    make("onGround", tr("On &Ground"), QKeySequence(tr("End")),
         tr("Drop the selected object onto the real surface below it"),
         [this] { dropSelectedToSurface(); });
    QAction* overlays =
        make("overlays", tr("&Overlays"), QKeySequence(tr("H")),
             tr("Grid, proxy wireframes and object outlines over the augmented and dL views"),
             [this](bool on) { viewport_->setOverlaysVisible(on); });
    overlays->setCheckable(true);
    QAction* denoise = make("denoise", tr("&Denoise"), QKeySequence(tr("D")),
                            tr("Show the render with its change denoised (Open Image Denoise); "
                               "the photo and the exports stay as rendered"),
                            [this](bool on) { setDenoise(on); });
    denoise->setCheckable(true);
    QAction* matchPlate = make("matchPlate", tr("&Match Plate"), {},
                               tr("Give the objects and the change the photo's grain and softness, in the "
                                  "view and in exports (one undo step)"),
                               [this](bool on) { setMatchPlate(on); });
    matchPlate->setCheckable(true);
    QAction* exportExposure = make(
        "exportExposure", tr("Apply Display Exposure to Exports"), {},
        tr("PNG and JPEG exports at the display exposure instead of the render's own 0 EV"), [] {});
    exportExposure->setCheckable(true);
    make("fit", tr("Fit View"), QKeySequence(tr("Home")), tr("Fit the render in the window"),
         [this] { viewport_->fitView(); });

    viewGroup_ = new QActionGroup(this);
    const char* views[] = {"Photo", "Augmented", "dL"};
    const char* viewTips[] = {
        "The photograph as loaded", "The photograph with the objects",
        "Change in light on real surfaces: blue removed (shadows), red added (caustics)"};
    for (int i = 0; i < 3; ++i) {
        QAction* a = make(QStringLiteral("view%1").arg(views[i]), tr(views[i]),
                          QKeySequence(QString::number(i + 1)), tr(viewTips[i]),
                          [this, i] { viewport_->setViewMode(ViewMode(i)); });
        a->setCheckable(true);
        a->setChecked(i == 1);
        viewGroup_->addAction(a);
    }
    gizmoGroup_ = new QActionGroup(this);
    const char* modes[] = {"Move", "Rotate", "Scale"};
    const char* keys[] = {"G", "R", "S"};
    for (int i = 0; i < 3; ++i) {
        QAction* a =
            make(QStringLiteral("gizmo%1").arg(modes[i]), tr(modes[i]), {},
                 tr("%1 the selected object by dragging it (%2)").arg(tr(modes[i]), keys[i]),
                 [this, i] { viewport_->setGizmoMode(GizmoMode(i)); });
        a->setCheckable(true);
        a->setChecked(i == 0);
        gizmoGroup_->addAction(a);
    }
    connect(viewport_, &Viewport::gizmoModeChanged, this,
            [this](GizmoMode m) { gizmoGroup_->actions()[int(m)]->setChecked(true); });
    connect(viewport_, &Viewport::dragStarted, this, [this] { beginInteraction(); });
    connect(viewport_, &Viewport::dragFinished, this, [this] { endInteraction(); });
}

void MainWindow::createMenus() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    file->addActions({action("new"), action("open")});
    recentMenu_ = file->addMenu(tr("Open &Recent"));
    recentMenu_->setObjectName("recentMenu");
    recentMenu_->setToolTipsVisible(true);
    file->addActions({action("save"), action("saveAs"), action("relink")});
    file->addSeparator();
    file->addAction(action("importFspy"));
    file->addSeparator();
    file->addActions({action("export"), action("exportExposure"), action("exportUndistorted")});
    file->addAction(action("renderOnFarm"));
    file->addSeparator();
    file->addAction(action("quit"));
    QMenu* edit = menuBar()->addMenu(tr("&Edit"));
    edit->addActions({action("undo"), action("redo")});
    edit->addSeparator();
    QMenu* add = edit->addMenu(tr("&Add"));
    add->addActions({action("addSphere"), action("addBox"), action("addPlane")});
    add->addSeparator();
    add->addMenu(lightMenu_);
    edit->addAction(action("import"));
    QMenu* object = menuBar()->addMenu(tr("&Object"));
    object->setObjectName("objectMenu");
    QMenu* transform = object->addMenu(tr("&Transform"));
    transform->addActions({action("grab"), action("rotate"), action("scale")});
    object->addAction(action("onGround"));
    object->addSeparator();
    object->addActions({action("duplicate"), action("delete"), action("hide")});
    QMenu* view = menuBar()->addMenu(tr("&View"));
    view->setObjectName("viewMenu");
    view->addActions(viewGroup_->actions());
    view->addSeparator();
    view->addAction(action("overlays"));
    view->addAction(action("matchPlate"));
    view->addAction(action("denoise"));
    view->addSeparator();
    view->addAction(action("fit"));
    view->addSeparator();
    for (QDockWidget* d : findChildren<QDockWidget*>()) view->addAction(d->toggleViewAction());
    QMenu* help = menuBar()->addMenu(tr("&Help"));
    help->setObjectName("helpMenu");
    help->addAction(action("keyMap"));
    rebuildRecentMenu();
}

void MainWindow::createDocks() {
    auto dock = [this](const QString& name, const QString& title, QWidget* w,
                       Qt::DockWidgetArea area) {
        auto* scroll = new QScrollArea;
        scroll->setWidget(w);
        scroll->setWidgetResizable(true);

        auto* d = new QDockWidget(title, this);
        d->setObjectName(name);
        d->setWidget(scroll);
        addDockWidget(area, d);
        return d;
    };
    createLightMenu();
    scenePanel_ = new ScenePanel(doc_,
                                 {action("addSphere"), action("addBox"), action("addPlane"),
                                  action("import"), action("duplicate"), action("delete")},
                                 lightMenu_);
    materialPanel_ = new MaterialPanel(doc_);
    lightPanel_ = new LightPanel(doc_);
    auto* objects = new QWidget;
    auto* col = new QVBoxLayout(objects);
    col->addWidget(scenePanel_, 1);
    col->addWidget(materialPanel_);
    col->addWidget(lightPanel_);
    // A light has no material: its own panel takes the material's place.
    connect(doc_, &Document::selectionChanged, this,
            [this] { materialPanel_->setVisible(doc_->selectedLight() < 0); });
    dock("sceneDock", tr("Scene"), objects, Qt::RightDockWidgetArea);
    settingsPanel_ = new SettingsPanel(doc_);
    connect(settingsPanel_, &SettingsPanel::noiseTargetChanged, this, [this](double target) {
        renderer_->setNoiseTarget(target);
        if (options_.useSettings) QSettings().setValue("noiseTarget", target);
        // A lower target goes on refining the picture already there.
        if (renderer_->finished() && doc_->isOpen()) requestRender(false);
    });
    probePanel_ = new ProbePanel(doc_);
    cameraPanel_ = new CameraPanel(doc_);
    calibrationPanel_ = new CalibrationPanel(doc_, viewport_, cameraPanel_, reporter_);
    cameraPanel_->setCalibrationTools(calibrationPanel_);
    QDockWidget* render = dock("renderDock", tr("Render"), settingsPanel_, Qt::LeftDockWidgetArea);
    probeAlignPanel_ = new ProbeAlignPanel(doc_, viewport_, reporter_);
    auto* probeTools = new QWidget;
    auto* probeCol = new QVBoxLayout(probeTools);
    probeCol->setContentsMargins(0, 0, 0, 0);
    probeCol->addWidget(probePanel_);
    probeCol->addWidget(probeAlignPanel_);
    probeCol->addStretch(1);
    proxyPanel_ = new ProxyPanel(doc_, viewport_, reporter_);
    QDockWidget* probe = dock("probeDock", tr("Light Probe"), probeTools, Qt::LeftDockWidgetArea);
    QDockWidget* camera = dock("cameraDock", tr("Camera"), cameraPanel_, Qt::LeftDockWidgetArea);
    QDockWidget* proxies =
        dock("proxyDock", tr("Real Proxies"), proxyPanel_, Qt::LeftDockWidgetArea);
    // A second view of the scene, below the object list: where things stand in depth.
    auto* sceneViewBox = new QWidget;
    auto* sceneViewCol = new QVBoxLayout(sceneViewBox);
    sceneViewCol->setContentsMargins(0, 0, 0, 0);
    auto* viewRow = new QHBoxLayout;
    auto* sceneView = new SceneView(doc_);
    sceneView->setMinimumHeight(220);
    const std::pair<const char*, SceneView::View> views[] = {{"sceneViewTop", SceneView::View::Top},
                                                             {"sceneViewFront", SceneView::View::Front},
                                                             {"sceneViewSide", SceneView::View::Side},
                                                             {"sceneViewFree", SceneView::View::Orbit}};
    const QString viewLabels[] = {tr("Top"), tr("Front"), tr("Side"), tr("Free")};
    auto* viewGroup = new QButtonGroup(sceneViewBox);
    for (int k = 0; k < 4; ++k) {
        auto* b = new QToolButton;
        b->setObjectName(views[k].first);
        b->setText(viewLabels[k]);
        b->setCheckable(true);
        b->setChecked(k == 0);
        b->setToolTip(tr("Look at the scene from here: drag the selection to move it, elsewhere to "
                         "pan (or orbit, in the free view); the wheel zooms"));
        viewGroup->addButton(b);
        const SceneView::View v = views[k].second;
        connect(b, &QToolButton::clicked, sceneView, [sceneView, v] { sceneView->setView(v); });
        viewRow->addWidget(b);
    }
    viewRow->addStretch(1);
    sceneViewCol->addLayout(viewRow);
    sceneViewCol->addWidget(sceneView, 1);
    connect(viewport_, &Viewport::gizmoModeChanged, sceneView, &SceneView::setGizmoMode);
    connect(sceneView, &SceneView::dragStarted, this, [this] { beginInteraction(); });
    connect(sceneView, &SceneView::dragFinished, this, [this] { endInteraction(); });
    dock("sceneViewDock", tr("Scene View"), sceneViewBox, Qt::RightDockWidgetArea);
    tabifyDockWidget(render, probe);
    tabifyDockWidget(probe, camera);
    QDockWidget* holdouts = dock("holdoutDock", tr("Holdouts"), new HoldoutPanel(doc_, viewport_, reporter_),
                                 Qt::LeftDockWidgetArea);
    tabifyDockWidget(camera, proxies);
    tabifyDockWidget(proxies, holdouts);
    render->raise();
    // The viewport gets most of the width; the panels what their fields need (fitDocks).
    resizeDocks({render, findChild<QDockWidget*>("sceneDock")}, {300, 440}, Qt::Horizontal);
    connect(materialPanel_, &MaterialPanel::strokeStarted, this, [this] { beginInteraction(); });
    connect(materialPanel_, &MaterialPanel::strokeFinished, this, [this] { endInteraction(); });
    connect(lightPanel_, &LightPanel::strokeStarted, this, [this] { beginInteraction(); });
    connect(lightPanel_, &LightPanel::strokeFinished, this, [this] { endInteraction(); });
    connect(probePanel_, &ProbePanel::strokeStarted, this, [this] { beginInteraction(); });
    connect(probePanel_, &ProbePanel::strokeFinished, this, [this] { endInteraction(); });
    connect(cameraPanel_, &CameraPanel::overlaysChanged, this, [this] {
        OverlayOptions o;
        o.grid = cameraPanel_->gridBox()->isChecked();
        o.proxies = cameraPanel_->proxiesBox()->isChecked();
        o.outlines = cameraPanel_->outlinesBox()->isChecked();
        viewport_->setOverlays(o);
    });
}

int MainWindow::dockNeed(Qt::DockWidgetArea area) const {
    int need = 0;
    for (QDockWidget* d : findChildren<QDockWidget*>()) {
        if (dockWidgetArea(d) != area || d->isFloating() || !d->isVisible()) continue;
        auto* scroll = qobject_cast<QScrollArea*>(d->widget());
        if (!scroll || !scroll->widget()) continue;
        need = std::max(need, scroll->widget()->minimumSizeHint().width() +
                                  scroll->verticalScrollBar()->sizeHint().width() + 2 * scroll->frameWidth() + 4);
    }
    return need;
}

void MainWindow::fitDocks() {
    // The docks as wide as their panels' fields need where the window has room for that and
    // the viewport keeps half of it (the docks kept their first width and clipped their fields
    // even on a maximised window); narrower otherwise, scrolling across.
    QDockWidget* left = nullptr;
    QDockWidget* right = nullptr;
    for (QDockWidget* d : findChildren<QDockWidget*>()) {
        if (d->isFloating() || !d->isVisible()) continue;
        if (!left && dockWidgetArea(d) == Qt::LeftDockWidgetArea) left = d;
        if (!right && dockWidgetArea(d) == Qt::RightDockWidgetArea) right = d;
    }
    int needLeft = left ? dockNeed(Qt::LeftDockWidgetArea) : 0, needRight = right ? dockNeed(Qt::RightDockWidgetArea) : 0;
    const int budget = width() / 2;
    if (needLeft + needRight > budget && needLeft + needRight > 0) {
        const double k = double(budget) / double(needLeft + needRight);
        needLeft = int(needLeft * k), needRight = int(needRight * k);
    }
    QList<QDockWidget*> docks;
    QList<int> sizes;
    if (left) docks << left, sizes << needLeft;
    if (right) docks << right, sizes << needRight;
    if (!docks.isEmpty()) resizeDocks(docks, sizes, Qt::Horizontal);
}

void MainWindow::resizeEvent(QResizeEvent* e) {
    QMainWindow::resizeEvent(e);
    fitDocks();
}

void MainWindow::createToolbar() {
    QToolBar* bar = addToolBar(tr("Tools"));
    bar->setObjectName("toolbar");
    // The menu's Undo says what it undoes ("Undo Move sphere"); on the toolbar that text made
    // every button after it jump at each edit. The toolbar's buttons keep one word and say
    // the rest in their tooltips.
    for (const char* name : {"undo", "redo"}) {
        QAction* full = action(name);
        auto* shortAction = new QAction(full->text().remove(QLatin1Char('&')), bar);
        shortAction->setObjectName(QStringLiteral("%1Toolbar").arg(QLatin1String(name)));
        auto sync = [shortAction, full] {
            shortAction->setEnabled(full->isEnabled());
            shortAction->setToolTip(full->text().remove(QLatin1Char('&')));
        };
        connect(full, &QAction::changed, shortAction, sync);
        connect(shortAction, &QAction::triggered, full, &QAction::trigger);
        sync();
        bar->addAction(shortAction);
    }
    bar->addSeparator();
    bar->addActions(viewGroup_->actions());
    bar->addSeparator();
    bar->addActions(gizmoGroup_->actions());
    bar->addSeparator();
    bar->addWidget(new QLabel(tr(" Exposure ")));
    exposure_ = new QSlider(Qt::Horizontal);
    exposure_->setObjectName("exposureSlider");
    exposure_->setRange(-80, 80);
    exposure_->setMaximumWidth(180);
    exposure_->setToolTip(
        tr("Display exposure in stops, kept in the project (exports use it "
           "only with File > Apply Display Exposure to Exports)"));
    // One undo step per stroke of the slider.
    connect(exposure_, &QSlider::sliderPressed, this,
            [this] { exposureKey_ = doc_->newMergeKey(); });
    connect(exposure_, &QSlider::sliderReleased, this, [this] { exposureKey_ = -1; });
    connect(exposure_, &QSlider::valueChanged, this,
            [this](int v) { setDisplayExposure(float(v) / 10.0f); });
    bar->addWidget(exposure_);
    exposureLabel_ = new QLabel;
    exposureLabel_->setObjectName("exposureLabel");
    exposureLabel_->setMinimumWidth(60);
    exposureLabel_->setToolTip(tr("Display exposure in stops (EV)"));
    bar->addWidget(exposureLabel_);
    bar->addWidget(new QLabel(tr(" View ")));
    viewBox_ = new QComboBox;
    viewBox_->setObjectName("viewTransform");
    for (const std::string& v : available_views()) viewBox_->addItem(QString::fromStdString(v));
    viewBox_->setToolTip(tr("View transform of the viewport and of PNG/JPEG/TIFF exports, kept in the project: "
                            "Standard leaves an untouched photo pixel as it came in; Filmic rolls off "
                            "highlights of HDR plates"));
    connect(viewBox_, &QComboBox::textActivated, this, [this](const QString& v) { setDisplayView(v); });
    bar->addWidget(viewBox_);
    connect(doc_, &Document::changed, this, [this] { showDisplaySettings(); });
    showDisplaySettings();
}

void MainWindow::connectRenderer() {
    connect(doc_, &Document::changed, this, [this](Change change) {
        if (change == Change::None || !doc_->isOpen()) return;
        if (interactive_) editedWhileInteractive_ = true;
        requestRender(interactive_);
    });
    connect(doc_, &Document::reloaded, this, [this] {
        failPendingExport(tr("another project was opened before its render was ready"));
        failedGeneration_ = 0;
        renderer_->forgetPicture();
        viewport_->setFrame(nullptr);
        viewport_->setRenderSize(options_.renderSize);
        viewport_->fitView();
    });
    connect(renderer_, &RenderController::frameReady, this,
            [this](std::shared_ptr<const RenderFrame> f) { onFrame(f); });
    connect(renderer_, &RenderController::failed, this, [this](const QString& message) {
        failedGeneration_ = renderer_->generation();
        if (showMissingFiles()) {
            // A file moved or deleted behind the studio's back: relinking is the way on.
            waiting_ = true;
            failPendingExport(tr("files the project reads are missing"));
            relinkFiles();
            return;
        }
        failPendingExport(message);
        status_->setText(tr("Render failed"));
        error(tr("Render failed"), message);
    });
    connect(renderer_, &RenderController::assetWarnings, this, [this](const QStringList& list) {
        warnings_->setText(list.size() == 1 ? tr("⚠ 1 asset warning") : tr("⚠ %1 asset warnings").arg(list.size()));
        warnings_->setToolTip(list.join("\n"));
        warnings_->setVisible(!list.isEmpty());
    });
    connect(renderer_, &RenderController::refinementFinished, this,
            [this] { status_->setText(status_->text() + tr("  ·  done")); });
}

void MainWindow::onFrame(const std::shared_ptr<const RenderFrame>& f) {
    viewport_->setFrame(f);
    // Larger frames than this are left raw: here the filter takes about 4 s a megapixel and
    // its buffers several times the frame.
    constexpr size_t kMaxDenoisePixels = 2500000;
    // An edit's quick pass is denoised too (the edit seen clean within a second); a drag's
    // frames are not: the filter would take longer than the frame.
    if (renderer_->denoise() && !f->drag && f->update.image.size() <= kMaxDenoisePixels) {
        // A refined frame is denoised on its own thread, when the scheduler says (the first of
        // each new state at once, so the edit is seen clean within a pass).
        const bool newState = f->generation != denoisedGeneration_ || !sinceDenoise_.isValid();
        if (RenderScheduler::denoise_due(newState, f->update.finished,
                                         newState ? 0.0 : double(sinceDenoise_.elapsed()), denoiser_->lastMs())) {
            denoiser_->request(f);
            denoisedGeneration_ = f->generation;
            sinceDenoise_.start();
        }
    }
    // The renderer only delivers frames of the latest request: a full one is the current state.
    if (!pendingExport_.isEmpty() && !f->preview) {
        const QString path = pendingExport_;
        pendingExport_.clear();
        exportProgress_->setVisible(false);
        writeExport(path, *f);
    }
    const RenderStats& s = f->update.stats;
    // The error of what is shown: the denoised picture's where it is shown, else the raw one's.
    const bool denoisedError = renderer_->denoise() && shownErrorGeneration_ == f->generation && !f->preview;
    lastError_ = denoisedError ? shownError_ : s.estimated_rel_error;
    QString text = f->preview ? tr("Preview pass %1").arg(s.passes)
                   : options_.endless ? tr("Pass %1").arg(s.passes)
                   : f->update.target_passes > 0
                       ? tr("Pass %1 / %2").arg(s.passes).arg(f->update.target_passes)
                       : tr("Pass %1 (%2 s budget)").arg(s.passes).arg(f->update.time_budget_s);
    text += tr("  ·  %1 M photons/s").arg(s.photons_per_second / 1e6, 0, 'f', 2);
    text += lastError_ >= 0 ? tr("  ·  est. error %1%%2").arg(lastError_ * 100, 0, 'f', 1).arg(denoisedError ? tr(" denoised") : QString())
                            : tr("  ·  est. error -");
    if (!f->preview && options_.endless && s.mean_changed_value > 0) {
        text += tr(" (stops at %1%)").arg(renderer_->stopError(s) * 100, 0, 'f', 1);
    }
    status_->setText(text);
}

void MainWindow::onShownError(uint64_t generation, double error) {
    if (generation != renderer_->generation() || !renderer_->denoise()) return;
    shownError_ = error;
    shownErrorGeneration_ = generation;
    // The denoised picture the artist sees is clean: the refinement stops after its next pass.
    const auto f = renderer_->lastFullFrame();
    if (options_.endless && f && f->generation == generation && renderer_->shownClean(error, f->update.stats))
        renderer_->finishClean();
}

void MainWindow::beginInteraction() {
    interactive_ = true;
    denoiser_->setPaused(true);  // the drag's previews need both cores
    editedWhileInteractive_ = false;
}

void MainWindow::endInteraction() {
    interactive_ = false;
    denoiser_->setPaused(false);
    // The quick passes stop; refinement of the final state starts.
    if (editedWhileInteractive_) requestRender(false);
    editedWhileInteractive_ = false;
}

void MainWindow::commitTypedValue() {
    if (auto* field = qobject_cast<QAbstractSpinBox*>(QApplication::focusWidget()))
        field->interpretText();
}

void MainWindow::showKeyMap() {
    QString rows;
    auto row = [&rows](const QString& keys, const QString& what) {
        rows += QStringLiteral("<tr><td><b>%1</b></td><td>%2</td></tr>")
                    .arg(keys.toHtmlEscaped(), what.toHtmlEscaped());
    };
    const char* names[] = {"new",      "open",      "save",          "saveAs",    "export",
                           "quit",     "undo",      "redo",          "grab",      "rotate",
                           "scale",    "delete",    "hide",          "duplicate", "import",
                           "onGround", "viewPhoto", "viewAugmented", "viewdL",    "overlays",
                           "fit",      "keyMap"};
    // The named actions in their order, then every other action with a key (the list once
    // left Denoise's D out): a key the studio answers to is never missing here.
    QList<QAction*> listed;
    for (const char* name : names)
        if (QAction* a = action(name)) listed << a;
    for (QAction* a : findChildren<QAction*>())
        if (!listed.contains(a) && !a->objectName().isEmpty()) listed << a;
    for (QAction* a : listed) {
        if (a->shortcuts().isEmpty()) continue;
        QStringList keys;
        for (const QKeySequence& k : a->shortcuts()) keys << k.toString(QKeySequence::NativeText);
        row(keys.join(QStringLiteral(", ")), a->text().remove(QLatin1Char('&')));
    }
    row(tr("Enter / left click"), tr("Confirm a G / R / S transform"));
    row(tr("X / Y / Z during G / R / S"), tr("Keep to that world axis (again: free)"));
    row(tr("Digits during G / R / S"), tr("Type the value: metres, degrees or a factor"));
    row(tr("Esc / right click"), tr("Cancel a transform or a pick"));
    row(tr("Left drag"), tr("Transform the object or light in the toolbar's mode (a light's rotate tilts it)"));
    row(tr("Wheel / middle drag"), tr("Zoom / pan the view"));
    const QString text =
        tr("<table cellspacing='6'>%1</table><p>In number fields the letter keys stay shortcuts "
           "(digits, '.', '-' and e are typed); in the name field every letter is typed. Undo "
           "and redo always act on the project.</p>")
            .arg(rows);
    auto* box = new QMessageBox(QMessageBox::NoIcon, tr("Keyboard shortcuts"), text,
                                QMessageBox::Close, this);
    box->setObjectName("keyMapDialog");
    box->setTextFormat(Qt::RichText);
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();
}

bool MainWindow::event(QEvent* e) {
    if (e->type() == QEvent::StatusTip) return true;
    return QMainWindow::event(e);
}

void MainWindow::error(const QString& title, const QString& text) {
    reporter_->error(this, title, text);
}

}  // namespace dp::ui
