#include "probe/probe_lights.h"

#include <algorithm>

namespace dp {

ProbeLights::ProbeLights(const Probe& probe) : probe_(&probe) {
    const int w = probe.width(), h = probe.height();
    const size_t n = size_t(std::max(0, w)) * size_t(std::max(0, h));
    if (n == 0 || probe.total_luminance_power() <= 0) return;
    float brightest = 0;
    for (size_t k = 0; k < n; ++k) brightest = std::max(brightest, luminance(probe.pixel_radiance(k)));
    // Asked again while the tables are built rather than kept per pixel.
    auto bright = [&](size_t k) {
        return probe.pixel_weight(k) > 0 && luminance(probe.pixel_radiance(k)) >= kSunLevel * brightest;
    };
    double sun_power = 0, sun_solid_angle = 0;
    for (size_t k = 0; k < n; ++k)
        if (bright(k)) {
            sun_power += probe.pixel_weight(k);
            sun_solid_angle += probe.pixel_solid_angle(int(k / size_t(w)));
        }
    const double share = sun_power / probe.total_luminance_power();
    // Everything bright (a studio probe) or a small share: one light, the whole probe.
    const bool split = sun_solid_angle <= kMaxSunSolidAngle && share >= kMinSunShare && share < 1;
    if (split) {
        sun_ = LatLongTable(w, h, [&](size_t k) { return bright(k) ? probe.pixel_weight(k) : 0.0; });
        sun_share_ = share;
    }
    sky_ = LatLongTable(w, h, [&](size_t k) { return split && bright(k) ? 0.0 : probe.pixel_weight(k); });
}

float ProbeLights::pdf(const vec3& dir) const {
    if (sky_.empty() && sun_.empty()) return 0;
    const int w = probe_->width(), h = probe_->height();
    const size_t k = latlong_pixel(probe_->to_probe(dir), w, h);
    const double sun_pmf = sun_.pmf(k);
    const double pmf = sun_pmf > 0 ? sun_pmf : sky_.pmf(k);
    // As sample_table() rounds it, so that a direction's pdf is the one its sample carried.
    return float(pmf / probe_->pixel_solid_angle(int(k / size_t(w))));
}

float ProbeLights::sun_pdf(const vec3& dir) const {
    if (sun_.empty()) return 0;
    const int w = probe_->width(), h = probe_->height();
    const size_t k = latlong_pixel(probe_->to_probe(dir), w, h);
    return float(sun_.pmf(k) / probe_->pixel_solid_angle(int(k / size_t(w))));
}

}  // namespace dp
