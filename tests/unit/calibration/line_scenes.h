#pragma once
// Line segments "clicked" in photos of known cameras, exactly or with Gaussian click noise,
// and the statistics of many noisy draws against the camera that took them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <random>

#include "calibration/least_squares.h"
#include "calibration/vanishing.h"
#include "synthetic_board.h"

namespace dp::test {

/// World segments along the three axes and two ground points for the scale.
struct LineScene {
    CameraSpec truth;
    int width = 1000, height = 750;
    std::vector<std::pair<glm::dvec3, glm::dvec3>> x, y, z;
    glm::dvec3 distance_end{1.0, 0, 0};  ///< the scale: from the origin to here, on the ground

    Camera camera() const { return truth.build(width, height); }
    ImagePoint pixel(const glm::dvec3& w) const {
        vec2 p;
        EXPECT_TRUE(camera().project(vec3(w), p)) << "a point behind the camera";
        return glm::dvec2(p);
    }
    /// The clicks, each coordinate moved by `noise()`.
    VanishingInput clicks(const std::function<double()>& noise) const {
        VanishingInput in;
        auto click = [&](const glm::dvec3& w) {
            // Drawn in two statements: the order of a call's arguments is unspecified, and the
            // draws must not depend on the compiler (v first, as the gcc builds always drew).
            const double dv = noise();
            const double du = noise();
            return pixel(w) + glm::dvec2(du, dv);
        };
        auto add = [&](const auto& list, std::vector<LineSegment>& out) {
            for (const auto& [a, b] : list) out.push_back({click(a), click(b)});
        };
        add(x, in.x);
        add(y, in.y);
        add(z, in.z);
        in.origin = click(glm::dvec3(0.0));
        in.distance = VanishingInput::Distance{in.origin, click(distance_end),
                                               glm::length(distance_end)};
        return in;
    }
    VanishingInput exact() const {
        return clicks([] { return 0.0; });
    }
};

/// 1000x750, f = 800 px, at (1.5, 1.6, 2.5) looking down about 28 degrees at (0.3, 0, -0.2).
inline CameraSpec oblique_camera() {
    return camera_at({1.5, 1.6, 2.5}, {0.3, 0, -0.2}, 1000, 750, 800);
}

/// Long ground lines (pavement or floor tiles), 250 to 450 px in the image.
inline LineScene ground_lines() {
    LineScene s;
    s.truth = oblique_camera();
    for (double z : {0.0, 0.4, -0.5}) s.x.push_back({{-0.5, 0, z}, {1.0, 0, z}});
    for (double x : {0.0, 0.6, 1.0}) s.z.push_back({{x, 0, -0.6}, {x, 0, 0.5}});
    return s;
}

/// The ground lines and three vertical edges of a 0.28 m tall box: about 60 px each.
inline LineScene ground_lines_and_box_edges() {
    LineScene s = ground_lines();
    for (const glm::dvec3& foot : {glm::dvec3(0.1, 0, -0.1), glm::dvec3(0.7, 0, -0.1),
                                   glm::dvec3(0.1, 0, 0.3)})
        s.y.push_back({foot, foot + glm::dvec3(0, 0.28, 0)});
    return s;
}

/// Long ground lines across most of the photo, 420 to 790 px.
inline LineScene long_ground_lines() {
    LineScene s;
    s.truth = oblique_camera();
    for (double z : {0.6, -0.4, -1.6}) s.x.push_back({{-1.4, 0, z}, {1.6, 0, z}});
    for (double x : {-0.6, 0.5, 1.4}) s.z.push_back({{x, 0, -2.2}, {x, 0, 1.0}});
    return s;
}

/// Only the edges of a 0.8 x 0.28 x 0.6 m box (times `scale`): 60 to 210 px, close together.
inline LineScene box_edges(double scale = 1.0) {
    LineScene s;
    s.truth = oblique_camera();
    const double x0 = 0, x1 = 0.8 * scale, z0 = -0.4 * scale, z1 = 0.2 * scale, h = 0.28 * scale;
    s.x = {{{x0, 0, z1}, {x1, 0, z1}}, {{x0, h, z1}, {x1, h, z1}}, {{x0, h, z0}, {x1, h, z0}}};
    s.z = {{{x1, 0, z0}, {x1, 0, z1}}, {{x1, h, z0}, {x1, h, z1}}, {{x0, h, z0}, {x0, h, z1}}};
    s.y = {{{x0, 0, z1}, {x0, h, z1}}, {{x1, 0, z1}, {x1, h, z1}}, {{x1, 0, z0}, {x1, h, z0}}};
    return s;
}

/// A camera square to world X (tilted down, not turned): the X lines are parallel in the image
/// and their vanishing point is at infinity; vertical lines and Z lines converge.
inline LineScene parallel_x_lines() {
    LineScene s;
    s.truth = camera_at({0.4, 1.6, 3.0}, {0.4, 0, -0.5}, 1000, 750, 800);
    for (double z : {0.0, 0.5, -0.6}) s.x.push_back({{-0.4, 0, z}, {1.2, 0, z}});
    for (double x : {0.0, 0.7, 1.1}) s.z.push_back({{x, 0, -0.8}, {x, 0, 0.6}});
    for (double x : {-0.3, 1.0}) s.y.push_back({{x, 0, -0.8}, {x, 1.2, -0.8}});
    return s;
}

/// Rotation from the estimate to the truth as a rotation vector (camera frame), the error the
/// stated rotation covariance describes: R_true = exp([w]x) R.
inline glm::dvec3 rotation_error(const CalibrationResult& r, const CameraSpec& truth) {
    return calib::rotation_log(glm::dmat3(truth.rotation) * glm::transpose(r.pose.R));
}

/// e^T cov^-1 e: chi-squared with three degrees of freedom when the covariance is right.
inline double mahalanobis2(const glm::dvec3& e, const glm::dmat3& cov) {
    return glm::dot(e, glm::inverse(cov) * e);
}

/// chi-squared (3 degrees of freedom) 95 % quantile.
constexpr double kChi2Dof3Q95 = 7.815;

/// Counts over Monte Carlo draws.
struct DrawStats {
    int draws = 0, refused = 0;
    int focal_within = 0, rotation_within = 0;
    int focal_covered = 0, rotation_covered = 0, position_covered = 0;
    int outliers = 0;         ///< focal error over 20 %
    int silent_outliers = 0;  ///< ... without a warning
    double worst_focal = 0, worst_rotation_deg = 0;
    std::vector<double> focal_errors;

