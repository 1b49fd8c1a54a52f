#pragma once
#include <QWidget>

#include "camera/camera.h"
#include "gizmo.h"
#include "scene/project.h"

namespace dp::ui {

class Document;

/// A second view of the scene, away from the photo's camera, to judge and fix where things
/// stand in depth: from the top, the front, the side, or orbiting freely. It draws the photo's
/// camera as its frustum, the ground grid, the real proxies, the objects and the lights as the
/// viewport's overlays do. A click selects (a light's glyph before the object behind it);
/// dragging the selection applies the toolbar's mode as the viewport's gizmo does (a move from
/// the top or orbiting goes over the ground and onto real surfaces; from the front or the side
/// across and up), one undo step per drag; dragging elsewhere orbits (free view) or pans, and
/// the wheel zooms.
class SceneView : public QWidget {
    Q_OBJECT
public:
    enum class View { Top, Front, Side, Orbit };
    explicit SceneView(Document* doc, QWidget* parent = nullptr);

    void setView(View view);
    View view() const { return view_; }
    /// What dragging the selection does: the viewport's toolbar mode (move, rotate, scale).
    void setGizmoMode(GizmoMode mode) { mode_ = mode; }
    /// The camera this view draws with, at the widget's size (pixel centres at integers).
    Camera camera() const;
    /// Widget position of a world point; false if behind the view.
    bool widgetPosition(const vec3& world, QPointF& out) const;
    QSize sizeHint() const override { return {320, 240}; }

Q_SIGNALS:
    void viewChanged(dp::ui::SceneView::View view);
    /// A drag of the selection begins and ends (the renderer previews meanwhile, as for the
    /// viewport's drags).
    void dragStarted();
    void dragFinished();

protected:
    void paintEvent(QPaintEvent*) override;
    void mousePressEvent(QMouseEvent*) override;
    void mouseMoveEvent(QMouseEvent*) override;
    void mouseReleaseEvent(QMouseEvent*) override;
    void wheelEvent(QWheelEvent*) override;

private:
    /// The middle and the size of what is to be seen: the photo's camera, the objects, the
    /// lights and the near part of the proxies.
    void sceneBounds(vec3& centre, float& radius) const;
    /// The view's camera for those bounds.
    Camera cameraFor(vec3 centre, float radius) const;
    /// The selection's transform moved by the drag from `from` to `to` (camera pixels).
    Transform dragged(const Transform& start, bool light, vec2 from, vec2 to) const;

    Document* doc_;
    View view_ = View::Top;
    GizmoMode mode_ = GizmoMode::Translate;
    float azimuth_ = 30, elevation_ = 25;  ///< the free view's direction, degrees
    float zoom_ = 1;
    vec3 pan_{0.0f};
    enum class Drag { None, Selection, Orbit, Pan } drag_ = Drag::None;
    QPointF pressPos_, lastPos_;
    Transform startTransform_;
    Camera dragCamera_;  ///< the view as the drag began (a move does not move the view)
    int dragKey_ = -1;
};

}  // namespace dp::ui
