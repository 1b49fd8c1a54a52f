#include "render/photon_balance.h"

#include <algorithm>
#include <cmath>

namespace dp {

PhotonBalance::PhotonBalance(int64_t initial, int64_t least, int64_t most, size_t pixels)
    : photons_(std::clamp(initial, least, std::max(least, most))), least_(least), most_(std::max(least, most)),
      sums_(pixels) {}

bool PhotonBalance::end_pass(uint64_t photon_rays, size_t camera_samples) {
    photon_rays_ += double(photon_rays);
    camera_samples_ += double(camera_samples);
    return ++passes_ >= kWindow;
}

int64_t PhotonBalance::next_count(int64_t n, double var_photons, double var_rest, double cost_photons,
                                  double cost_rest, int64_t least, int64_t most, bool damped) {
    double step = kMaxStep;  // no noise left but the photons': more of them
    if (!(var_photons > 0)) step = 1.0 / kMaxStep;
    else if (var_rest > 0 && cost_photons > 0)
        step = std::clamp(std::sqrt(var_photons * cost_rest / (var_rest * cost_photons)), 1.0 / kMaxStep, kMaxStep);
    if (damped) step = std::clamp(std::sqrt(step), 0.5, 2.0);
    const double next = std::round(double(n) * step);
    return std::clamp(int64_t(next), least, std::max(least, most));
}

int64_t PhotonBalance::decide(const std::function<bool(size_t)>& counted) {
    const double n = double(passes_);
    double vp = 0, vr = 0;
    for (size_t i = 0; i < sums_.size(); ++i) {
        const Sums& s = sums_[i];
        if (s.pp == 0 && s.rr == 0) continue;
        if (!counted(i)) continue;
        vp += std::max(0.0, s.pp / n - (s.p / n) * (s.p / n));
        vr += std::max(0.0, s.rr / n - (s.r / n) * (s.r / n));
    }
    if (vp + vr > 0) {
        share_ = vp / (vp + vr);
        photons_ = next_count(photons_, vp, vr, photon_rays_ / n, kRaysPerCameraSample * camera_samples_ / n,
                              least_, most_, decisions_++ > 0);
    }
    std::fill(sums_.begin(), sums_.end(), Sums{});
    passes_ = 0;
    photon_rays_ = camera_samples_ = 0;
    return photons_;
}

}  // namespace dp
