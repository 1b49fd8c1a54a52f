#pragma once
#include <QImage>
#include <QWidget>
#include <memory>

#include "display.h"
#include "gizmo.h"
#include "matte_tool.h"
#include "overlays.h"
#include "pick_tool.h"
#include "render_controller.h"

namespace dp::ui {

class Document;

/// Shows the progressive render (photo / augmented / dL), zooms (wheel) and pans (middle
/// mouse), draws the overlays, and moves the selected object or light with the gizmo: click
/// selects (a light's glyph before the object behind it),
/// left-drag applies the toolbar's mode, and startModalTransform (the window's G, R and S keys)
/// makes the object follow the mouse until a click or Enter confirms it; Esc or the right button
/// cancels a drag. While the pick tool is active, left clicks and drags go to it
/// (calibration and proxy tools) and Esc cancels it; so too the matte tool (holdout masks).
class Viewport : public QWidget {
    Q_OBJECT
public:
    explicit Viewport(Document* doc, QWidget* parent = nullptr);

    void setFrame(std::shared_ptr<const RenderFrame> frame);
    /// The frame on screen (null before the first).
    std::shared_ptr<const RenderFrame> frame() const { return frame_; }
    /// Shows denoised pictures in the augmented view (`setDenoised`'s, for refined frames of
    /// the same state).
    void setDenoise(bool on);
    bool denoise() const { return denoise_; }
    /// The denoised augmented image of `frame`; shown while the frames on screen are of its
    /// state (generation), until a newer one comes.
    void setDenoised(std::shared_ptr<const RenderFrame> frame, std::shared_ptr<const Image> image);
    /// Whether the picture shown is a denoised one.
    bool showingDenoised() const { return showingDenoised_; }
    /// Gives the refined pictures of the augmented view the photo's grain and softness (on a
    /// worker; the unmatched picture shows until it is done). Drags and quick passes stay raw.
    void setMatchPlate(bool on);
    bool matchPlate() const { return matchPlate_; }
    /// Whether the picture shown is matched to the plate.
    bool showingMatched() const { return showingMatched_; }
    /// What was measured of the photo, for people (empty before the first match).
    QString plateSummary() const;
    /// Size of the full render in pixels (overlays and picking work in it).
    void setRenderSize(QSize size);
    QSize renderSize() const { return renderSize_; }

    void setViewMode(ViewMode mode);
    void setExposure(float stops);
    float exposure() const { return exposure_; }
    /// The view transform pictures are shown through (the project's display.view and look;
    /// exposure comes from setExposure). An unknown view shows Standard.
    void setView(const ViewSettings& view);
    const ViewSettings& view() const { return view_; }
    void setOverlays(const OverlayOptions& o);
    OverlayOptions overlays() const { return overlays_; }
    void setGizmoMode(GizmoMode mode);
    GizmoMode gizmoMode() const { return gizmo_; }
    /// Blender-style G / R / S: the selected object follows the mouse in `mode` until a left
    /// click or Enter confirms or Esc or a right click cancels; then the toolbar's mode is what
    /// it was before. Starts from the cursor when it is over the viewport, else from the object
    /// (the cursor is moved there). False (nothing starts) without a selection or during a drag.
    bool startModalTransform(GizmoMode mode);
    /// A drag or a modal transform is under way.
    bool transforming() const { return dragging_; }
    /// During a modal transform: the world axis it is constrained to (X, Y or Z pressed: 0, 1,
    /// 2; -1 none) and the value typed so far (Blender's numeric input).
    int transformAxis() const { return axis_; }
    QString typedValue() const { return typed_; }
    /// Grid, proxy wireframes and object outlines (which ones: setOverlays) over the
    /// augmented and dL views; never over the photo, which stays as taken.
    void setOverlaysVisible(bool on);
    bool overlaysVisible() const { return showOverlays_; }
    /// Whether the overlays are drawn in the current view.
    bool overlaysDrawn() const { return showOverlays_ && mode_ != ViewMode::Photo; }
    ViewMode viewMode() const { return mode_; }
    /// The camera the viewport draws and picks with (the render's size).
    Camera viewCamera() const { return camera(); }
    /// Fits the render into the widget (zoom 1, no pan).
    void fitView();

