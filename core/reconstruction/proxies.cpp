#include "reconstruction/proxies.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>

#include "base/error.h"

namespace dp {

namespace {

constexpr float kDegPerRad = 180.0f / kPi;

/// Rotation about +Y by `theta` radians, as Transform's Euler Y angle turns (X goes to -Z).
vec3 rotate_y(const vec3& v, float theta) {
    float c = std::cos(theta), s = std::sin(theta);
    return vec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z);
}

/// Yaw (radians) of a horizontal direction, such that rotate_y(+X, yaw) points along it.
float yaw_of(const vec3& d) {
    return std::atan2(-d.z, d.x);
}

std::string pixel_text(vec2 p) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "(%g, %g)", p.x, p.y);
    return buf;
}

float rms_reprojection(const Camera& camera, const std::vector<vec2>& clicks,
                       const std::vector<vec3>& fitted) {
    double sum = 0;
    for (const vec2& c : clicks) {
        double best = std::numeric_limits<double>::max();
        for (const vec3& f : fitted) {
            vec2 px;
            if (!camera.project(f, px)) continue;
            best = std::min(best, double(glm::dot(px - c, px - c)));
        }
        sum += best;
    }
    return clicks.empty() ? 0.0f : float(std::sqrt(sum / clicks.size()));
}

void check_size(float value, const char* field, const char* what) {
    if (!(value > 0) || !std::isfinite(value))
        throw InputError(
            "", field,
            std::string(what) + " must be a positive number (got " + std::to_string(value) + ")");
}

}  // namespace

vec3 point_on_plane_y(const Camera& camera, vec2 pixel, float height, const std::string& field) {
    if (!std::isfinite(pixel.x) || !std::isfinite(pixel.y))
        throw InputError("", field, "image point is not a finite number");
    Ray ray = camera.generate_ray(pixel.x, pixel.y);
    const float dy = height - ray.org.y;
    const std::string where = "image point " + pixel_text(pixel);
    if (dy == 0)
        throw InputError("", field, "the camera lies in the plane y = " + std::to_string(height));
    if (ray.dir.y == 0 || (dy > 0) != (ray.dir.y > 0)) {
        if (height == 0 && dy < 0)
            throw InputError("", field,
                             where + " is above the horizon: its ray never meets the ground");
        throw InputError("", field,
                         where + ": its ray never meets the plane y = " + std::to_string(height));
    }
    const float t = dy / ray.dir.y;
    vec3 p = ray.org + t * ray.dir;
    // Within about 0.06 degrees of the horizon the point's distance is ill-conditioned.
    float horizontal = std::hypot(p.x - ray.org.x, p.z - ray.org.z);
    if (!std::isfinite(t) || horizontal > 1000.0f * std::abs(dy))
        throw InputError("", field,
                         where + " is too close to the horizon to place it on the plane");
    return p;
}

