#include "probe/probe_lights.h"

#include <algorithm>

namespace dp {

ProbeLights::ProbeLights(const Probe& probe) : probe_(&probe) {
    const int w = probe.width(), h = probe.height();
    const size_t n = size_t(std::max(0, w)) * size_t(std::max(0, h));
    if (n == 0 || probe.total_luminance_power() <= 0) return;
    float brightest = 0;
    for (size_t k = 0; k < n; ++k) brightest = std::max(brightest, luminance(probe.pixel_radiance(k)));
    in_sun_.assign(n, 0);
    double sun_power = 0, sun_solid_angle = 0;
    for (size_t k = 0; k < n; ++k)
        if (probe.pixel_weight(k) > 0 && luminance(probe.pixel_radiance(k)) >= kSunLevel * brightest) {
            in_sun_[k] = 1;
            sun_power += probe.pixel_weight(k);
            sun_solid_angle += probe.pixel_solid_angle(int(k / size_t(w)));
        }
    const double share = sun_power / probe.total_luminance_power();
    // Everything bright (a studio probe) or a small share: one light, the whole probe.
    const bool split = sun_solid_angle <= kMaxSunSolidAngle && share >= kMinSunShare && share < 1;
    if (!split) std::fill(in_sun_.begin(), in_sun_.end(), uint8_t(0));
    std::vector<double> sun(n, 0.0), sky(n, 0.0);
    for (size_t k = 0; k < n; ++k) (in_sun_[k] ? sun : sky)[k] = probe.pixel_weight(k);
    if (split) {
        sun_ = LatLongTable(w, h, sun);
        sun_share_ = share;
    }
    sky_ = LatLongTable(w, h, sky);
    pdf_.resize(n);
    for (size_t k = 0; k < n; ++k) {
        const LatLongTable& owner = in_sun_[k] ? sun_ : sky_;
        pdf_[k] = float(owner.pmf(k) / probe.pixel_solid_angle(int(k / size_t(w))));
    }
}

float ProbeLights::pdf(const vec3& dir) const {
    if (pdf_.empty()) return 0;
    return pdf_[latlong_pixel(probe_->to_probe(dir), probe_->width(), probe_->height())];
}

}  // namespace dp
