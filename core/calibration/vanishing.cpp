#include "calibration/vanishing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <opencv2/core.hpp>

#include "base/error.h"
#include "calibration/cv_util.h"
#include "calibration/least_squares.h"
#include "calibration/reprojection.h"
#include "calibration/vanishing_scale.h"

namespace dp {
namespace {

using calib::LeastSquaresResult;

constexpr const char* kAxisName[3] = {"x", "y", "z"};

glm::dvec3 homog(const ImagePoint& p) {
    return glm::dvec3(p, 1.0);
}
glm::dvec3 column(const glm::dmat3& R, int a) {
    return glm::dvec3(R[a][0], R[a][1], R[a][2]);
}

/// The segments of the directions in use.
struct Axes {
    std::array<const std::vector<LineSegment>*, 3> segs{};
    std::array<bool, 3> used{};
    int count = 0, segments = 0;
};

/// What the lines are fitted for: world-to-camera rotation, focal length, principal point.
struct LineCamera {
    glm::dmat3 R{1.0};
    double f = 1;
    ImagePoint c{0.0};

    /// Homogeneous vanishing point of world axis `a` (w = 0 at infinity).
    glm::dvec3 vp(int a) const {
        const glm::dvec3 d = column(R, a);
        return glm::dvec3(f * d.x + c.x * d.z, f * d.y + c.y * d.z, d.z);
    }
    Intrinsics intrinsics(int w, int h) const {
        Intrinsics k = Intrinsics::centred(w, h, f);
        k.cx = c.x, k.cy = c.y;
        return k;
    }
};

/// sqrt(2) times the distance of the segment's end points (equal and opposite) from the line
/// through its midpoint and the vanishing point `v`: independent end-point noise sigma gives
/// residuals of spread sigma.
double segment_residual(const LineSegment& s, const glm::dvec3& v) {
    const glm::dvec3 l = glm::cross(homog(0.5 * (s.a + s.b)), v);
    const double n = glm::length(glm::dvec2(l));
    if (!(n > 0)) return n == 0 ? 0.0 : HUGE_VAL;  // overflow must not pass for a perfect fit
    return std::sqrt(2.0) * glm::dot(l, homog(s.a)) / n;
}

/// One residual per segment, through its axis' vanishing point in `cam`.
void line_residuals(const LineCamera& cam, const Axes& ax, std::vector<double>& r) {
    r.clear();
    for (int a = 0; a < 3; ++a) {
        if (!ax.used[size_t(a)]) continue;
        const glm::dvec3 v = cam.vp(a);
        for (const LineSegment& s : *ax.segs[size_t(a)]) r.push_back(segment_residual(s, v));
    }
}

/// Parameters: rotation vector (R = exp([w]x) R0), log focal length ratio, principal point
/// shift in image sizes; the last two only where estimated.
struct LineParams {
    LineCamera base;
    bool free_focal = false, free_pp = false;
    double size = 1;

    int count() const { return 3 + int(free_focal) + 2 * int(free_pp); }
    LineCamera apply(const std::vector<double>& x) const {
        LineCamera c = base;
        c.R = calib::rotation_exp(glm::dvec3(x[0], x[1], x[2])) * base.R;
        size_t i = 3;
        // Within a factor of 10^6 either way: beyond, the focal length is meaningless anyway.
        if (free_focal) c.f = base.f * std::exp(std::clamp(x[i++], -14.0, 14.0));
        if (free_pp) c.c += size * glm::dvec2(x[i], x[i + 1]);
        return c;
    }
};

/// World axes signed as the conventions say: Y up in the image, X to the right, Z = X x Y.
/// Flipping the sign of an axis moves no vanishing point, so the fit is unchanged.
glm::dmat3 signed_axes(const glm::dmat3& R) {
    glm::dvec3 x = column(R, 0), y = column(R, 1);
    if (y.y > 0) y = -y;
    if (x.x < 0) x = -x;
    return glm::dmat3(x, y, glm::cross(x, y));
}

/// A starting rotation from the directions' own vanishing points for focal `f`.
glm::dmat3 rotation_from_vps(const std::array<glm::dvec3, 3>& vp, const Axes& ax, double f,
                             const ImagePoint& c) {
    std::array<glm::dvec3, 3> d{};
    for (int a = 0; a < 3; ++a)
        if (ax.used[size_t(a)]) {
            const glm::dvec3& v = vp[size_t(a)];
            d[size_t(a)] =
                glm::normalize(glm::dvec3((v.x - c.x * v.z) / f, (v.y - c.y * v.z) / f, v.z));
        }
    if (ax.used[1] && d[1].y > 0) d[1] = -d[1];
    if (ax.used[0] && d[0].x < 0) d[0] = -d[0];
    if (!ax.used[1]) {
        d[1] = glm::cross(d[2], d[0]);
        if (d[1].y > 0) d[2] = -d[2], d[1] = -d[1];
    } else if (!ax.used[0]) {
        d[0] = glm::cross(d[1], d[2]);
        if (d[0].x < 0) d[2] = -d[2], d[0] = -d[0];
    }
    if (ax.used[2] && glm::dot(d[2], glm::cross(d[0], d[1])) < 0) d[2] = -d[2];
    if (!ax.used[2]) d[2] = glm::cross(d[0], d[1]);
    cv::Matx33d D;
    for (int a = 0; a < 3; ++a)
        for (int r = 0; r < 3; ++r) D(r, a) = d[size_t(a)][r];
    cv::Matx33d U, Vt;
    cv::Vec3d sv;
    cv::SVD::compute(D, sv, U, Vt);
    if (cv::determinant(U * Vt) < 0)
        for (int r = 0; r < 3; ++r) U(r, 2) = -U(r, 2);
    return calib::from_cv(U * Vt);
}

/// A fit of the lines and its covariance at the optimum.
struct LineFit {
    LineParams params;  ///< based at the optimum: parameters zero are the solution
    double cost = 0;
    int residuals = 0;
    double sigma = 0;
    cv::Mat cov;