    /// Widget position of a world point (for tests and tools); false if not visible.
    bool widgetPosition(const vec3& world, QPointF& out) const;
    /// The image currently shown (display-transformed), empty before the first frame.
    const QImage& shownImage() const { return shown_; }
    /// Rectangle of the widget covered by the render.
    QRectF imageRect() const;
    /// Widget position of a render pixel (pixel centres at integers).
    QPointF widgetFromRender(QPointF renderPx) const;
    /// The point and segment picker the calibration and proxy tools share.
    PickTool* pickTool() const { return pick_; }
    /// The holdout mask painter (the holdout panel drives it); while active it takes left
    /// clicks and drags before anything else.
    MatteTool* matteTool() const { return matte_; }

Q_SIGNALS:
    void dragStarted();
    void dragFinished();
    void gizmoModeChanged(dp::ui::GizmoMode mode);

protected:
    void paintEvent(QPaintEvent*) override;
    void mousePressEvent(QMouseEvent*) override;
    void mouseMoveEvent(QMouseEvent*) override;
    void mouseReleaseEvent(QMouseEvent*) override;
    void mouseDoubleClickEvent(QMouseEvent*) override;
    void wheelEvent(QWheelEvent*) override;
    void keyPressEvent(QKeyEvent*) override;
    bool event(QEvent*) override;

  private:
    void rebuildImage();
    QTransform imageToWidget() const;
    vec2 toImage(QPointF widget) const;
    Camera camera() const;
    /// An object or a light is selected.
    bool hasSelection() const;
    /// The selected object's or light's transform in `p`.
    Transform& selectionTransform(Project& p) const;
    void beginDrag(QPointF pos);
    void finishDrag(bool cancel);
    /// Applies the drag so far: the typed value if there is one, else the cursor's travel.
    void applyDrag();
    /// Handles a key of the modal transform's numeric input and axes; false if not one.
    bool modalKey(QKeyEvent* e);

    Document* doc_;
    PickTool* pick_;
    MatteTool* matte_;
    std::shared_ptr<const RenderFrame> frame_;
    bool denoise_ = false, showingDenoised_ = false;
    std::shared_ptr<const Image> denoised_;
    uint64_t denoisedGeneration_ = 0;
    int denoisedPasses_ = 0;
    /// The denoised picture is a quick pass's: shown over that pass only, never over the
    /// full-size frames that follow (its half size and eighth of the photons show through).
    bool denoisedPreview_ = false;
    QImage shown_;
    QSize renderSize_;
    class PlateMatchWorker* plate_;
    bool matchPlate_ = false, showingMatched_ = false;
    std::shared_ptr<const Image> matchedSource_, matched_;  ///< the last match, and what it was made from
    std::weak_ptr<const Image> requested_;                   ///< the picture last sent to be matched
    ViewMode mode_ = ViewMode::Augmented;
    float exposure_ = 0;
    ViewSettings view_;
    std::shared_ptr<const DisplayTransform> transform_;  ///< null: the built-in Standard
    OverlayOptions overlays_;
    GizmoMode gizmo_ = GizmoMode::Translate;
    double zoom_ = 1;
    QPointF pan_;
    // Interaction state.
    bool dragging_ = false, panning_ = false;
    QPointF pressPos_, lastPos_;
    Transform dragStart_;
    Project projectAtDrag_;
    int dragKey_ = -1;
    bool modal_ = false;  ///< the drag is a keyed G / R / S, not a mouse drag
    GizmoMode modeBeforeModal_ = GizmoMode::Translate;
    int axis_ = -1;  ///< world axis of the modal transform, -1 none
    QString typed_;  ///< value typed during the modal transform
    bool showOverlays_ = false;
};

}  // namespace dp::ui
