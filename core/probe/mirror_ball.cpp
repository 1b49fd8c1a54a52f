#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "probe/probe.h"

namespace dp {

namespace {

constexpr double kPiD = std::numbers::pi;

// A unit ball at the origin photographed from +Z looking along -Z, either orthographically or
// by a pinhole at distance D = 1 / sin(fov / 2) (in ball radii) so that the ball's silhouette
// just touches the image edges. Everything is rotationally symmetric about Z, so a ball point
// is described by alpha, its angle from +Z, and its reflected direction by beta, also measured
// from +Z, in the same azimuthal plane.
class BallCamera {
public:
    explicit BallCamera(double fov_rad) : perspective_(fov_rad > 0) {
        if (perspective_) {
            distance_ = 1.0 / std::sin(fov_rad / 2);
            tan_half_fov_ = std::tan(fov_rad / 2);
            alpha_max_ = std::acos(1.0 / distance_);  // the silhouette as seen from the camera
        } else {
            alpha_max_ = kPiD / 2;
        }
        beta_max_ = reflected_angle(alpha_max_);
        // beta(alpha) is smooth and increasing (slope about 2) up to the rim, so a dense table
        // inverted by bisection once per entry and read with linear interpolation is accurate
        // far below a pixel.
        table_.resize(kTableSize + 1);
        for (int k = 0; k <= kTableSize; ++k) table_[k] = solve_alpha(beta_max_ * k / kTableSize);
    }

    double beta_max() const { return beta_max_; }

    /// Ball point angle alpha whose reflection leaves at angle beta (clamped to the rim).
    double alpha_for(double beta) const {
        double t = std::clamp(beta / beta_max_, 0.0, 1.0) * kTableSize;
        int k = std::min(int(t), kTableSize - 1);
        return table_[k] + (table_[k + 1] - table_[k]) * (t - k);
    }

    /// Distance of the ball point from the image centre, 1 being the ball's rim.
    double image_radius(double alpha) const {
        if (!perspective_) return std::sin(alpha);
        return std::sin(alpha) / (distance_ - std::cos(alpha)) / tan_half_fov_;
    }

    /// Angle from +Z of the view ray reflected at the ball point alpha.
    double reflected_angle(double alpha) const {
        double px = std::sin(alpha), pz = std::cos(alpha);  // point = normal
        double wx = 0, wz = -1;                              // orthographic view ray
        if (perspective_) {
            wx = px;
            wz = pz - distance_;
            double len = std::hypot(wx, wz);
            wx /= len;
            wz /= len;
        }
        double d = wx * px + wz * pz;
        return std::atan2(wx - 2 * d * px, wz - 2 * d * pz);
    }

private:
    static constexpr int kTableSize = 4096;

    double solve_alpha(double beta) const {
        if (!perspective_) return beta / 2;
        double lo = 0, hi = alpha_max_;
        for (int it = 0; it < 60; ++it) {
            double mid = 0.5 * (lo + hi);
            (reflected_angle(mid) < beta ? lo : hi) = mid;
        }
        return 0.5 * (lo + hi);
    }

    bool perspective_;
    double distance_ = 0, tan_half_fov_ = 0, alpha_max_ = 0, beta_max_ = 0;
    std::vector<double> table_;
};

}  // namespace

Image unwrap_mirror_ball(const Image& ball, int out_width, int out_height, float camera_fov_deg) {
    if (ball.empty()) throw std::invalid_argument("unwrap_mirror_ball: empty ball image");
    if (out_width <= 0 || out_height <= 0)
        throw std::invalid_argument("unwrap_mirror_ball: output size must be positive");
    if (!(camera_fov_deg >= 0 && camera_fov_deg < 180))
        throw std::invalid_argument("unwrap_mirror_ball: field of view must be in [0, 180)");

    BallCamera camera(double(camera_fov_deg) * kPiD / 180);
    // A non-square photo is read as its centred square. The ball's radius in pixels and how far
    // from its rim we may look: bilinear filtering reaches up to sqrt(2) pixels away, so 1.5
    // pixels keep every tap on a pixel whose centre is on the ball. Directions beyond (those
    // hidden behind the ball) take the value on the rim at the same azimuth.
    double radius_px = 0.5 * std::min(ball.width(), ball.height());
    double cx = 0.5 * ball.width(), cy = 0.5 * ball.height();
    double max_radius = std::max(0.0, 1.0 - 1.5 / radius_px);

    Image out(out_width, out_height);
    for (int j = 0; j < out_height; ++j) {
        for (int i = 0; i < out_width; ++i) {
            vec3 d = latlong_direction((i + 0.5f) / out_width, (j + 0.5f) / out_height);
            double rho = std::hypot(double(d.x), double(d.y));
            double beta = std::atan2(rho, double(d.z));
            // Azimuth of the direction is the azimuth of the ball point; at the poles any works.
            double ax = rho > 0 ? d.x / rho : 1.0, ay = rho > 0 ? d.y / rho : 0.0;
            double r = std::min(camera.image_radius(camera.alpha_for(beta)), max_radius);
            // Image x grows with +X, image rows grow downwards (-Y); centres at integer + 0.5.
            double x = cx + r * ax * radius_px - 0.5;
            double y = cy - r * ay * radius_px - 0.5;
            out.at(i, j) = ball.bilinear(float(x), float(y));
        }
    }
    return out;
}

}  // namespace dp