    const LineCamera& camera() const { return params.base; }
    double rms() const { return residuals ? std::sqrt(cost / (2.0 * residuals)) : 0.0; }
    double relative_sigma_focal() const {
        return params.free_focal ? std::sqrt(cov.at<double>(3, 3)) : 0.0;
    }
    double sigma_pp(int i) const {
        const int j = 3 + int(params.free_focal) + i;  // after the rotation and focal length
        return params.free_pp ? params.size * std::sqrt(cov.at<double>(j, j)) : 0.0;
    }
};

/// Fits from each start and keeps the lowest cost.
LineFit fit_lines(const Axes& ax, const std::vector<LineCamera>& starts, bool free_focal,
                  bool free_pp, double size, double click_sigma) {
    LineFit best;
    best.cost = HUGE_VAL;
    for (const LineCamera& start : starts) {
        LineParams p{start, free_focal, free_pp, size};
        const LeastSquaresResult r = calib::levenberg_marquardt(
            [&](const std::vector<double>& x, std::vector<double>& res) {
                line_residuals(p.apply(x), ax, res);
            },
            std::vector<double>(size_t(p.count()), 0.0));
        if (r.cost < best.cost) {
            best.params = p;
            best.params.base = p.apply(r.x);
            best.cost = r.cost;
            best.residuals = r.residuals;
        }
    }
    best.params.base.R = signed_axes(best.params.base.R);
    const LineParams& p = best.params;
    const calib::ResidualFunction f = [&](const std::vector<double>& x, std::vector<double>& res) {
        line_residuals(p.apply(x), ax, res);
    };
    const cv::Mat J = calib::numeric_jacobian(f, std::vector<double>(size_t(p.count()), 0.0));
    best.sigma = calib::residual_sigma(best.cost, best.residuals, p.count(), click_sigma);
    best.cov = best.sigma * best.sigma * calib::inverse_normal_matrix(J);
    return best;
}

Axes check_axes(const VanishingInput& in, double image_size, const std::string& source) {
    Axes ax;
    ax.segs = {&in.x, &in.y, &in.z};
    for (int a = 0; a < 3; ++a) {
        const auto& segs = *ax.segs[size_t(a)];
        if (segs.empty()) continue;
        if (segs.size() < 2)
            throw InputError(
                source, kAxisName[a],
                "need at least 2 line segments per direction, got " + std::to_string(segs.size()));
        for (const LineSegment& s : segs) {
            if (!std::isfinite(s.a.x) || !std::isfinite(s.a.y) || !std::isfinite(s.b.x) ||
                !std::isfinite(s.b.y))
                throw InputError(source, kAxisName[a], "line segments must be finite pixels");
            if (glm::length(s.b - s.a) < 1e-6 * image_size)
                throw InputError(source, kAxisName[a], "a line segment has zero length");
        }
        ax.used[size_t(a)] = true;
        ++ax.count;
        ax.segments += int(segs.size());
    }
    if (ax.count < 2)
        throw InputError(source, "",
                         "need line segments for at least two of the directions x, y, z");
    return ax;
}

bool at_infinity(const glm::dvec3& v, double image_size) {
    return std::abs(v.z) * 1000.0 * image_size <= glm::length(glm::dvec2(v));
}

/// f^2 that makes the directions through two finite vanishing points orthogonal, for the
/// principal point `c` (negative when no focal length can).
double focal_squared(const glm::dvec3& va, const glm::dvec3& vb, const glm::dvec2& c) {
    return -glm::dot(glm::dvec2(va) / va.z - c, glm::dvec2(vb) / vb.z - c);
}

/// Starting cameras: the given focal length, or the one two orthogonal vanishing points give
/// with the principal point at the centre, and a spread of fields of view in case noise makes
/// that one meaningless.
std::vector<LineCamera> starts(const Axes& ax, const VanishingInput& in, const ImagePoint& c,
                               double size, std::array<glm::dvec3, 3>& vp) {
    for (int a = 0; a < 3; ++a)
        if (ax.used[size_t(a)]) vp[size_t(a)] = vanishing_point(*ax.segs[size_t(a)]);
    std::vector<double> focals;
    if (in.focal_px) {
        focals.push_back(*in.focal_px);
    } else {
        for (int a = 0; a < 3; ++a)
            for (int b = a + 1; b < 3; ++b) {
                const glm::dvec3 &va = vp[size_t(a)], &vb = vp[size_t(b)];
                if (!ax.used[size_t(a)] || !ax.used[size_t(b)] || at_infinity(va, size) ||
                    at_infinity(vb, size))
                    continue;
                const double f2 = focal_squared(va, vb, c);
                if (f2 > 0) focals.push_back(std::sqrt(f2));
            }
        for (double s : {0.3, 0.5, 0.8, 1.2, 2.0, 3.5, 6.0}) focals.push_back(s * size);
    }
    std::vector<LineCamera> out;
    for (double f : focals) out.push_back({rotation_from_vps(vp, ax, f, c), f, c});
    return out;
}

/// Names the reason when the focal length is left undetermined.
std::string undetermined_focal(const LineCamera& cam, const Axes& ax, double size) {
    for (int a = 0; a < 3; ++a)
        if (ax.used[size_t(a)] && at_infinity(cam.vp(a), size))
            return std::string("the ") + kAxisName[a] +
                   " lines are parallel in the image (their vanishing point is at infinity), "
                   "which leaves the focal length free: give it (--focal, --exif), or draw "
                   "lines along a third direction";
    return "give the focal length (--focal, --exif), or draw longer lines, farther apart, or "
           "along a third direction";
}

/// Throws when the directions' own vanishing points cannot be at right angles for any focal
/// length and forcing them to be costs far more than click noise explains (`joint_cost`
/// against each direction fitted alone): the grouping is wrong, not the clicks.
/// `force` skips the cost test (the fit already escaped to an undetermined focal length).
void check_orthogonal(const std::array<glm::dvec3, 3>& vp, const Axes& ax, const ImagePoint& c,
                      double size, double joint_cost, double click_sigma, bool force,
                      const std::string& source) {
    double alone = 0;
    for (int a = 0; a < 3; ++a)
        if (ax.used[size_t(a)])
            for (const LineSegment& s : *ax.segs[size_t(a)])
                alone += std::pow(segment_residual(s, vp[size_t(a)]), 2);
    // 25 sigma^2 for at most three constraints: far beyond what noise does.
    const double sigma = std::max(click_sigma, 0.05);
    if (!force && !(joint_cost - alone > 25 * sigma * sigma)) return;
    for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b) {
            const glm::dvec3 &va = vp[size_t(a)], &vb = vp[size_t(b)];
            if (!ax.used[size_t(a)] || !ax.used[size_t(b)] || at_infinity(va, size) ||
                at_infinity(vb, size))
                continue;
            const double f2 = focal_squared(va, vb, c);
            if (!(f2 > 0))
                throw InputError(source, "",
                                 "these directions cannot be orthogonal in a pinhole photo (the "
                                 "focal length squared would be " +
                                     std::to_string(f2) +
                                     " px^2 <= 0): check that each group's lines are parallel "
                                     "in the world (a line in the wrong group?) and the groups "
                                     "are at right angles");
        }
}

/// What the steps of the fit share: the checked input and the figures derived from it.
struct LineProblem {
    const VanishingInput& in;
    const std::string& source;
    int width = 0, height = 0;
    Axes ax;
    double size = 0;   ///< the longer image side, pixels: the scale of every tolerance
    double click = 0;  ///< the click noise floor, pixels
    bool free_focal = false;
};

/// Throws InputError for an empty image, unusable segments or a focal length <= 0.
LineProblem checked_problem(const VanishingInput& in, int width, int height,
                            const std::string& source) {
    if (width <= 0 || height <= 0)
        throw InputError(source, "size", "the image size must be positive");
    const double size = double(std::max(width, height));
    const Axes ax = check_axes(in, size, source);
    if (in.focal_px) check_focal(*in.focal_px, source, "focal");
    return {in, source, width, height, ax, size, std::max(0.0, in.click_sigma_px), !in.focal_px};
}

/// `fit` refitted with the principal point free where the lines pin it down (three directions,
/// to within 5 % of the image size); otherwise `fit` itself, and a warning says why.
LineFit with_free_principal_point(const LineProblem& p, const LineFit& fit,
                                  std::vector<std::string>& warnings) {
    if (p.ax.count < 3) {
        warnings.push_back(
            "the principal point needs lines along all three directions: it "
            "is held at the image centre");
        return fit;
    }
    LineFit free = fit_lines(p.ax, {fit.camera()}, p.free_focal, true, p.size, p.click);
    const double s = std::max(free.sigma_pp(0), free.sigma_pp(1));
    if (s < 0.05 * p.size) return free;
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "the lines do not pin down the principal point (± %.0f px): it is "
                  "held at the image centre",
                  s);
    warnings.push_back(buf);
    return fit;
}

