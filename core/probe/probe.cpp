#include "probe/probe.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

namespace dp {

namespace {

constexpr double kPiD = std::numbers::pi;
constexpr float kOneMinusEpsilonF = 0x1.fffffep-1f;
constexpr double kOneMinusEpsilon = 0x1.fffffffffffffp-1;

dvec3 direction_d(double u, double v) {
    double theta = kPiD * v, phi = 2 * kPiD * (u - 0.5);
    double st = std::sin(theta);
    return dvec3(st * std::sin(phi), std::cos(theta), -st * std::cos(phi));
}

// Exact band area; the product form avoids cancelling cos(theta_top) - cos(theta_bottom)
// near the poles.
double row_solid_angle(int row, int width, int height) {
    return 4 * kPiD / width * std::sin(kPiD * (row + 0.5) / height) *
           std::sin(kPiD / (2.0 * height));
}

}  // namespace

vec3 latlong_direction(float u, float v) { return vec3(direction_d(u, v)); }

vec2 latlong_uv(const vec3& dir) {
    double x = dir.x, y = dir.y, z = dir.z;
    // atan2 for theta is accurate near the poles (acos is not) and ignores the length of dir.
    double theta = std::atan2(std::sqrt(x * x + z * z), y);
    double phi = std::atan2(x, -z);
    float u = float(phi / (2 * kPiD) + 0.5);
    float v = float(theta / kPiD);
    // phi = pi (or rounding up to 1) is the same meridian as u = 0.
    if (u >= 1.0f) u -= 1.0f;
    // A NaN direction maps to (0, 0) so that pixel lookups stay in range.
    u = std::isnan(u) ? 0.0f : std::clamp(u, 0.0f, kOneMinusEpsilonF);
    v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, kOneMinusEpsilonF);
    return vec2(u, v);
}

size_t latlong_pixel(const vec3& dir, int width, int height) {
    vec2 uv = latlong_uv(dir);
    int i = std::min(int(uv.x * float(width)), width - 1);
    int j = std::min(int(uv.y * float(height)), height - 1);
    return size_t(j) * size_t(width) + size_t(i);
}

Probe::Probe(Image latlong, const glm::mat3& rotation, float intensity)
    : image_(std::move(latlong)),
      rotation_(rotation),
      inverse_rotation_(glm::inverse(rotation)),
      intensity_(intensity) {
    for (size_t k = 0; k < image_.size(); ++k)
        if (!is_finite(image_[k])) image_[k] = vec3(0);

    const int w = width(), h = height();
    std::vector<double> weights(image_.size(), 0.0);
    for (int j = 0; j < h; ++j) {
        double omega = pixel_solid_angle(j);
        for (int i = 0; i < w; ++i) {
            double lum = luminance(dvec3(image_.at(i, j)) * double(intensity_));
            weights[size_t(j) * w + i] = lum > 0 ? lum * omega : 0.0;
        }
    }
    table_ = AliasTable(weights);
}

double Probe::pixel_solid_angle(int row) const {
    return row_solid_angle(row, width(), height());
}

vec3 Probe::pixel_radiance(size_t pixel) const { return image_[pixel] * intensity_; }

vec3 Probe::radiance(const vec3& dir) const {
    if (image_.empty()) return vec3(0);
    return pixel_radiance(latlong_pixel(to_probe(dir), width(), height()));
}

ProbeSample Probe::sample(float u0, float u1, float u2) const {
    ProbeSample s;
    if (table_.total() <= 0 || image_.empty()) {
        s.dir = glm::normalize(to_world(vec3(0, 1, 0)));  // glm vectors are not zeroed by default
        s.radiance = vec3(0);
        return s;
    }
    // A float carries 24 bits: too few to pick among millions of pixels and still flip the
    // alias coin. u1 fills in the bits below u0; what the table leaves of the combined number
    // is the horizontal position inside the pixel.
    double u = std::min(double(u0) + double(u1) * 0x1p-24, kOneMinusEpsilon);
    double x_in_pixel = 0;
    size_t pixel = table_.sample(u, &x_in_pixel);

    const int w = width(), h = height();
    int i = int(pixel % size_t(w)), j = int(pixel / size_t(w));
    // Uniform in solid angle inside the pixel: phi uniform, cos(theta) uniform in the band.
    double cos_top = std::cos(kPiD * j / h), cos_bottom = std::cos(kPiD * (j + 1) / h);
    double cos_theta = cos_top + (cos_bottom - cos_top) * double(u2);
    double sin_theta = std::sqrt(std::max(0.0, (1 - cos_theta) * (1 + cos_theta)));
    double phi = 2 * kPiD * ((i + x_in_pixel) / w - 0.5);
    dvec3 d(sin_theta * std::sin(phi), cos_theta, -sin_theta * std::cos(phi));

    s.dir = glm::normalize(to_world(vec3(d)));
    s.radiance = pixel_radiance(pixel);
    s.pdf = float(table_.pmf(pixel) / pixel_solid_angle(j));
    s.pixel = pixel;
    return s;
}

float Probe::pdf(const vec3& dir) const {
    if (table_.total() <= 0 || image_.empty()) return 0;
    size_t pixel = latlong_pixel(to_probe(dir), width(), height());
    return float(table_.pmf(pixel) / pixel_solid_angle(int(pixel / size_t(width()))));
}

glm::mat3 euler_xyz_deg(const vec3& deg) {
    const glm::mat4 id(1.0f);
    glm::mat3 rx(glm::rotate(id, glm::radians(deg.x), vec3(1, 0, 0)));
    glm::mat3 ry(glm::rotate(id, glm::radians(deg.y), vec3(0, 1, 0)));
    glm::mat3 rz(glm::rotate(id, glm::radians(deg.z), vec3(0, 0, 1)));
    return rz * ry * rx;
}

}  // namespace dp
