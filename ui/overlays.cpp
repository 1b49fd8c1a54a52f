#include "overlays.h"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <array>
#include <cmath>

#include "gizmo.h"
#include "placement.h"
#include "project_edit.h"

namespace dp::ui {

namespace {

/// Draws world segments, clipped against the camera's near plane and split so distortion and
/// perspective bend them as they should.
class LineDrawer {
public:
    LineDrawer(QPainter& p, const Camera& c, const QTransform& t) : p_(p), c_(c), t_(t) {}

    void line(vec3 a, vec3 b, int pieces = 4) {
        const float near = 1e-3f;
        const float za = cam_z(a), zb = cam_z(b);
        if (za <= near && zb <= near) return;
        if (za <= near) a = a + (b - a) * ((near - za) / (zb - za));
        if (zb <= near) b = b + (a - b) * ((near - zb) / (za - zb));
        QPainterPath path;
        for (int i = 0; i <= pieces; ++i) {
            vec2 px;
            if (!c_.project(a + (b - a) * (float(i) / float(pieces)), px)) return;
            const QPointF q = t_.map(QPointF(px.x, px.y));
            if (i == 0)
                path.moveTo(q);
            else
                path.lineTo(q);
        }
        p_.drawPath(path);
    }

    /// Widget position of a world point; false behind the camera.
    bool point(const vec3& w, QPointF& out) const {
        vec2 px;
        if (cam_z(w) <= 1e-3f || !c_.project(w, px)) return false;
        out = t_.map(QPointF(px.x, px.y));
        return true;
    }

