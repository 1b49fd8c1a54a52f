#include "scene_view.h"

#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

#include "document.h"
#include "overlays.h"
#include "photo_geometry.h"
#include "placement.h"

namespace dp::ui {

namespace {

/// The orthographic views are perspective ones from far away: straight lines stay straight and
/// the viewport's overlay drawing serves both.
constexpr float kFar = 200.0f;

const char* view_name(SceneView::View v) {
    switch (v) {
        case SceneView::View::Top: return "Top";
        case SceneView::View::Front: return "Front";
        case SceneView::View::Side: return "Side";
        case SceneView::View::Orbit: return "Free";
    }
    return "";
}

}  // namespace

SceneView::SceneView(Document* doc, QWidget* parent) : QWidget(parent), doc_(doc) {
    setObjectName("sceneView");
    setMinimumSize(160, 120);
    setFocusPolicy(Qt::ClickFocus);
    connect(doc_, &Document::changed, this, [this] { update(); });
    connect(doc_, &Document::selectionChanged, this, [this] { update(); });
    connect(doc_, &Document::reloaded, this, [this] {
        pan_ = vec3(0.0f);
        zoom_ = 1;
        update();
    });
}

void SceneView::setView(View view) {
    view_ = view;
    pan_ = vec3(0.0f);
    update();
    Q_EMIT viewChanged(view);
}

void SceneView::sceneBounds(vec3& centre, float& radius) const {
    const Project& p = doc_->project();
    std::vector<vec3> pts;
    try {
        // The photo's camera, and the real surface it looks at.
        const Camera photo = photo_camera(doc_->assets(), p);
        pts.push_back(photo.position());
        pts.push_back(view_centre_point(p, photo));
    } catch (const std::exception&) {
        // No photo yet: the scene alone.
    }
    for (const VirtualObject& o : p.objects) pts.push_back(o.transform.translation);
    for (const VirtualLight& l : p.lights) pts.push_back(l.transform.translation);
    if (pts.empty()) pts.push_back(vec3(0.0f));
    vec3 lo(INFINITY), hi(-INFINITY);
    for (const vec3& q : pts) lo = glm::min(lo, q), hi = glm::max(hi, q);
    centre = 0.5f * (lo + hi);
    radius = std::max(0.5f * glm::length(hi - lo), 0.25f);
}

Camera SceneView::camera() const {
    vec3 centre;
    float radius;
    sceneBounds(centre, radius);
    return cameraFor(centre, radius);
}

Camera SceneView::cameraFor(vec3 centre, float radius) const {
    centre += pan_;
    const int w = std::max(width(), 2), h = std::max(height(), 2);
    const float fit = 1.25f * radius / zoom_;  // half the view's height, in metres
    vec3 dir, up(0, 1, 0);
    float distance = kFar * radius;
    switch (view_) {
        case View::Top: dir = vec3(0, 1, 0), up = vec3(0, 0, -1); break;
        case View::Front: dir = vec3(0, 0, 1); break;
        case View::Side: dir = vec3(1, 0, 0); break;
        case View::Orbit: {
            const float a = glm::radians(azimuth_), e = glm::radians(elevation_);
            dir = vec3(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
            distance = 3.0f * radius / zoom_;
            break;
        }
    }
    const float vfov = view_ == View::Orbit ? 45.0f : glm::degrees(2.0f * std::atan(fit / distance));
    return Camera::look_at(w, h, centre + distance * dir, centre, up, vfov);
}

bool SceneView::widgetPosition(const vec3& world, QPointF& out) const {
    vec2 px;
    if (!camera().project(world, px)) return false;
    out = QPointF(px.x + 0.5, px.y + 0.5);
    return true;
}

void SceneView::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    painter.fillRect(rect(), QColor(38, 40, 44));
    if (!doc_->isOpen()) return;
    // The scene's bounds once a paint: they read the photo's camera and cast rays.
    vec3 centre;
    float radius;
    sceneBounds(centre, radius);
    const Camera cam = cameraFor(centre, radius);
    auto at = [&](const vec3& world, QPointF& out) {
        vec2 px;
        if (!cam.project(world, px)) return false;
        out = QPointF(px.x + 0.5, px.y + 0.5);
        return true;
    };
    const QTransform toWidget = QTransform::fromTranslate(0.5, 0.5);
    OverlayOptions o;
    o.selected = doc_->selected();
    o.selectedLight = doc_->selectedLight();
    draw_overlays(painter, doc_->project(), cam, toWidget, o);
    // The photo's camera: its eye and the frustum out to what it looks at.
    try {
        const Camera photo = photo_camera(doc_->assets(), doc_->project());
        const float depth = std::max(glm::length(centre - photo.position()), radius);
        const float corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        QPointF eye, far[4];
        bool ok = at(photo.position(), eye);
        for (int k = 0; k < 4; ++k) {
            const Ray r = photo.generate_ray(corners[k][0] * float(photo.width() - 1), corners[k][1] * float(photo.height() - 1));
            ok = ok && at(r.org + r.dir * (depth / std::max(glm::dot(r.dir, photo.forward()), 1e-3f)), far[k]);
        }
        if (ok) {
            painter.setRenderHint(QPainter::Antialiasing);
            painter.setPen(QPen(QColor(120, 220, 255), 1.5));
            for (int k = 0; k < 4; ++k) {
                painter.drawLine(eye, far[k]);
                painter.drawLine(far[k], far[(k + 1) % 4]);
            }
            painter.setBrush(QColor(120, 220, 255));
            painter.drawEllipse(eye, 3, 3);
        }
    } catch (const std::exception&) {
        // No photo to size the frustum by: the scene alone.
    }
    painter.setPen(QColor(230, 230, 230));
    painter.drawText(QPointF(6, 14), tr("%1 view").arg(tr(view_name(view_))));
}

Transform SceneView::dragged(const Transform& start, bool light, vec2 from, vec2 to) const {
    const Camera& cam = dragCamera_;
    if (mode_ != GizmoMode::Translate || view_ == View::Top || view_ == View::Orbit)
        return light ? light_drag_transform(mode_, start, cam, from, to, -1)
                     : drag_transform(mode_, start, cam, from, to, &doc_->project());
    // Front and side: across and up in the view's plane, by the metres a pixel spans there.
    const vec3 right = glm::normalize(glm::cross(cam.forward(), vec3(0, 1, 0)));
    const float depth = glm::dot(start.translation - cam.position(), cam.forward());
    const float per_px = depth / cam.fy();
    Transform t = start;
    t.translation += per_px * ((to.x - from.x) * right - (to.y - from.y) * vec3(0, 1, 0));
    return t;
}

void SceneView::mousePressEvent(QMouseEvent* e) {
    pressPos_ = lastPos_ = e->position();
    if (!doc_->isOpen()) return;
    if (e->button() == Qt::MiddleButton) {
        drag_ = Drag::Pan;
        return;
    }
    if (e->button() != Qt::LeftButton) return;
    dragCamera_ = camera();
    const float px = float(e->position().x() - 0.5), py = float(e->position().y() - 0.5);
    const Project& p = doc_->project();
    const int light = pick_light(p, dragCamera_, px, py, 10.0f);
    if (light >= 0) {
        doc_->selectLight(light);
    } else {
        const int object = pick_object(p, dragCamera_, px, py);
        if (object < 0) {
            drag_ = view_ == View::Orbit ? Drag::Orbit : Drag::Pan;
            return;
        }
        doc_->select(object);
    }
    drag_ = Drag::Selection;
    Q_EMIT dragStarted();
    startTransform_ = doc_->selectedLight() >= 0 ? p.lights[size_t(doc_->selectedLight())].transform
                                                 : p.objects[size_t(doc_->selected())].transform;
    dragKey_ = doc_->newMergeKey();
}

void SceneView::mouseMoveEvent(QMouseEvent* e) {
    const QPointF d = e->position() - lastPos_;
    lastPos_ = e->position();
    switch (drag_) {
        case Drag::None: return;
        case Drag::Orbit:
            azimuth_ -= 0.4f * float(d.x());
            elevation_ = std::clamp(elevation_ + 0.4f * float(d.y()), -89.0f, 89.0f);
            update();
            return;
        case Drag::Pan: {
            const Camera cam = camera();
            const vec3 right = glm::normalize(glm::cross(cam.forward(), view_ == View::Top ? vec3(0, 0, -1) : vec3(0, 1, 0)));
            const vec3 up = glm::cross(right, cam.forward());
            vec3 centre;
            float radius;
            sceneBounds(centre, radius);
            const float per_px = glm::length(centre + pan_ - cam.position()) / cam.fy();
            pan_ -= per_px * (float(d.x()) * right - float(d.y()) * up);
            update();
            return;
        }
        case Drag::Selection: {
            Project p = doc_->project();
            const vec2 from(float(pressPos_.x() - 0.5), float(pressPos_.y() - 0.5)),
                to(float(e->position().x() - 0.5), float(e->position().y() - 0.5));
            const int light = doc_->selectedLight();
            Transform& t = light >= 0 ? p.lights[size_t(light)].transform : p.objects[size_t(doc_->selected())].transform;
            t = dragged(startTransform_, light >= 0, from, to);
            const QString name = QString::fromStdString(light >= 0 ? p.lights[size_t(light)].name
                                                                   : p.objects[size_t(doc_->selected())].name);
            doc_->edit(tr("Move %1").arg(name), p, dragKey_);
            return;
        }
    }
}

void SceneView::mouseReleaseEvent(QMouseEvent*) {
    if (drag_ == Drag::Selection) Q_EMIT dragFinished();
    drag_ = Drag::None;
}

void SceneView::wheelEvent(QWheelEvent* e) {
    zoom_ = std::clamp(zoom_ * float(std::pow(1.15, e->angleDelta().y() / 120.0)), 0.05f, 50.0f);
    update();
}

}  // namespace dp::ui
