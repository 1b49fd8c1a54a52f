#include "gizmo.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "project_edit.h"
#include "assets/scene_builder.h"

namespace dp::ui {

int pick_object(const Project& project, const Camera& camera, float px, float py) {
    const Ray ray = camera.generate_ray(px, py);
    int best = -1;
    float best_t = INFINITY;
    for (size_t i = 0; i < project.objects.size(); ++i) {
        const VirtualObject& o = project.objects[i];
        if (!o.visible) continue;
        vec3 c;
        float r;
        bounding_sphere(o, c, r);
        const vec3 oc = ray.org - c;
        const float b = glm::dot(oc, ray.dir), cc = glm::dot(oc, oc) - r * r;
        const float disc = b * b - cc;
        if (disc < 0) continue;
        float t = -b - std::sqrt(disc);
        if (t < 0) t = -b + std::sqrt(disc);
        if (t > 0 && t < best_t) {
            best_t = t;
            best = int(i);
        }
    }
    return best;
}

void light_face(const VirtualLight& light, vec3 corners[4]) {
    const glm::mat4 m = light.transform.matrix();
    const float hx = 0.5f * light.size.x;
    const float hz = 0.5f * (light.kind == VirtualLight::Kind::Disk ? light.size.x : light.size.y);
    const vec2 c[4] = {vec2(-hx, -hz), vec2(hx, -hz), vec2(hx, hz), vec2(-hx, hz)};
    for (int i = 0; i < 4; ++i) corners[i] = vec3(m * glm::vec4(c[i].x, 0, c[i].y, 1));
}

int pick_light(const Project& project, const Camera& camera, float px, float py, float radius) {
    const Ray ray = camera.generate_ray(px, py);
    int best = -1;
    float best_d = radius;
    for (size_t i = 0; i < project.lights.size(); ++i) {
        const VirtualLight& l = project.lights[i];
        vec2 at;
        if (camera.project(l.transform.translation, at)) {
            const float d = glm::length(at - vec2(px, py));
            if (d <= best_d) {
                best_d = d;
                best = int(i);
            }
        }
        if (best == int(i) || (l.kind != VirtualLight::Kind::Rect && l.kind != VirtualLight::Kind::Disk))
            continue;
        // The face: the ray meets its plane inside the rectangle (or the disk).
        vec3 q[4];
        light_face(l, q);
        const vec3 u = q[1] - q[0], v = q[3] - q[0], n = glm::cross(u, v);
        const float dn = glm::dot(ray.dir, n);
        if (std::abs(dn) < 1e-12f || best >= 0) continue;
        const float t = glm::dot(q[0] - ray.org, n) / dn;
        if (!(t > 0)) continue;
        const vec3 h = ray.org + t * ray.dir - q[0];
        const float a = glm::dot(h, u) / glm::dot(u, u), b = glm::dot(h, v) / glm::dot(v, v);
        const bool inside = l.kind == VirtualLight::Kind::Disk
                                ? (a - 0.5f) * (a - 0.5f) + (b - 0.5f) * (b - 0.5f) <= 0.25f
                                : a >= 0 && a <= 1 && b >= 0 && b <= 1;
        if (inside) best = int(i);
    }
    return best;
}

namespace {

/// Where the ray through pixel (px, py) meets the plane through `at` with normal `n`.
bool plane_point(const Camera& camera, float px, float py, const vec3& at, const vec3& n, vec3& out) {
    const Ray ray = camera.generate_ray(px, py);
    const float dn = glm::dot(ray.dir, n);
    if (std::abs(dn) < 1e-6f) return false;
    const float t = glm::dot(at - ray.org, n) / dn;
    if (!(t > 0) || !std::isfinite(t)) return false;
    out = ray.org + t * ray.dir;
    return true;
}

}  // namespace

Transform light_drag_transform(GizmoMode mode, const Transform& start, const Camera& camera,
                               vec2 from, vec2 to, int axis) {
    if (mode == GizmoMode::Translate && axis < 0) {
        // A lamp often hangs near the eye's height, where its horizontal plane is seen edge on
        // and a pixel is metres of depth: there it slides across the view at its height.
        const vec3 sight = start.translation - camera.position();
        const float len = glm::length(sight);
        vec3 flat(sight.x, 0, sight.z);
        if (len > 0 && std::abs(sight.y) < 0.17f * len && glm::length(flat) > 1e-6f) {
            flat = glm::normalize(flat);
            vec3 a, b;
            Transform t = start;
            if (plane_point(camera, from.x, from.y, start.translation, flat, a) &&
                plane_point(camera, to.x, to.y, start.translation, flat, b)) {
                t.translation.x += b.x - a.x;
                t.translation.z += b.z - a.z;
            }
            return t;
        }
    }
    if (mode != GizmoMode::Rotate || axis >= 0)
        return axis_drag_transform(mode, start, camera, from, to, axis, nullptr);
    // Tilts about the level axes of the view at the light: across the screen about the line of
    // sight (the light's beam swings the way the mouse goes), up and down about the view's right.
    const vec3 sight = start.translation - camera.position();
    vec3 ahead(sight.x, 0, sight.z);
    ahead = glm::length(ahead) > 1e-6f ? glm::normalize(ahead) : vec3(0, 0, -1);
    const vec3 right = glm::cross(ahead, vec3(0, 1, 0));
    Transform t = start;
    const glm::mat4 turn = glm::rotate(glm::mat4(1), glm::radians(-0.5f * (to.y - from.y)), right) *
                           glm::rotate(glm::mat4(1), glm::radians(0.5f * (to.x - from.x)), -ahead);
    t.rotation_deg = euler_deg(glm::mat3(turn) * glm::mat3(start.matrix()));
    return t;
}

bool ground_point(const Camera& camera, float px, float py, float height, vec3& out) {
    const Ray ray = camera.generate_ray(px, py);
    if (std::abs(ray.dir.y) < 1e-6f) return false;
    const float t = (height - ray.org.y) / ray.dir.y;
    if (!(t > 0) || !std::isfinite(t)) return false;
    out = ray.org + t * ray.dir;
    return true;
}

float support_height(const Project& project, float x, float z) {
    float best = 0;
    for (const RealProxy& r : project.real) {
        const Transform& t = r.transform;
        if (t.rotation_deg.x != 0 || t.rotation_deg.z != 0) continue;  // not lying flat
        if (r.shape.kind != Shape::Kind::Box && r.shape.kind != Shape::Kind::Plane) continue;
        // Into the proxy's frame: undo the translation, then the turn about Y.
        const float a = glm::radians(t.rotation_deg.y);
        const float dx = x - t.translation.x, dz = z - t.translation.z;
        const float lx = std::cos(a) * dx - std::sin(a) * dz;
        const float lz = std::sin(a) * dx + std::cos(a) * dz;
        const vec3 half = 0.5f * r.shape.size * glm::abs(t.scale);
        if (std::abs(lx) > half.x || std::abs(lz) > half.z) continue;
        const float top = t.translation.y + (r.shape.kind == Shape::Kind::Box ? half.y : 0.0f);
        best = std::max(best, top);
    }
    return best;
}

Transform drag_transform(GizmoMode mode, const Transform& start, const Camera& camera, vec2 from,
                         vec2 to, const Project* snap) {
    Transform t = start;
    switch (mode) {
        case GizmoMode::Translate: {
            vec3 a, b;
            const float h = start.translation.y;
            if (ground_point(camera, from.x, from.y, h, a) &&
                ground_point(camera, to.x, to.y, h, b)) {
                t.translation.x += b.x - a.x;
                t.translation.z += b.z - a.z;
                if (snap) {
                    const vec3& s0 = start.translation;
                    t.translation.y += support_height(*snap, t.translation.x, t.translation.z) -
                                       support_height(*snap, s0.x, s0.z);
                }
            }
            break;
        }
        case GizmoMode::Rotate:
            t.rotation_deg.y = start.rotation_deg.y + 0.5f * (to.x - from.x);
            t.rotation_deg.y = std::remainder(t.rotation_deg.y, 360.0f);
            break;
        case GizmoMode::Scale: {
            vec2 c;
            if (!camera.project(start.translation, c)) break;
            const float d0 = glm::length(from - c), d1 = glm::length(to - c);
            if (d0 < 1.0f) break;
            const float k = std::clamp(d1 / d0, 0.01f, 100.0f);
            t.scale = start.scale * k;
            break;
        }
    }
    return t;
}

vec3 rotate_about_world_axis(const vec3& e, int axis, float degrees) {
    // M = Rz Ry Rx: a world turn about Z composes with Rz; about Y it commutes past Rz = I; about
    // X past Rz = Ry = I. Those cases stay exact (no round trip through a matrix).
    vec3 out = e;
    if (axis == 2 || (axis == 1 && e.z == 0) || (axis == 0 && e.y == 0 && e.z == 0)) {
        out[axis] = std::remainder(e[axis] + degrees, 360.0f);
        return out;
    }
    Transform a, b;
    a.rotation_deg = e;
    b.rotation_deg[axis] = degrees;
    return euler_deg(glm::mat3(b.matrix()) * glm::mat3(a.matrix()));
}

vec3 euler_deg(const glm::mat3& r) {
    // r = Rz(c) Ry(b) Rx(a), glm's m[col][row].
    const float sb = std::clamp(-r[0][2], -1.0f, 1.0f);
    const float by = std::asin(sb);
    float ax, cz;
    if (std::abs(sb) < 0.99999f) {
        ax = std::atan2(r[1][2], r[2][2]);
        cz = std::atan2(r[0][1], r[0][0]);
    } else {  // gimbal lock: only a + c (or a - c) is defined
        ax = 0;
        cz = std::atan2(-r[1][0], r[1][1]);
    }
    return vec3(glm::degrees(ax), glm::degrees(by), glm::degrees(cz));
}

Transform typed_transform(GizmoMode mode, const Transform& start, int axis, float value) {
    Transform t = start;
    switch (mode) {
        case GizmoMode::Translate:
            t.translation[axis < 0 ? 0 : axis] += value;
            break;
        case GizmoMode::Rotate:
            t.rotation_deg =
                rotate_about_world_axis(start.rotation_deg, axis < 0 ? 1 : axis, value);
            break;
        case GizmoMode::Scale:
            if (axis < 0)
                t.scale = start.scale * value;
            else
                t.scale[axis] = start.scale[axis] * value;
            break;
    }
    return t;
}

Transform axis_drag_transform(GizmoMode mode, const Transform& start, const Camera& camera,
                              vec2 from, vec2 to, int axis, const Project* snap) {
    if (axis < 0) return drag_transform(mode, start, camera, from, to, snap);
    Transform t = start;
    switch (mode) {
        case GizmoMode::Translate: {
            // The axis's image through the object: pixels per metre along it.
            vec3 dir(0);
            dir[axis] = 1;
            vec2 a, b;
            if (!camera.project(start.translation, a) ||
                !camera.project(start.translation + 0.1f * dir, b))
                break;
            const vec2 perMetre = (b - a) / 0.1f;
            const float len2 = glm::dot(perMetre, perMetre);
            if (len2 < 1e-6f) break;  // the axis points at the camera
            t.translation[axis] += glm::dot(to - from, perMetre) / len2;
            break;
        }
        case GizmoMode::Rotate:
            t.rotation_deg =
                rotate_about_world_axis(start.rotation_deg, axis, 0.5f * (to.x - from.x));
            break;
        case GizmoMode::Scale: {
            const Transform u = drag_transform(mode, start, camera, from, to);
            t.scale[axis] = start.scale[axis] * (u.scale.x / start.scale.x);
            break;
        }
    }
    return t;
}

Camera view_camera(const Project& project, int photo_w, int photo_h, int width, int height) {
    return scaled_camera(project.camera, photo_w, photo_h, width, height).build(width, height);
}

}  // namespace dp::ui