/// Throws InputError when the fit gives no usable camera: directions that cannot be
/// orthogonal, a focal length the lines leave free, or residuals far beyond click noise.
/// `r` holds the fit's intrinsics and RMS error.
void refuse_unusable_fit(const LineProblem& p, const LineFit& fit,
                         const std::array<glm::dvec3, 3>& vp, const CalibrationResult& r) {
    const LineCamera& cam = fit.camera();
    // A poor fit whose directions' own vanishing points contradict orthogonality is a
    // grouping mistake; say so before anything the fit then did to reconcile them.
    check_orthogonal(vp, p.ax, cam.c, p.size, fit.cost, p.click, false, p.source);
    if (p.free_focal && !(fit.relative_sigma_focal() < 1.0)) {
        check_orthogonal(vp, p.ax, cam.c, p.size, fit.cost, p.click, true, p.source);
        throw InputError(p.source, "focal",
                         "the focal length is not determined by these lines: " +
                             undetermined_focal(cam, p.ax, p.size));
    }
    check_usable_fit(r, p.source, "",
                     "check that each group's lines are parallel in the world and the groups "
                     "are at right angles (a line in the wrong group?)");
}

/// The world-to-camera pose: the fitted rotation, the centre placed by the origin and scale.
Pose placed_pose(const LineProblem& p, const LineCamera& cam, const Intrinsics& k) {
    const glm::dvec3 C = calib::place_camera(cam.R, k, p.in, p.source);
    Pose pose;
    pose.R = cam.R;
    pose.t = -(cam.R * C);
    return pose;
}