    double rate(int n) const { return draws ? double(n) / draws : 0.0; }
    /// One line of the figures, for the test log.
    std::string summary() const {
        char buf[512];
        std::snprintf(buf, sizeof(buf),
                      "%d draws, %d refused: focal within tolerance %.1f %%, rotation within "
                      "tolerance %.1f %%, 95th percentile focal error %.2f %%, worst %.2f %% and "
                      "%.2f deg; stated uncertainty covers focal %.1f %%, rotation %.1f %%, "
                      "position %.1f %%; %d over 20 %% (%d without a warning)",
                      draws, refused, 100 * rate(focal_within), 100 * rate(rotation_within),
                      100 * quantile_focal(0.95), 100 * worst_focal, worst_rotation_deg,
                      100 * rate(focal_covered), 100 * rate(rotation_covered),
                      100 * rate(position_covered), outliers, silent_outliers);
        return buf;
    }
    double quantile_focal(double q) const {
        std::vector<double> e = focal_errors;
        std::sort(e.begin(), e.end());
        return e.empty() ? 0.0 : e[std::min(e.size() - 1, size_t(q * double(e.size())))];
    }
};

/// `n` draws of `scene` with Gaussian click noise of `sigma` px (seeded: reproducible),
/// calibrated with `prepare` applied to the input; focal errors are relative, counted
/// "within" below `focal_tol` and `rotation_tol_deg`.
inline DrawStats monte_carlo(const LineScene& scene, int n, double sigma, double focal_tol,
                             double rotation_tol_deg,
                             const std::function<void(VanishingInput&)>& prepare = {}) {
    std::mt19937 rng(20240601);
    std::normal_distribution<double> gauss(0.0, sigma);
    DrawStats s;
    const Camera truth = scene.camera();
    for (int i = 0; i < n; ++i) {
        VanishingInput in = scene.clicks([&] { return gauss(rng); });
        if (prepare) prepare(in);
        ++s.draws;
        CalibrationResult r;
        try {
            r = calibrate_vanishing(in, scene.width, scene.height, "draw");
        } catch (const std::exception&) {
            ++s.refused;
            continue;
        }
        const Uncertainty& u = r.uncertainty;
        const double ef = r.intrinsics.fx / scene.truth.fx - 1;
        const glm::dvec3 er = rotation_error(r, scene.truth);
        const double er_deg = glm::length(er) * 180 / std::numbers::pi;
        const glm::dvec3 ep = r.pose.position() - glm::dvec3(truth.position());
        s.focal_errors.push_back(std::abs(ef));
        s.worst_focal = std::max(s.worst_focal, std::abs(ef));
        s.worst_rotation_deg = std::max(s.worst_rotation_deg, er_deg);
        s.focal_within += std::abs(ef) <= focal_tol;
        s.rotation_within += er_deg <= rotation_tol_deg;
        s.focal_covered += !u.focal_free || std::abs(ef) * scene.truth.fx <= 1.96 * u.fx;
        s.rotation_covered += mahalanobis2(er, u.rotation_cov) <= kChi2Dof3Q95;
        s.position_covered += mahalanobis2(ep, u.position_cov) <= kChi2Dof3Q95;
        s.outliers += std::abs(ef) > 0.2;
        s.silent_outliers += std::abs(ef) > 0.2 && r.warnings.empty();
    }
    return s;
}

}  // namespace dp::test
