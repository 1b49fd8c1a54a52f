#pragma once
#include "probe/latlong_table.h"
#include "probe/probe.h"

namespace dp {

/// The probe as two lights for next-event estimation: its sun (the brightest pixels, when they
/// are compact and carry a fair share of the power) and the rest, the sky. Each has its own
/// table, so an estimate takes one sample of each: a sample drawn from the whole probe lands
/// on the sun only with the sun's share of the power, and a shadow estimated from it flickers
/// between none and too much. Without a sun the sky is the whole probe.
class ProbeLights {
public:
    /// Pixels at least this fraction of the brightest pixel's luminance are the sun's...
    static constexpr double kSunLevel = 0.05;
    /// ...if they cover at most this solid angle (a disk of about 10 degrees)...
    static constexpr double kMaxSunSolidAngle = 0.1;
    /// ...and carry at least this share of the probe's power.
    static constexpr double kMinSunShare = 0.2;

    ProbeLights() = default;
    explicit ProbeLights(const Probe& probe);

    bool has_sun() const { return !sun_.empty(); }
    double sun_share() const { return sun_share_; }
    /// A direction towards the sun (pdf over the sun's pixels); pdf 0 without a sun.
    ProbeSample sample_sun(vec2 u) const { return probe_->sample_table(sun_, u); }
    /// A direction from the rest of the probe (pdf over the sky's pixels).
    ProbeSample sample_sky(vec2 u) const { return probe_->sample_table(sky_, u); }
    /// The pdf of the light that owns direction dir (the sun's table where dir is in the sun,
    /// the sky's elsewhere): the one other strategy that can draw dir.
    float pdf(const vec3& dir) const;
    /// The density with which sample_sun draws `dir` (0 outside the sun, or without one).
    float sun_pdf(const vec3& dir) const;
    /// Bytes the two tables hold per probe pixel.
    double bytes_per_pixel() const { return sun_.bytes_per_pixel() + sky_.bytes_per_pixel(); }

private:
    const Probe* probe_ = nullptr;
    /// The sun's table keeps only the sun's rows; a pixel is the sun's where its pmf there is
    /// positive, so no per-pixel owner or pdf is stored.
    LatLongTable sun_, sky_;
    double sun_share_ = 0;
};

}  // namespace dp
