#pragma once
#include <optional>
#include <QElapsedTimer>
#include <QMainWindow>
#include <QPointer>
#include <memory>
#include <string>
#include <vector>

#include "display.h"
#include "gizmo.h"
#include "scene/project.h"
#include "studio_options.h"

class QAction;
class QActionGroup;
class QLabel;
class QMenu;
class QProgressBar;
class QSlider;
class QComboBox;
class QToolButton;

namespace dp {
struct RenderFrame;
}

namespace dp::ui {

class Autosave;
class CalibrationPanel;
class FarmDialog;
class CameraPanel;
class Document;
class ErrorReporter;
class LightPanel;
class MaterialPanel;
class MissingFilesDialog;
class ProbeAlignPanel;
class ProbePanel;
class ProxyPanel;
class RenderController;
class ScenePanel;
class SettingsPanel;
class DenoiseWorker;
class ShortcutPolicy;
class Viewport;

/// The studio's main window: viewport in the middle, panels docked around it, menus with the
/// usual shortcuts. Every operation a menu offers is also a public method, which is what the
/// tests drive (with the same code paths as the menus, minus the file dialogs).
class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(const StudioOptions& options = {}, QWidget* parent = nullptr);
    ~MainWindow() override;

    Document* document() const { return doc_; }
    RenderController* renderer() const { return renderer_; }
    /// The refined frames' denoiser; null where the library is not installed.
    DenoiseWorker* denoiser() const { return denoiser_; }
    Viewport* viewport() const { return viewport_; }
    MaterialPanel* materialPanel() const { return materialPanel_; }
    /// The selected light's settings (shown in place of the material while a light is selected).
    LightPanel* lightPanel() const { return lightPanel_; }
    /// Edit > Add > Light, and the scene panel's Add Light button.
    QMenu* lightMenu() const { return lightMenu_; }
    CameraPanel* cameraPanel() const { return cameraPanel_; }
    CalibrationPanel* calibrationPanel() const { return calibrationPanel_; }
    /// File > Render on Farm...: the dialog, made on first use and kept (a render goes on
    /// while it is closed).
    FarmDialog* farmDialog();
    ProxyPanel* proxyPanel() const { return proxyPanel_; }
    ScenePanel* scenePanel() const { return scenePanel_; }
    SettingsPanel* settingsPanel() const { return settingsPanel_; }
    Autosave* autosave() const { return autosave_; }
    QAction* action(const QString& objectName) const;

    /// Display exposure in stops: the project's `display.exposure`, set as one undoable edit
    /// (the toolbar slider and its label show it). Exports apply it only when asked
    /// (setExportAppliesExposure).
    void setDisplayExposure(float stops);
    float displayExposure() const;
    /// The view transform of the viewport and of PNG/JPEG/TIFF exports: the project's
    /// `display.view`, set as one undoable edit (the toolbar's View box).
    void setDisplayView(const QString& view);
    /// PNG / JPEG exports at the display exposure (on) or at 0 EV, the render as it is (off,
    /// the default). File > Apply Display Exposure to Exports.
    void setExportAppliesExposure(bool on);
    bool exportAppliesExposure() const;
    /// Overlays over the augmented and dL views (View > Overlays, H); never over the photo.
    void setOverlaysVisible(bool on);
    /// The augmented view with the render's change denoised (View > Denoise, D): previews at
    /// once, refined frames every few seconds on a thread of their own. Off, with the reason
    /// in its tooltip, where Open Image Denoise is not installed.
    void setDenoise(bool on);

    /// Offers to recover the autosaved work of a studio that stopped without a clean quit (its
    /// own copy: Autosave), newest first; the first accepted becomes this window's document,
    /// declined ones are deleted, and the rest wait for the next start.
    void checkRecovery();

    // File operations; each reports its errors through the reporter and returns false. They
    // replace the document without asking: the menus, Open Recent, drops and closing the window
    // ask Save / Discard / Cancel first (maybeSave).