ProxyFit ground_proxy(const Camera& camera, float max_distance, const std::string& name) {
    const vec3 eye = camera.position();
    if (!(eye.y > 0))
        throw InputError("", "camera",
                         "the camera is not above the ground (y = " + std::to_string(eye.y) + ")");
    if (max_distance < 0 || !std::isfinite(max_distance))
        throw InputError("", "max_distance", "must be >= 0 (0 picks 20 times the camera height)");
    if (max_distance == 0) max_distance = 20.0f * eye.y;

    // The image border, densely enough that a distorted border is followed too.
    std::vector<vec2> border;
    const int n = 32;
    const float W = float(camera.width()) - 0.5f, H = float(camera.height()) - 0.5f;
    for (int k = 0; k <= n; ++k) {
        float s = float(k) / n;
        border.push_back({-0.5f + s * (W + 0.5f), -0.5f});
        border.push_back({-0.5f + s * (W + 0.5f), H});
        border.push_back({-0.5f, -0.5f + s * (H + 0.5f)});
        border.push_back({W, -0.5f + s * (H + 0.5f)});
    }
    std::vector<vec3> points;
    bool sees_ground = false;
    for (const vec2& b : border) {
        Ray r = camera.generate_ray(b.x, b.y);
        vec3 flat(r.dir.x, 0, r.dir.z);
        float flat_len = glm::length(flat);
        if (r.dir.y < 0) {
            sees_ground = true;
            vec3 p = r.org + (-r.org.y / r.dir.y) * r.dir;
            vec3 off(p.x - eye.x, 0, p.z - eye.z);
            float d = glm::length(off);
            if (d > max_distance) p = vec3(eye.x, 0, eye.z) + off * (max_distance / d);
            points.push_back(vec3(p.x, 0, p.z));
        } else if (flat_len > 0) {
            // Above the horizon: the ground it would show lies at the far limit.
            points.push_back(vec3(eye.x, 0, eye.z) + flat * (max_distance / flat_len));
        }
    }
    if (!sees_ground)
        throw InputError("", "camera", "the camera does not see the ground (y = 0) at all");

    // Turn the rectangle to the camera's heading; looking straight down, to the image's up.
    vec3 heading(camera.forward().x, 0, camera.forward().z);
    if (glm::length(heading) < 1e-3f) {
        vec3 image_up = -glm::transpose(camera.rotation())[1];
        heading = vec3(image_up.x, 0, image_up.z);
    }
    heading = glm::normalize(heading);
    // The plane's local -Z (its texture's up) looks along the heading.
    const float theta = std::atan2(-heading.x, -heading.z);
    vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const vec3& p : points) {
        vec3 q = rotate_y(p, -theta);
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
    vec3 size = hi - lo;
    vec3 margin = 0.02f * vec3(std::max(size.x, size.z));
    lo -= margin;
    hi += margin;
    size = hi - lo;
    vec3 centre = rotate_y(0.5f * (lo + hi), theta);

    ProxyFit fit;
    fit.proxy.name = name;
    fit.proxy.shape.kind = Shape::Kind::Plane;
    fit.proxy.shape.size = vec3(size.x, 1, size.z);
    fit.proxy.transform.translation = vec3(centre.x, 0, centre.z);
    fit.proxy.transform.rotation_deg = vec3(0, theta * kDegPerRad + 0.0f, 0);
    for (vec3 c :
         {vec3(lo.x, 0, hi.z), vec3(hi.x, 0, hi.z), vec3(hi.x, 0, lo.z), vec3(lo.x, 0, lo.z)})
        fit.footprint.push_back(rotate_y(c, theta));
    return fit;
}

ProxyFit wall_proxy(const Camera& camera, vec2 a, vec2 b, float height, float thickness,
                    const std::string& name) {
    check_size(height, "height", "the wall's height");
    check_size(thickness, "thickness", "the wall's thickness");
    vec3 A = point_on_plane_y(camera, a, 0, "points[0]");
    vec3 B = point_on_plane_y(camera, b, 0, "points[1]");
    vec3 e = B - A;
    float len = glm::length(e);
    float reach = std::max(glm::length(A - camera.position()), glm::length(B - camera.position()));
    if (len <= 1e-5f * reach)
        throw InputError("", "points", "the two points of the wall fall on the same ground point");
    e /= len;
    vec3 n(-e.z, 0, e.x);
    vec3 mid = 0.5f * (A + B);
    vec3 to_wall(mid.x - camera.position().x, 0, mid.z - camera.position().z);
    if (glm::dot(n, to_wall) < 0) n = -n;  // the thickness goes behind the clicked face

    ProxyFit fit;
    fit.proxy.name = name;
    fit.proxy.shape.kind = Shape::Kind::Box;
    fit.proxy.shape.size = vec3(len, height, thickness);
    fit.proxy.transform.translation = mid + 0.5f * thickness * n + vec3(0, 0.5f * height, 0);
    fit.proxy.transform.rotation_deg = vec3(0, yaw_of(e) * kDegPerRad + 0.0f, 0);
    fit.footprint = {A, B, B + thickness * n, A + thickness * n};
    return fit;
}