/// Covariance (m^2) of the camera centre from the click noise `sigma` of the origin and scale
/// points, which the line fit's parameters do not carry: central differences per coordinate.
glm::dmat3 placement_click_covariance(const LineProblem& p, const LineCamera& cam,
                                      const Intrinsics& k, double sigma) {
    const std::vector<ImagePoint> clicks = calib::placement_points(p.in);
    cv::Mat Jc(3, int(2 * clicks.size()), CV_64F);
    for (size_t i = 0; i < 2 * clicks.size(); ++i) {
        std::vector<ImagePoint> plus = clicks, minus = clicks;
        plus[i / 2][int(i % 2)] += 1e-3;
        minus[i / 2][int(i % 2)] -= 1e-3;
        auto at = [&](const std::vector<ImagePoint>& points) {
            return calib::place_camera(cam.R, k, calib::with_placement_points(p.in, points),
                                       p.source);
        };
        const glm::dvec3 d = (at(plus) - at(minus)) / 2e-3;
        for (int j = 0; j < 3; ++j) Jc.at<double>(j, int(i)) = d[j];
    }
    const cv::Mat click_cov = sigma * sigma * Jc * Jc.t();
    glm::dmat3 cov(0.0);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) cov[j][i] = click_cov.at<double>(i, j);
    return cov;
}

