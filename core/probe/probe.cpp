#include "probe/probe.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "probe/alias_build.h"

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

}  // namespace

// Exact band area; the product form avoids cancelling cos(theta_top) - cos(theta_bottom)
// near the poles.
double latlong_row_solid_angle(int row, int width, int height) {
    return 4 * kPiD / width * std::sin(kPiD * (row + 0.5) / height) *
           std::sin(kPiD / (2.0 * height));
}

vec3 latlong_direction(float u, float v) { return vec3(direction_d(u, v)); }

vec3 latlong_pixel_direction(size_t pixel, int width, int height) {
    return latlong_direction((float(pixel % size_t(width)) + 0.5f) / float(width),
                             (float(pixel / size_t(width)) + 0.5f) / float(height));
}

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

struct Probe::InverseTable {
    std::once_flag once;
    LatLongTable table;
};

Probe::Probe() { build(); }

Probe::Probe(Image latlong, const glm::mat3& rotation, const vec3& gain)
    : rotation_(rotation), inverse_rotation_(glm::inverse(rotation)), gain_(gain) {
    for (size_t k = 0; k < latlong.size(); ++k)
        if (!is_finite(latlong[k])) latlong[k] = vec3(0);
    image_ = std::make_shared<const Image>(std::move(latlong));
    build();
}

Probe::Probe(std::shared_ptr<const Image> latlong, const glm::mat3& rotation, const vec3& gain)
    : rotation_(rotation), inverse_rotation_(glm::inverse(rotation)), gain_(gain) {
    if (!latlong) latlong = std::make_shared<const Image>();
    const Image& img = *latlong;
    bool finite = true;
    for (size_t k = 0; k < img.size() && finite; ++k) finite = is_finite(img[k]);
    if (finite) {
        image_ = std::move(latlong);
    } else {
        Image copy = img;
        for (size_t k = 0; k < copy.size(); ++k)
            if (!is_finite(copy[k])) copy[k] = vec3(0);
        image_ = std::make_shared<const Image>(std::move(copy));
    }
    build();
}

void Probe::build() {
    inverse_ = std::make_shared<InverseTable>();
    const int w = width(), h = height();
    rows_.resize(size_t(std::max(h, 0)));
    for (int j = 0; j < h; ++j) {
        // Once per row here rather than once per sample.
        const double cos_top = std::cos(kPiD * j / h), cos_bottom = std::cos(kPiD * (j + 1) / h);
        rows_[j] = Row{cos_top, cos_bottom - cos_top, latlong_row_solid_angle(j, w, h)};
    }
    // Straight into the compact table: no per-pixel array of weights or pmf is kept, even
    // while building (an 8k probe has 33 million pixels).
    columns_.resize(image_->size());
    total_power_ = build_alias_table(
        columns_.size(), [&](size_t k) { return pixel_weight(k); },
        [&](size_t k, double prob, uint32_t alias) { columns_[k] = Column{float(prob), alias}; });
}

const LatLongTable& Probe::inverse_table() const {
    std::call_once(inverse_->once, [&] {
        inverse_->table = LatLongTable(width(), height(), [&](size_t k) { return pixel_weight(k); });
    });
    return inverse_->table;
}

float Probe::pixel_pdf(size_t pixel) const {
    // pmf / Omega = (luminance * Omega / total) / Omega: the solid angle cancels.
    const double lum = luminance(dvec3((*image_)[pixel]) * dvec3(gain_));
    return lum > 0 && total_power_ > 0 ? float(lum / total_power_) : 0.0f;
}

double Probe::pixel_weight(size_t pixel) const {
    const double lum = luminance(dvec3((*image_)[pixel]) * dvec3(gain_));
    return lum > 0 ? lum * rows_[pixel / size_t(width())].solid_angle : 0.0;
}

double Probe::pixel_pmf(size_t pixel) const {
    // The alias table's pmf, weight / total, without keeping a table of it.
    return total_power_ > 0 ? pixel_weight(pixel) / total_power_ : 0.0;
}

double Probe::pixel_solid_angle(int row) const {
    // The same number as row_solid_angle gives, computed once per row.
    if (row >= 0 && size_t(row) < rows_.size()) return rows_[size_t(row)].solid_angle;
    return latlong_row_solid_angle(row, width(), height());
}

