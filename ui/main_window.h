#pragma once
#include <QMainWindow>
#include <memory>

#include "display.h"
#include "scene/project.h"
#include "studio_options.h"

class QAction;
class QActionGroup;
class QLabel;
class QMenu;
class QSlider;
class QToolButton;

namespace dp::ui {

class Autosave;
class CalibrationPanel;
class CameraPanel;
class Document;
class ErrorReporter;
class MaterialPanel;
class ProbeAlignPanel;
class ProbePanel;
class ProxyPanel;
class RenderController;
class ScenePanel;
class SettingsPanel;
class Viewport;
struct RenderFrame;

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
    Viewport* viewport() const { return viewport_; }
    MaterialPanel* materialPanel() const { return materialPanel_; }
    CameraPanel* cameraPanel() const { return cameraPanel_; }
    CalibrationPanel* calibrationPanel() const { return calibrationPanel_; }
    ProxyPanel* proxyPanel() const { return proxyPanel_; }
    Autosave* autosave() const { return autosave_; }
    QAction* action(const QString& objectName) const;

    /// Display exposure in stops (the toolbar slider; PNG export uses it).
    void setDisplayExposure(float stops);

    /// Offers to recover autosaved work, if any (called once the window is shown).
    void checkRecovery();

    // File operations; each reports its errors through the reporter and returns false.
    bool openProject(const QString& path);
    bool saveProject();
    bool saveProjectAs(const QString& path);
    bool newProject(const QString& photo, const QString& probe, bool mirrorBall = false);
    /// Writes the latest full-size render: .png/.jpg (display exposure) or .exr with layers
    /// dL, alpha and shadow.
    bool exportImage(const QString& path);
    bool importMesh(const QString& path);

    // Edits.
    void addObject(Shape::Kind kind);
    void duplicateSelected();
    void deleteSelected();
    void toggleSelectedVisible();

protected:
    void closeEvent(QCloseEvent*) override;
    void dragEnterEvent(QDragEnterEvent*) override;
    void dropEvent(QDropEvent*) override;

private:
    void createActions();
    void createMenus();
    void createDocks();
    void createToolbar();
    void connectRenderer();
    void onFrame(const std::shared_ptr<const RenderFrame>& frame);
    void beginInteraction();
    void endInteraction();
    void updateTitle();
    void addRecent(const QString& path);
    void rebuildRecentMenu();
    void restoreSettings();
    void error(const QString& title, const QString& text);
    // Dialog front-ends of the file operations.
    void openDialog();
    void saveAsDialog();
    void newDialog(const QString& photo = {}, const QString& probe = {});
    void exportDialog();
    void importDialog();

    StudioOptions options_;
    std::unique_ptr<ErrorReporter> ownReporter_;
    ErrorReporter* reporter_;
    Document* doc_;
    RenderController* renderer_;
    Viewport* viewport_;
    ScenePanel* scenePanel_ = nullptr;
    MaterialPanel* materialPanel_ = nullptr;
    SettingsPanel* settingsPanel_ = nullptr;
    ProbePanel* probePanel_ = nullptr;
    CameraPanel* cameraPanel_ = nullptr;
    CalibrationPanel* calibrationPanel_ = nullptr;
    ProxyPanel* proxyPanel_ = nullptr;
    ProbeAlignPanel* probeAlignPanel_ = nullptr;
    Autosave* autosave_ = nullptr;
    QLabel* status_;
    QToolButton* warnings_;  ///< "n asset warnings", hidden while there are none
    QSlider* exposure_ = nullptr;
    QMenu* recentMenu_ = nullptr;
    QActionGroup *viewGroup_ = nullptr, *gizmoGroup_ = nullptr;
    QStringList recent_;
    double lastError_ = -1;
    bool interactive_ = false, editedWhileInteractive_ = false;
};

}  // namespace dp::ui