/// The fit's covariance carried to the intrinsics and the camera centre, plus the click noise
/// of the origin and scale points.
Uncertainty line_fit_uncertainty(const LineProblem& p, const LineFit& fit, const Intrinsics& k) {
    const LineCamera& cam = fit.camera();
    Uncertainty u;
    u.known = true;
    u.point_sigma_px = fit.sigma;
    u.focal_free = p.free_focal;
    u.principal_free = fit.params.free_pp;
    u.fx = u.fy = cam.f * fit.relative_sigma_focal();
    u.cx = fit.sigma_pp(0), u.cy = fit.sigma_pp(1);
    calib::pose_uncertainty(
        fit.cov, std::vector<double>(size_t(fit.params.count()), 0.0),
        [&](const std::vector<double>& x) {
            const LineCamera c = fit.params.apply(x);
            return calib::place_camera(c.R, c.intrinsics(p.width, p.height), p.in, p.source);
        },
        u, placement_click_covariance(p, cam, k, fit.sigma));
    return u;
}

/// A focal length found 20 % too long or too short is a wrong camera that must not pass
/// silently: the true one would then be the found one times these factors.
constexpr double kFocalRange[2] = {1.0 / 1.2, 1.0 / 0.8};
/// The cost rise, in click-noise variances, that rules such a focal length out: 16 = 4 sigma
/// for one parameter, the margin the 5 % rule of add_quality_warnings gives 20 % where the
/// cost is quadratic.
constexpr double kFocalRangeChi2 = 16.0;

/// A warning when a focal length 20 % away (see kFocalRange), with the rotation (and a freed
/// principal point) refitted, fits the lines within 4 sigma of the best fit. The covariance
/// behind the 5 % rule is the cost's curvature at the optimum; with short or few lines the cost
/// is far from quadratic across 20 % and rises more slowly on one side (which one depends on
/// the lines), and that side alone can leave 20 % unexcluded while the curvature promises 5 %.
std::optional<std::string> focal_range_warning(const LineProblem& p, const LineFit& fit,
                                               const std::array<glm::dvec3, 3>& vp) {
    const LineCamera& cam = fit.camera();
    const double allowed = fit.cost + kFocalRangeChi2 * fit.sigma * fit.sigma;
    for (const double factor : kFocalRange) {
        const double f = factor * cam.f;
        // From the fitted rotation and from the directions' own vanishing points at f: the
        // profile must not miss its minimum, or the check would pass for want of a fit.
        const std::vector<LineCamera> from = {{cam.R, f, cam.c},
                                              {rotation_from_vps(vp, p.ax, f, cam.c), f, cam.c}};
        const LineFit at_f = fit_lines(p.ax, from, false, fit.params.free_pp, p.size, p.click);
        if (at_f.cost <= allowed) {
            char buf[400];
            std::snprintf(buf, sizeof(buf),
                          "the focal length is uncertain: fx %.0f px (%+.0f %%) fits the lines "
                          "within the click noise almost as well as fx %.0f px; give the focal "
                          "length if it is known (EXIF, the lens), or draw longer lines farther "
                          "apart",
                          f, 100 * (factor - 1), cam.f);
            return std::string(buf);
        }
    }
    return std::nullopt;
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
        glm::dvec3 l =
            glm::cross(homog((segments[i].a - o) / scale), homog((segments[i].b - o) / scale));
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
    const LineProblem p = checked_problem(in, width, height, source);
    const ImagePoint centre(0.5 * (width - 1), 0.5 * (height - 1));
    std::array<glm::dvec3, 3> vp{};  // each direction's own vanishing point, from `starts`
    LineFit fit =
        fit_lines(p.ax, starts(p.ax, in, centre, p.size, vp), p.free_focal, false, p.size, p.click);
    std::vector<std::string> warnings;
    if (in.free_principal_point) fit = with_free_principal_point(p, fit, warnings);

    CalibrationResult r;
    r.intrinsics = fit.camera().intrinsics(width, height);
    r.rms_px = fit.rms();
    refuse_unusable_fit(p, fit, vp, r);
    r.pose = placed_pose(p, fit.camera(), r.intrinsics);
    r.uncertainty = line_fit_uncertainty(p, fit, r.intrinsics);
    r.warnings = warnings;
    for (std::string& w : calib::scale_warnings(fit.camera().R, r.intrinsics, in, fit.sigma))
        r.warnings.push_back(std::move(w));
    add_quality_warnings(r);
    // Only where the 5 % rule was silent: one warning about the focal length is enough.
    if (p.free_focal && r.uncertainty.fx <= 0.05 * r.intrinsics.fx)
        if (std::optional<std::string> w = focal_range_warning(p, fit, vp))
            r.warnings.push_back(std::move(*w));
    return r;
}

}  // namespace dp