vec3 Probe::pixel_radiance(size_t pixel) const { return (*image_)[pixel] * gain_; }

vec3 Probe::radiance(const vec3& dir) const {
    if (image_->empty()) return vec3(0);
    return pixel_radiance(latlong_pixel(to_probe(dir), width(), height()));
}

ProbeSample Probe::sample(float u0, float u1, float u2) const {
    ProbeSample s;
    if (total_power_ <= 0 || columns_.empty()) {
        s.dir = glm::normalize(to_world(vec3(0, 1, 0)));  // glm vectors are not zeroed by default
        s.radiance = vec3(0);
        return s;
    }
    // A float carries 24 bits: too few to pick among millions of pixels and still flip the
    // alias coin. u1 fills in the bits below u0; what the table leaves of the combined number
    // is the horizontal position inside the pixel. This is AliasTable::sample's arithmetic, so
    // the same numbers pick the same pixel.
    const size_t n = columns_.size();
    const double u = std::min(double(u0) + double(u1) * 0x1p-24, kOneMinusEpsilon);
    const double scaled = u * double(n);
    const size_t column = std::min(size_t(scaled), n - 1);
    const double frac = std::min(scaled - double(column), kOneMinusEpsilon);
    const Column& c = columns_[column];
    const double prob = double(c.prob);
    const bool keep = frac < prob;
    const size_t pixel = keep ? column : size_t(c.alias);
    const double rest = keep ? frac / prob : (frac - prob) / (1.0 - prob);
    const double x_in_pixel = std::clamp(rest, 0.0, kOneMinusEpsilon);

    const uint32_t w = uint32_t(width());
    const uint32_t j = uint32_t(pixel) / w, i = uint32_t(pixel) - j * w;
    const Row& row = rows_[j];
    // Uniform in solid angle inside the pixel: phi uniform, cos(theta) uniform in the band.
    // cos(theta) and sin(theta) stay in double, which keeps sin(theta) accurate near the poles;
    // phi lies in [-pi, pi], where float trigonometry is as accurate as the float result.
    const double cos_theta = row.cos_top + row.cos_span * double(u2);
    const float sin_theta = float(std::sqrt(std::max(0.0, (1 - cos_theta) * (1 + cos_theta))));
    const float phi = float(2 * kPiD * ((i + x_in_pixel) / w - 0.5));
    const vec3 d(sin_theta * std::sin(phi), float(cos_theta), -sin_theta * std::cos(phi));

    s.dir = glm::normalize(to_world(d));
    s.radiance = pixel_radiance(pixel);
    s.pdf = pixel_pdf(pixel);
    s.pixel = pixel;
    return s;
}

ProbeSample Probe::sample_table(const LatLongTable& table, vec2 u) const {
    ProbeSample s;
    if (table.empty() || image_->empty()) {
        s.dir = glm::normalize(to_world(vec3(0, 1, 0)));
        s.radiance = vec3(0);
        return s;
    }
    const LatLongTable::Pick pick = table.sample(u);
    const int w = width();
    const size_t j = pick.pixel / size_t(w), i = pick.pixel % size_t(w);
    const Row& row = rows_[j];
    // Uniform in solid angle inside the pixel, as sample() does.
    const double cos_theta = row.cos_top + row.cos_span * pick.fy;
    const float sin_theta = float(std::sqrt(std::max(0.0, (1 - cos_theta) * (1 + cos_theta))));
    const float phi = float(2 * kPiD * ((double(i) + pick.fx) / w - 0.5));
    const vec3 d(sin_theta * std::sin(phi), float(cos_theta), -sin_theta * std::cos(phi));
    s.dir = glm::normalize(to_world(d));
    s.radiance = pixel_radiance(pick.pixel);
    // The full table's pdf is the probe's own, rounded as pdf() rounds it.
    s.pdf = &table == &inverse_->table ? pixel_pdf(pick.pixel) : float(table.pmf(pick.pixel) / row.solid_angle);
    s.pixel = pick.pixel;
    return s;
}

float Probe::pdf(const vec3& dir) const {
    if (total_power_ <= 0 || columns_.empty()) return 0;
    return pixel_pdf(latlong_pixel(to_probe(dir), width(), height()));
}

}  // namespace dp
