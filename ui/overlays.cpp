#include "overlays.h"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <array>
#include <cmath>

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

}  // namespace

void draw_overlays(QPainter& painter, const Project& project, const Camera& camera,
                   const QTransform& toWidget, const OverlayOptions& o) {
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing, true);
    painter.setBrush(Qt::NoBrush);
    LineDrawer d(painter, camera, toWidget);
    // Grid and outlines are drawn as a difference: visible on bright and dark photos alike.
    if (o.grid) {
        painter.setCompositionMode(QPainter::CompositionMode_Difference);
        painter.setPen(QPen(QColor(255, 255, 255, 90), 0));
        for (int i = -10; i <= 10; ++i) {
            const float k = 0.5f * float(i);
            d.line(vec3(k, 0, -5), vec3(k, 0, 5), 16);
            d.line(vec3(-5, 0, k), vec3(5, 0, k), 16);
        }
        painter.setCompositionMode(QPainter::CompositionMode_SourceOver);
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
            if (sel) {
                const float len = 1.5f * r;
                painter.setPen(QPen(QColor(230, 60, 60), 2));
                d.line(c, c + vec3(len, 0, 0), 1);
                painter.setPen(QPen(QColor(60, 200, 60), 2));
                d.line(c, c + vec3(0, len, 0), 1);
                painter.setPen(QPen(QColor(70, 110, 240), 2));
                d.line(c, c + vec3(0, 0, len), 1);
            }
        }
    }
    painter.restore();
}

}  // namespace dp::ui