ProxyFit box_proxy(const Camera& camera, const std::vector<vec2>& corners, float height,
                   const std::string& name) {
    if (corners.size() != 3 && corners.size() != 4)
        throw InputError("", "points",
                         "a box footprint needs 3 or 4 corner points (got " +
                             std::to_string(corners.size()) + ")");
    check_size(height, "height", "the box's height");
    std::vector<vec3> p;
    for (size_t i = 0; i < corners.size(); ++i)
        p.push_back(point_on_plane_y(camera, corners[i], 0, "points[" + std::to_string(i) + "]"));
    if (p.size() == 3) p.push_back(p[0] + p[2] - p[1]);

    // Convex and simple: every turn the same way, none (nearly) straight or folded back.
    float perimeter = 0;
    for (int i = 0; i < 4; ++i) perimeter += glm::length(p[(i + 1) % 4] - p[i]);
    int sign = 0;
    for (int i = 0; i < 4; ++i) {
        vec3 e = p[(i + 1) % 4] - p[i], f = p[(i + 2) % 4] - p[(i + 1) % 4];
        float le = glm::length(e), lf = glm::length(f);
        if (le <= 1e-5f * perimeter || lf <= 1e-5f * perimeter)
            throw InputError("", "points", "two footprint corners fall on the same ground point");
        float turn = (e.z * f.x - e.x * f.z) / (le * lf);  // sine of the turn, + counter-clockwise
        if (std::abs(turn) < 0.02f)
            throw InputError("", "points",
                             "the footprint is degenerate: three corners are (nearly) collinear");
        int s = turn > 0 ? 1 : -1;
        if (sign != 0 && s != sign)
            throw InputError(
                "", "points",
                "the footprint corners must go around the box in order (the outline crosses itself "
                "or is not convex)");
        sign = s;
    }
    if (sign < 0) std::reverse(p.begin(), p.end());  // counter-clockwise seen from above

    // Orientation: the edges' directions averaged modulo 90 degrees (angle quadrupled).
    std::complex<double> acc(0, 0);
    for (int i = 0; i < 4; ++i) {
        vec3 e = p[(i + 1) % 4] - p[i];
        acc += double(glm::length(e)) * std::polar(1.0, 4.0 * double(yaw_of(e)));
    }
    const float theta = float(std::arg(acc) / 4);
    vec3 centroid = 0.25f * (p[0] + p[1] + p[2] + p[3]);
    float hx = 0, hz = 0;
    for (const vec3& q : p) {
        vec3 l = rotate_y(q - centroid, -theta);
        hx += 0.25f * std::abs(l.x);
        hz += 0.25f * std::abs(l.z);
    }

    ProxyFit fit;
    fit.proxy.name = name;
    fit.proxy.shape.kind = Shape::Kind::Box;
    fit.proxy.shape.size = vec3(2 * hx, height, 2 * hz);
    fit.proxy.transform.translation = vec3(centroid.x, 0.5f * height, centroid.z);
    fit.proxy.transform.rotation_deg = vec3(0, theta * kDegPerRad + 0.0f, 0);
    for (vec3 c : {vec3(-hx, 0, hz), vec3(hx, 0, hz), vec3(hx, 0, -hz), vec3(-hx, 0, -hz)})
        fit.footprint.push_back(centroid + rotate_y(c, theta));
    fit.rms_error_px = rms_reprojection(camera, corners, fit.footprint);
    return fit;
}

bool add_or_replace_real_proxy(Project& project, RealProxy proxy) {
    auto same = std::find_if(project.real.begin(), project.real.end(),
                             [&](const RealProxy& r) { return r.name == proxy.name; });
    if (same == project.real.end()) {
        project.real.push_back(std::move(proxy));
        return false;
    }
    proxy.albedo = same->albedo;
    *same = std::move(proxy);
    return true;
}

}  // namespace dp