    void circle(const vec3& centre, const vec3& u, const vec3& v, float r, int pieces = 48) {
        for (int i = 0; i < pieces; ++i) {
            const float a0 = 2 * kPi * float(i) / float(pieces),
                        a1 = 2 * kPi * float(i + 1) / float(pieces);
            line(centre + r * (std::cos(a0) * u + std::sin(a0) * v),
                 centre + r * (std::cos(a1) * u + std::sin(a1) * v), 1);
        }
    }

private:
    float cam_z(const vec3& w) const { return (c_.rotation() * w + c_.translation()).z; }
    QPainter& p_;
    const Camera& c_;
    const QTransform& t_;
};

void draw_box(LineDrawer& d, const glm::mat4& m, const vec3& size) {
    std::array<vec3, 8> v;
    for (int i = 0; i < 8; ++i) {
        const vec3 local = 0.5f * size * vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
        v[i] = vec3(m * glm::vec4(local, 1));
    }
    for (int i = 0; i < 8; ++i)
        for (int bit = 1; bit < 8; bit <<= 1)
            if (!(i & bit)) d.line(v[i], v[i | bit], 1);
}

void draw_plane(LineDrawer& d, const glm::mat4& m, const vec3& size) {
    std::array<vec3, 4> v;
    const float hx = 0.5f * size.x, hz = 0.5f * size.z;
    const std::array<vec2, 4> corners = {vec2(-hx, -hz), vec2(hx, -hz), vec2(hx, hz),
                                         vec2(-hx, hz)};
    for (int i = 0; i < 4; ++i) v[i] = vec3(m * glm::vec4(corners[i].x, 0, corners[i].y, 1));
    for (int i = 0; i < 4; ++i) d.line(v[i], v[(i + 1) % 4], 8);
}

void draw_shape(LineDrawer& d, const Shape& s, const Transform& t) {
    const glm::mat4 m = t.matrix();
    switch (s.kind) {
        case Shape::Kind::Box:
            draw_box(d, m, s.size);
            break;
        case Shape::Kind::Plane:
            draw_plane(d, m, s.size);
            break;
        case Shape::Kind::Sphere: {
            const vec3 c = vec3(m * glm::vec4(0, 0, 0, 1));
            const float r = s.radius * std::max({t.scale.x, t.scale.y, t.scale.z});
            d.circle(c, vec3(1, 0, 0), vec3(0, 0, 1), r);
            break;
        }
        case Shape::Kind::Mesh:
            draw_box(d, m, vec3(0.2f));
            break;  // bounds unknown here
    }
}

/// The selection's gizmo axes: X red, Y green, Z blue, `len` long from `c`.
void draw_axes(QPainter& painter, LineDrawer& d, const vec3& c, float len) {
    painter.setPen(QPen(QColor(230, 60, 60), 2));
    d.line(c, c + vec3(len, 0, 0), 1);
    painter.setPen(QPen(QColor(60, 200, 60), 2));
    d.line(c, c + vec3(0, len, 0), 1);
    painter.setPen(QPen(QColor(70, 110, 240), 2));
    d.line(c, c + vec3(0, 0, len), 1);
}

/// The sun glyph of a light's position, at a fixed size on screen so it can be found at any
/// distance: a disk with eight rays.
void draw_bulb(QPainter& p, QPointF c, bool filled) {
    p.setBrush(filled ? p.pen().color() : QColor(Qt::transparent));
    p.drawEllipse(c, 4.0, 4.0);
    p.setBrush(Qt::NoBrush);
    for (int i = 0; i < 8; ++i) {
        const double a = i * kPi / 4;
        const QPointF d(std::cos(a), std::sin(a));
        p.drawLine(c + 6.5 * d, c + 10.0 * d);
    }
}

void draw_light(QPainter& painter, LineDrawer& d, const Project& project, const VirtualLight& l,
                float scale) {
    const vec3 pos = l.transform.translation;
    const glm::mat3 r = glm::mat3(l.transform.matrix());
    const vec3 axis = glm::normalize(r * vec3(0, -1, 0));
    QPointF at;
    if (d.point(pos, at)) draw_bulb(painter, at, l.kind == VirtualLight::Kind::Point);
    // How high it hangs: a dashed line down to the real surface below.
    const QPen pen = painter.pen();
    painter.setPen(QPen(pen.color(), 1.0, Qt::DashLine));
    d.line(pos, vec3(pos.x, surface_below(project, pos), pos.z), 1);
    painter.setPen(pen);
    const vec3 side = glm::normalize(glm::cross(axis, std::abs(axis.y) < 0.99f ? vec3(0, 1, 0) : vec3(1, 0, 0)));
    const vec3 up = glm::cross(axis, side);
    if (l.kind == VirtualLight::Kind::Spot) {
        // The cone, cut a scene-sized length along the axis.
        const float half = glm::radians(std::min(l.spot_angle_deg, 170.0f) * 0.5f);
        const float len = scale, rad = len * std::tan(half);
        const vec3 c = pos + len * axis;
        d.circle(c, side, up, rad, 32);
        for (int i = 0; i < 4; ++i) {
            const float a = float(i) * kPi / 2;
            d.line(pos, c + rad * (std::cos(a) * side + std::sin(a) * up), 4);
        }
    } else if (l.kind == VirtualLight::Kind::Rect || l.kind == VirtualLight::Kind::Disk) {
        vec3 q[4];
        light_face(l, q);
        if (l.kind == VirtualLight::Kind::Rect) {
            for (int i = 0; i < 4; ++i) d.line(q[i], q[(i + 1) % 4], 4);
        } else {
            const vec3 c = 0.5f * (q[0] + q[2]);
            d.circle(c, 0.5f * (q[1] - q[0]), 0.5f * (q[3] - q[0]), 1.0f, 32);
        }
        d.line(pos, pos + 0.5f * scale * axis, 1);  // which way it shines
    }
}

/// Where the camera looks: the look-at target, or the origin.
vec3 view_target(const Project& project) {
    return project.camera.model == CameraSpec::Model::LookAt ? project.camera.target : vec3(0);
}

}  // namespace

void draw_overlays(QPainter& painter, const Project& project, const Camera& camera,
                   const QTransform& toWidget, const OverlayOptions& o) {
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing, true);
    painter.setBrush(Qt::NoBrush);
    LineDrawer d(painter, camera, toWidget);
    // Outlines are drawn as a difference: visible on bright and dark photos alike.
    if (o.grid) {
        // Its spacing follows what the view shows of the ground: centimetres at a desk.
        const GroundGrid g = ground_grid(project, camera);
        // A dark line under a light one: seen on any photo (a difference blend vanished on mid-grey).
        const float half = g.spacing * float(g.half_lines);
        for (const QPen& pen : {QPen(QColor(0, 0, 0, 70), 2.0), QPen(QColor(255, 255, 255, 110), 1.0)}) {
            painter.setPen(pen);
            for (int i = -g.half_lines; i <= g.half_lines; ++i) {
                const float k = g.spacing * float(i);
                d.line(g.centre + vec3(k, 0, -half), g.centre + vec3(k, 0, half), 16);
                d.line(g.centre + vec3(-half, 0, k), g.centre + vec3(half, 0, k), 16);
            }
        }
        painter.setPen(QColor(255, 255, 255, 200));
        const QString label = g.spacing >= 1     ? QStringLiteral("grid %1 m").arg(double(g.spacing))
                              : g.spacing >= 0.01 ? QStringLiteral("grid %1 cm").arg(double(g.spacing) * 100)
                                                  : QStringLiteral("grid %1 mm").arg(double(g.spacing) * 1000);
        painter.drawText(toWidget.map(QPointF(4, camera.height() - 6)), label);
    }
    if (o.proxies) {
        painter.setPen(QPen(QColor(80, 200, 255, 160), 0));
        for (const RealProxy& r : project.real) draw_shape(d, r.shape, r.transform);
    }
    if (o.outlines) {
        const vec3 eye = camera.position();
        for (size_t i = 0; i < project.objects.size(); ++i) {
            const VirtualObject& obj = project.objects[i];
            const bool sel = int(i) == o.selected;
            QColor colour = sel ? QColor(255, 190, 40) : QColor(255, 255, 255, 200);
            if (!obj.visible) colour.setAlpha(90);
            painter.setCompositionMode(sel ? QPainter::CompositionMode_SourceOver
                                           : QPainter::CompositionMode_Difference);
            painter.setPen(
                QPen(colour, sel ? 2.0 : 1.0, obj.visible ? Qt::SolidLine : Qt::DashLine));
            vec3 c;
            float r;
            bounding_sphere(obj, c, r);
            // The outline of a sphere is the circle perpendicular to the line of sight.
            const vec3 w = glm::normalize(c - eye);
            const vec3 u = glm::normalize(
                glm::cross(w, std::abs(w.y) < 0.99f ? vec3(0, 1, 0) : vec3(1, 0, 0)));
            d.circle(c, u, glm::cross(w, u), r);
            painter.setCompositionMode(QPainter::CompositionMode_SourceOver);
            if (sel) draw_axes(painter, d, c, 1.5f * r);
        }
        // Lights over everything, in their own warm colour; the selected one brighter.
        const float scale = 0.5f * std::max(0.2f, glm::length(camera.position() - view_target(project)));
        for (size_t i = 0; i < project.lights.size(); ++i) {
            const bool sel = int(i) == o.selectedLight;
            painter.setPen(QPen(sel ? QColor(255, 190, 40) : QColor(255, 235, 150, 220), sel ? 2.0 : 1.2));
            draw_light(painter, d, project, project.lights[i], 0.25f * scale);
            if (sel) draw_axes(painter, d, project.lights[i].transform.translation, 0.15f * scale);
        }
    }
    painter.restore();
}

}  // namespace dp::ui
