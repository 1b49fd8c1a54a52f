#include "calibration/vanishing.h"

#include <array>
#include <cmath>

#include <opencv2/core.hpp>

#include "base/error.h"
#include "calibration/cv_util.h"

namespace dp {
namespace {

constexpr const char* kAxisName[3] = {"x", "y", "z"};

glm::dvec3 homog(const ImagePoint& p) { return glm::dvec3(p, 1.0); }

/// Vanishing point as a finite image point; throws when its lines are parallel in the image.
ImagePoint finite_vp(const std::vector<LineSegment>& segs, int axis, double image_size,
                     const std::string& source) {
    const std::string field = kAxisName[axis];
    if (segs.size() < 2)
        throw InputError(source, field,
                         "need at least 2 line segments per direction, got " +
                             std::to_string(segs.size()));
    for (const LineSegment& s : segs)
        if (glm::length(s.b - s.a) < 1e-6 * image_size)
            throw InputError(source, field, "a line segment has zero length");
    const glm::dvec3 v = vanishing_point(segs);
    // Farther than ~1000 image sizes: the lines are parallel in the image.
    if (std::abs(v.z) * 1000.0 * image_size <= glm::length(glm::dvec2(v)))
        throw InputError(source, field,
                         "the " + field + " line segments are parallel in the image, so their "
                         "vanishing point is at infinity; draw lines that converge in "
                         "perspective (or use another direction)");
    return glm::dvec2(v) / v.z;
}

/// Orthocentre of a triangle: the principal point given three orthogonal vanishing points.
ImagePoint orthocentre(const ImagePoint& a, const ImagePoint& b, const ImagePoint& c) {
    // Altitude from a is perpendicular to bc: (p - a).(c - b) = 0; likewise from b.
    const glm::dvec2 u = c - b, w = c - a;
    const double det = u.x * w.y - u.y * w.x;
    const double r0 = glm::dot(a, u), r1 = glm::dot(b, w);
    return ImagePoint((r0 * w.y - u.y * r1) / det, (u.x * r1 - w.x * r0) / det);
}

}  // namespace

glm::dvec3 vanishing_point(const std::vector<LineSegment>& segments) {
    // Conditioned: lines through points relative to the first end point, scaled to unit size.
    const ImagePoint o = segments[0].a;
    double scale = 0;
    for (const LineSegment& s : segments)
        scale = std::max({scale, glm::length(s.a - o), glm::length(s.b - o)});
    scale = scale > 0 ? scale : 1;
    cv::Mat A(int(segments.size()), 3, CV_64F);
    for (size_t i = 0; i < segments.size(); ++i) {
        glm::dvec3 l = glm::cross(homog((segments[i].a - o) / scale),
                                  homog((segments[i].b - o) / scale));
        l /= glm::length(glm::dvec2(l));
        A.at<double>(int(i), 0) = l.x, A.at<double>(int(i), 1) = l.y, A.at<double>(int(i), 2) = l.z;
    }
    cv::Mat w, u, vt;
    cv::SVDecomp(A, w, u, vt, cv::SVD::FULL_UV);
    const glm::dvec3 v(vt.at<double>(2, 0), vt.at<double>(2, 1), vt.at<double>(2, 2));
    // Back to pixels: x = o + scale * x'.
    return glm::dvec3(scale * v.x + o.x * v.z, scale * v.y + o.y * v.z, v.z);
}

CalibrationResult calibrate_vanishing(const VanishingInput& in, int width, int height,
                                      const std::string& source) {
    if (width <= 0 || height <= 0) throw InputError(source, "size", "the image size must be positive");
    const double image_size = double(std::max(width, height));
    const std::array<const std::vector<LineSegment>*, 3> segs = {&in.x, &in.y, &in.z};
    std::array<bool, 3> used{};
    std::array<ImagePoint, 3> vp{};
    int count = 0;
    for (int a = 0; a < 3; ++a) {
        if (segs[size_t(a)]->empty()) continue;
        vp[size_t(a)] = finite_vp(*segs[size_t(a)], a, image_size, source);
        used[size_t(a)] = true;
        ++count;
    }
    if (count < 2)
        throw InputError(source, "",
                         "need line segments for at least two of the directions x, y, z");

    Intrinsics k = Intrinsics::centred(width, height, 1.0);
    std::vector<std::string> warnings;
    if (count == 3 && !in.focal_px) {
        const ImagePoint p = orthocentre(vp[0], vp[1], vp[2]);
        if (!std::isfinite(p.x) || !std::isfinite(p.y))
            throw InputError(source, "", "the three vanishing points are collinear");
        k.cx = p.x, k.cy = p.y;
    }
    if (in.focal_px) {
        check_focal(*in.focal_px, source, "focal");
        k.fx = k.fy = *in.focal_px;
    } else {
        const ImagePoint c(k.cx, k.cy);
        double f2 = 0;
        int pairs = 0;
        for (int a = 0; a < 3; ++a)
            for (int b = a + 1; b < 3; ++b)
                if (used[size_t(a)] && used[size_t(b)]) {
                    f2 += -glm::dot(vp[size_t(a)] - c, vp[size_t(b)] - c);
                    ++pairs;
                }
        f2 /= pairs;
        if (!(f2 > 0))
            throw InputError(source, "",
                             "these directions cannot be orthogonal in a pinhole photo (the "
                             "focal length squared would be " + std::to_string(f2) +
                                 " px^2 <= 0): check that each group of lines is parallel in "
                                 "the world and the groups are at right angles");
        k.fx = k.fy = std::sqrt(f2);
    }
    if (k.fx > 50 * image_size)
        warnings.push_back("the focal length is very long: the vanishing points are far away "
                           "and it is poorly determined");

    // Camera-space directions of the world axes (up to sign).
    std::array<glm::dvec3, 3> d{};
    for (int a = 0; a < 3; ++a)
        if (used[size_t(a)])
            d[size_t(a)] = glm::normalize(glm::dvec3((vp[size_t(a)].x - k.cx) / k.fx,
                                                     (vp[size_t(a)].y - k.cy) / k.fy, 1.0));
    // Signs: Y up in the image (camera -y), X to the right (camera +x), Z = X x Y.
    if (used[1] && d[1].y > 0) d[1] = -d[1];
    if (used[0] && d[0].x < 0) d[0] = -d[0];
    if (!used[1]) {
        d[1] = glm::cross(d[2], d[0]);
        if (d[1].y > 0) d[2] = -d[2], d[1] = -d[1];
    } else if (!used[0]) {
        d[0] = glm::cross(d[1], d[2]);
        if (d[0].x < 0) d[2] = -d[2], d[0] = -d[0];
    }
    d[2] = used[2] && glm::dot(d[2], glm::cross(d[0], d[1])) < 0 ? -d[2] : d[2];
    if (!used[2]) d[2] = glm::cross(d[0], d[1]);
    // Nearest rotation to the three directions (its columns are the world axes in camera space).
    cv::Matx33d D;
    for (int a = 0; a < 3; ++a)
        for (int r = 0; r < 3; ++r) D(r, a) = d[size_t(a)][r];
    cv::Matx33d U, Vt;
    cv::Vec3d sv;
    cv::SVD::compute(D, sv, U, Vt);
    const glm::dmat3 R = calib::from_cv(U * Vt);

    // Scale: rays in world space; the camera sits at -s * ray(origin), above the ground.
    const glm::dmat3 Rt = glm::transpose(R);
    auto ray = [&](const ImagePoint& p) {
        return Rt * glm::dvec3((p.x - k.cx) / k.fx, (p.y - k.cy) / k.fy, 1.0);
    };
    const glm::dvec3 ro = ray(in.origin);
    if (!(ro.y < 0))
        throw InputError(source, "origin",
                         "the origin must be a point on the ground, below the horizon");
    double s = 0;
    if (in.camera_height) {
        if (!(*in.camera_height > 0))
            throw InputError(source, "camera-height", "the camera height must be > 0 metres");
        s = *in.camera_height / -ro.y;
    } else if (in.distance) {
        const auto& dist = *in.distance;
        if (!(dist.metres > 0))
            throw InputError(source, "distance", "the distance must be > 0 metres");
        const glm::dvec3 c1 = -ro / -ro.y;  // camera at height 1
        auto ground = [&](const ImagePoint& p) {
            const glm::dvec3 r = ray(p);
            if (!(r.y < 0))
                throw InputError(source, "distance",
                                 "the distance's end points must be on the ground, below the "
                                 "horizon");
            return c1 + (-c1.y / r.y) * r;
        };
        const double unit = glm::length(ground(dist.a) - ground(dist.b));
        if (!(unit > 0))
            throw InputError(source, "distance", "the distance's end points coincide");
        s = dist.metres / unit / -ro.y;
    } else {
        throw InputError(source, "",
                         "give a scale: the camera height or a distance between two ground "
                         "points");
    }
    const glm::dvec3 C = -s * ro;

    CalibrationResult r;
    r.intrinsics = k;
    r.pose.R = R;
    r.pose.t = -(R * C);
    r.warnings = warnings;
    // Error figure: distance of the segment end points from the lines joining the segment
    // midpoints to the fitted vanishing points.
    double sum = 0;
    int n = 0;
    for (int a = 0; a < 3; ++a) {
        const glm::dvec3 col(R[a][0], R[a][1], R[a][2]);  // world axis a in camera space
        const glm::dvec3 v(k.fx * col.x + k.cx * col.z, k.fy * col.y + k.cy * col.z, col.z);
        for (const LineSegment& sgm : *segs[size_t(a)]) {
            glm::dvec3 l = glm::cross(homog(0.5 * (sgm.a + sgm.b)), v);
            const double norm = glm::length(glm::dvec2(l));
            if (norm == 0) continue;
            for (const ImagePoint& p : {sgm.a, sgm.b}) {
                const double e = glm::dot(l, homog(p)) / norm;
                sum += e * e;
                ++n;
            }
        }
    }
    r.rms_px = n ? std::sqrt(sum / n) : 0.0;
    return r;
}

}  // namespace dp