    /// Opens a project once the core would render it (its files readable, its scene valid:
    /// scene_problem); otherwise the document and its undo history stay as they were. A project
    /// whose files have moved is opened as it is, with the render waiting, and the Missing Files
    /// dialog is offered (relinkFiles).
    bool openProject(const QString& path);
    bool saveProject();
    /// Writes the project to `path`, never onto one of its inputs. Over the document's own file,
    /// when that changed on disk since this window read or wrote it (another studio saved it),
    /// it first asks: keep mine (overwrite), take theirs (load the file as an undoable step, so
    /// Undo brings this window's edits back), save as, or cancel.
    bool saveProjectAs(const QString& path);
    bool newProject(const QString& photo, const QString& probe, bool mirrorBall = false);
    /// Writes a full-size render of the document as it is now: .png/.jpg (display exposure) or
    /// .exr with layers dL, alpha and shadow. If the latest full pass shows an earlier state (an
    /// edit is still rendering), the export waits for the first full pass of the current state
    /// without blocking (the status bar shows it) and writes that. Returns false for what fails
    /// at once; exportFinished() reports every export, now or later.
    bool exportImage(const QString& path);
    /// An export is waiting for the current state's pass.
    bool exportPending() const { return !pendingExport_.isEmpty(); }
    /// Adds a mesh object (the unsaved work is checkpointed to the recovery file first).
    bool importMesh(const QString& path);
    /// Makes fSpy's camera the project's (File > Import fSpy..., a .fspy dropped on the
    /// window): from an fSpy project or fSpy's exported camera parameters JSON (read_fspy), as
    /// one undoable edit. The camera is scaled to the project's photo where that is the same
    /// picture at another size, and refused where the aspect ratios differ. A project whose
    /// photo file is missing gets the .fspy's embedded photo, written next to the project. With
    /// no project open, the embedded photo is written next to the .fspy and starts a new
    /// project with the light probe `probe` (none given: the New Project dialog asks, the photo
    /// filled in). Errors are reported; returns whether the camera was applied.
    bool importFspy(const QString& path, const QString& probe = {});
    /// Opens the dialog that relinks the project's files (File > Relink Files..., and by itself
    /// when a project opens or a render fails with files missing). It is window-modal but does
    /// not block: relinkDialog() is it while it shows. OK relinks as one undoable edit.
    void relinkFiles();
    MissingFilesDialog* relinkDialog() const;
    /// The fields of the project's files that are missing ("photo.path", ...): while there are
    /// any, nothing is rendered and the status bar says so.
    QStringList missingFiles() const;
    /// Asks Save / Discard / Cancel if the document has unsaved changes; true when the caller
    /// may go on (saved, discarded, or nothing to save). Cancel and Esc keep everything.
    bool maybeSave();

    // Edits.
    void addObject(Shape::Kind kind);
    /// Adds a light of `kind` above the real surface under the view centre, shining down
    /// (new_light), and selects it.
    void addLight(VirtualLight::Kind kind);
    /// Duplicates the selected object or light.
    void duplicateSelected();
    /// Deletes the selected object or light.
    void deleteSelected();
    void toggleSelectedVisible();
    /// Moves the selected object down (or up) onto the real surface below it (Object > On
    /// Ground, End).
    void dropSelectedToSurface();

