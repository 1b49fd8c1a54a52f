#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace dp {

/// Sets a render's photons per pass from what they add to the error per unit of work, in the
/// spirit of Grittmann et al. 2018 ("lightweight photon mapping") and 2022 ("efficiency-aware
/// multiple importance sampling"). Under the split estimator a pixel's change is the sum of a
/// photon estimate and a ray estimate (direct light, objects), independent within a pass. With
/// per-pass variances V_p (photons) and V_r (rays) over the changed pixels and per-pass costs
/// C_p, C_r, the photon count that minimises error x time is N sqrt(V_p C_r / (V_r C_p)): a
/// change that is all direct shadow spends almost nothing on photons, a caustic most.
///
/// Deterministic: the costs are counted in rays, not timed, so a render is the same on every
/// machine and in every run (a studio's picture and the CLI's agree bit for bit).
class PhotonBalance {
public:
    /// Camera samples are weighed as this many photon rays: a camera sample with its direct
    /// estimate and gather costs about what 7 to 14 photon rays do (timed per pass on the soft
    /// shadow, caustic and bleeding benchmark scenes).
    static constexpr double kRaysPerCameraSample = 10.0;
    /// Passes measured before each decision.
    static constexpr int kWindow = 4;
    /// The most a decision changes the count by (either way): the variances come from few passes
    /// and a caustic's are heavy-tailed. The first decision may go this far; later ones go half
    /// the way (in log) to what their window asks, at most a factor 2, so one noisy window does
    /// not swing the count.
    static constexpr double kMaxStep = 4.0;

    /// `initial` photons per pass (the project's), between `least` and `most`.
    PhotonBalance(int64_t initial, int64_t least, int64_t most, size_t pixels);

    /// The count the next pass traces.
    int64_t photons() const { return photons_; }
    /// The last decision's V_p / (V_p + V_r); negative before the first.
    double photon_share() const { return share_; }

    /// One shaded sample of pixel i in the current pass: the photons' part of its luminance
    /// change and the rest. Pixels not shaded in a pass count as 0 for both. Thread-safe for
    /// distinct pixels.
    void add(size_t i, float photon, float rest) {
        Sums& s = sums_[i];
        s.p += photon, s.pp += double(photon) * photon, s.r += rest, s.rr += double(rest) * rest;
    }
    /// Ends a pass that traced `photon_rays` and shaded `camera_samples`. True when a decision
    /// is due (call decide).
    bool end_pass(uint64_t photon_rays, size_t camera_samples);
    /// The next count from the variances of the pixels `counted` picks (the changed pixels of
    /// tiles still sampled), then starts a new window.
    int64_t decide(const std::function<bool(size_t)>& counted);

    /// The count one window asks for: n sqrt(V_p C_r / (V_r C_p)), the step bounded by
    /// kMaxStep; `damped`: half of that step (in log), at most 2. Within [least, most].
    static int64_t next_count(int64_t n, double var_photons, double var_rest, double cost_photons,
                              double cost_rest, int64_t least, int64_t most, bool damped = false);

private:
    struct Sums {
        double p = 0, pp = 0, r = 0, rr = 0;
    };
    int64_t photons_, least_, most_;
    double share_ = -1.0;
    int passes_ = 0, decisions_ = 0;
    double photon_rays_ = 0, camera_samples_ = 0;
    std::vector<Sums> sums_;
};

}  // namespace dp
