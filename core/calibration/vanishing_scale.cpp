#include "calibration/vanishing_scale.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "base/error.h"

namespace dp::calib {

namespace {

/// The camera with the world origin under the origin click and the camera one unit above the
/// ground: every scale is a factor on this frame.
struct UnitFrame {
    glm::dmat3 R;
    Intrinsics k;
    glm::dvec3 c1;  ///< camera centre at height 1
    std::string source;

    glm::dvec3 ray(const ImagePoint& p) const {
        return glm::transpose(R) * glm::dvec3((p.x - k.cx) / k.fx, (p.y - k.cy) / k.fy, 1.0);
    }
    /// Ground point (y = 0) seen at `p`; throws above the horizon.
    glm::dvec3 ground(const ImagePoint& p, const std::string& field,
                      const std::string& what) const {
        const glm::dvec3 r = ray(p);
        if (!(r.y < 0))
            throw InputError(source, field, what + " must be on the ground, below the horizon");
        return c1 + (-c1.y / r.y) * r;
    }
    ImagePoint pixel(const glm::dvec3& world) const {
        const glm::dvec3 c = R * (world - c1);
        return ImagePoint(k.fx * c.x / c.z + k.cx, k.fy * c.y / c.z + k.cy);
    }
    /// Height (in units of the camera height) of the point above the foot's ground point that
    /// comes closest to the top's ray, and that point.
    double vertical_height(const VanishingInput::Distance& v, glm::dvec3* top = nullptr) const {
        const glm::dvec3 G = ground(v.a, "vertical", "the vertical length's foot (first point)");
        const glm::dvec3 rt = ray(v.b), up(0, 1, 0), w0 = G - c1;
        // Closest points of the lines G + h up and c1 + s rt (normal equations in h, s).
        const double b = glm::dot(up, rt), c = glm::dot(rt, rt), d = glm::dot(up, w0),
                     e = glm::dot(rt, w0);
        const double det = c - b * b;
        if (!(std::abs(det) > 1e-12 * c))
            throw InputError(source, "vertical",
                             "the vertical length's top is seen straight above or below the "
                             "camera: its height cannot be measured");
        const double s = (e - b * d) / det, h = -d + b * s;
        if (top) *top = G + h * up;
        return h;
    }
};

UnitFrame unit_frame(const glm::dmat3& R, const Intrinsics& k, const VanishingInput& in,
                     const std::string& source) {
    UnitFrame f{R, k, glm::dvec3(0.0), source};
    const glm::dvec3 ro = f.ray(in.origin);
    if (!(ro.y < 0))
        throw InputError(source, "origin",
                         "the origin must be a point on the ground, below the horizon");
    f.c1 = -ro / -ro.y;
    return f;
}

}  // namespace

glm::dvec3 place_camera(const glm::dmat3& R, const Intrinsics& k, const VanishingInput& in,
                        const std::string& source) {
    const int scales =
        int(bool(in.camera_height)) + int(bool(in.distance)) + int(bool(in.vertical));
    if (scales > 1)
        throw InputError(source, "",
                         "give one scale only: the camera height, a ground distance or a "
                         "vertical length");
    const UnitFrame f = unit_frame(R, k, in, source);
    double height = 0;
    if (in.camera_height) {
        if (!(*in.camera_height > 0))
            throw InputError(source, "camera-height", "the camera height must be > 0 metres");
        height = *in.camera_height;
    } else if (in.distance) {
        const auto& d = *in.distance;
        if (!(d.metres > 0))
            throw InputError(source, "distance", "the distance must be > 0 metres");
        const std::string what = "the distance's end points";
        const double unit = glm::length(f.ground(d.a, "distance", what) -
                                        f.ground(d.b, "distance", what));
        if (!(unit > 0)) throw InputError(source, "distance", "the distance's end points coincide");
        height = d.metres / unit;
    } else if (in.vertical) {
        const auto& v = *in.vertical;
        if (!(v.metres > 0))
            throw InputError(source, "vertical", "the vertical length must be > 0 metres");
        const double h = f.vertical_height(v);
        if (!(h > 0))
            throw InputError(source, "vertical",
                             "the vertical length's top (second point) must be above its foot "
                             "on the ground (first point) in the photo");
        height = v.metres / h;
    } else {
        throw InputError(source, "",
                         "give a scale: the camera height, a distance between two ground "
                         "points or a vertical length");
    }
    return height * f.c1;
}

std::vector<ImagePoint> placement_points(const VanishingInput& in) {
    std::vector<ImagePoint> p = {in.origin};
    for (const auto* d : {&in.distance, &in.vertical})
        if (*d) p.push_back((*d)->a), p.push_back((*d)->b);
    return p;
}

VanishingInput with_placement_points(VanishingInput in, const std::vector<ImagePoint>& p) {
    size_t i = 0;
    in.origin = p[i++];
    for (auto* d : {&in.distance, &in.vertical})
        if (*d) (*d)->a = p[i++], (*d)->b = p[i++];
    return in;
}

std::vector<std::string> scale_warnings(const glm::dmat3& R, const Intrinsics& k,
                                        const VanishingInput& in, double sigma_px) {
    std::vector<std::string> out;
    char buf[512];
    if (in.distance) {
        // A ground line through the point below the camera and a vertical edge both image
        // onto lines through the vertical vanishing point: the clicks cannot tell them apart.
        const glm::dvec3 up(R[1][0], R[1][1], R[1][2]);
        const glm::dvec3 v(k.fx * up.x + k.cx * up.z, k.fy * up.y + k.cy * up.z, up.z);
        const glm::dvec2 a = in.distance->a, b = in.distance->b, m = 0.5 * (a + b);
        const glm::dvec2 seg = b - a, to_v = glm::dvec2(v) - m * v.z;
        const double len = glm::length(seg), sin_angle =
            std::abs(seg.x * to_v.y - seg.y * to_v.x) / std::max(1e-300, len * glm::length(to_v));
        if (len > 10 && sin_angle < std::sin(std::numbers::pi / 180))
            out.push_back("the distance's two points line up with the vertical direction in the "
                          "photo: if they are the ends of a vertical edge, give them as a "
                          "vertical length; as a ground distance they run straight away from "
                          "the camera, where the scale is least precise");
    }
    if (in.vertical) {
        const UnitFrame f = unit_frame(R, k, in, "");
        glm::dvec3 top;
        f.vertical_height(*in.vertical, &top);
        const double off = glm::length(f.pixel(top) - in.vertical->b);
        if (off > std::max(2.0, 4 * sigma_px)) {
            std::snprintf(buf, sizeof(buf),
                          "the vertical length's top is %.1f px off the vertical through its "
                          "foot: click the foot on the ground straight below the top",
                          off);
            out.push_back(buf);
        }
    }
    return out;
}

}  // namespace dp::calib