  Q_SIGNALS:
    /// An export was written (ok) or failed; `path` as passed to exportImage.
    void exportFinished(const QString& path, bool ok);

protected:
    void closeEvent(QCloseEvent*) override;
    void resizeEvent(QResizeEvent*) override;
    /// Swallows status tips: hovering a menu or a button would hide the render's status line
    /// and wipe a message the user has not read yet. The same words are in the tooltips.
    bool event(QEvent* e) override;
    void dragEnterEvent(QDragEnterEvent*) override;
    void dropEvent(QDropEvent*) override;

private:
    void createActions();
    /// The Add Light menu and its actions (addPointLight, addSpotLight, addRectLight,
    /// addDiskLight).
    void createLightMenu();
    void createMenus();
    void createDocks();
    void createToolbar();
    void connectRenderer();
    /// Asks the renderer for the document as it is, unless files are missing (then the render
    /// stops and waits, and the status bar says for what). Returns whether it asked.
    bool requestRender(bool interactive);
    /// Shows the missing files in the status bar (hidden when there are none); returns whether
    /// there are any.
    bool showMissingFiles();
    void onFrame(const std::shared_ptr<const RenderFrame>& frame);
    /// The denoiser's estimate of the shown picture's error (DenoiseWorker::shownError).
    void onShownError(uint64_t generation, double error);
    void beginInteraction();
    void endInteraction();
    void updateTitle();
    void addRecent(const QString& path);
    void rebuildRecentMenu();
    void restoreSettings();
    void error(const QString& title, const QString& text);
    /// Applies what a number field holds but has not applied yet (before saving or exporting).
    void commitTypedValue();
    bool writeExport(const QString& path, const RenderFrame& f);
    /// Why `path` may not be written: it is one of the files the project reads (the project file
    /// too with `projectFileToo`); "" when it may.
    QString inputOverwriteProblem(const QString& path, bool projectFileToo) const;
    /// Before a save over the document's own file: nullopt to go on, else the save's result
    /// after the user answered that the file changed on disk.
    std::optional<bool> settleDiskConflict(const QString& path);
    bool takeDiskVersion(const QString& path);
    void failPendingExport(const QString& why);
    void startModal(GizmoMode mode);
    /// The slider and label show the project's display exposure.
    void showDisplaySettings();
    /// The widest minimum of the panels docked in `area` (visible ones), scroll bar included.
    int dockNeed(Qt::DockWidgetArea area) const;
    /// Sizes the left and right docks to their panels' needs while the viewport keeps half the
    /// window; scaled down together where it would not.
    void fitDocks();
    /// Switches the project's display.match_plate (one undo step).
    void setMatchPlate(bool on);
    /// The camera new objects are placed for: the viewport's, or the photo's before it has one.
    Camera placementCamera() const;
    void showKeyMap();
    void openRecent(const QString& path);
    // Dialog front-ends of the file operations.
    void openDialog();
    void saveAsDialog();
    void newDialog(const QString& photo = {}, const QString& probe = {});
    void exportDialog();
    void importDialog();
    void importFspyDialog();

    StudioOptions options_;
    std::unique_ptr<ErrorReporter> ownReporter_;
    ErrorReporter* reporter_;
    Document* doc_;
    RenderController* renderer_;
    Viewport* viewport_;
    ScenePanel* scenePanel_ = nullptr;
    MaterialPanel* materialPanel_ = nullptr;
    LightPanel* lightPanel_ = nullptr;
    QMenu* lightMenu_ = nullptr;
    SettingsPanel* settingsPanel_ = nullptr;
    DenoiseWorker* denoiser_ = nullptr;
    QElapsedTimer sinceDenoise_;  ///< since a refined frame was last sent to the denoiser
    uint64_t denoisedGeneration_ = 0;  ///< the request whose frames were last sent to the denoiser
    ProbePanel* probePanel_ = nullptr;
    CameraPanel* cameraPanel_ = nullptr;
    CalibrationPanel* calibrationPanel_ = nullptr;
    FarmDialog* farmDialog_ = nullptr;
    ProxyPanel* proxyPanel_ = nullptr;
    ProbeAlignPanel* probeAlignPanel_ = nullptr;
    Autosave* autosave_ = nullptr;
    QLabel* status_;
    QToolButton* warnings_;  ///< "n asset warnings", hidden while there are none
    QToolButton* missing_;   ///< "n missing files", hidden while there are none
    QPointer<MissingFilesDialog> relinkDialog_;
    bool waiting_ = false;                    ///< the render waits for missing files
    std::vector<std::string> renderedPaths_;  ///< the file paths of the last render asked for
    QSlider* exposure_ = nullptr;
    QLabel* exposureLabel_ = nullptr;
    QComboBox* viewBox_ = nullptr;
    int exposureKey_ = -1;  ///< merge key of the slider stroke under way (-1: none)
    QMenu* recentMenu_ = nullptr;
    QActionGroup *viewGroup_ = nullptr, *gizmoGroup_ = nullptr;
    QStringList recent_;
    ShortcutPolicy* shortcutPolicy_ = nullptr;
    QString pendingExport_;
    QProgressBar* exportProgress_ = nullptr;
    uint64_t failedGeneration_ = 0;  ///< renderer generation whose render failed (0: none)
    double lastError_ = -1;
    double shownError_ = -1;            ///< the denoised picture's estimated error (DenoiseWorker::shownError)
    uint64_t shownErrorGeneration_ = 0; ///< the request it is of
    bool interactive_ = false, editedWhileInteractive_ = false;
};

}  // namespace dp::ui
