#include "reconstruction/probe_align.h"
#include "base/euler.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "assets/irradiance.h"
#include "base/error.h"
#include "base/rng.h"
#include "probe/probe.h"
#include "reconstruction/proxies.h"

namespace dp {

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

double wrap_deg(double a) {
    a = std::fmod(a, 360.0);
    if (a > 180) a -= 360;
    if (a <= -180) a += 360;
    return a;
}

}  // namespace

vec3 sun_direction_from_shadow(const Camera& camera, const ShadowCue& cue) {
    if (!(cue.height > 0) || !std::isfinite(cue.height))
        throw InputError("", "object_height",
                         "the object point's height must be a positive number");
    vec3 tip = point_on_plane_y(camera, cue.shadow_px, 0, "shadow tip");
    vec3 top =
        cue.object_is_base
            ? point_on_plane_y(camera, cue.object_px, 0, "object base") + vec3(0, cue.height, 0)
            : point_on_plane_y(camera, cue.object_px, cue.height, "object point");
    vec3 d = top - tip;
    float horizontal = std::hypot(d.x, d.z);
    if (horizontal <= 1e-4f * cue.height)
        throw InputError(
            "", "shadow tip",
            "the shadow tip lies at the object's foot: the sun would be straight overhead, "
            "which gives no azimuth");
    return glm::normalize(d);
}

Bearing bearing_of(const vec3& d) {
    constexpr float kDegPerRad = 180.0f / kPi;
    return {std::atan2(d.x, -d.z) * kDegPerRad, std::asin(d.y) * kDegPerRad};
}

vec3 brightest_direction(const Image& map, float fraction, float cone_deg,
                         const std::string& field) {
    const int W = map.width(), H = map.height();
    size_t best = 0;
    float best_lum = 0;
    for (size_t i = 0; i < map.size(); ++i) {
        float l = luminance(map[i]);
        if (std::isfinite(l) && l > best_lum) {
            best_lum = l;
            best = i;
        }
    }
    if (!(best_lum > 0))
        throw InputError("", field, "the light probe is black: it has no bright region");
    auto dir = [&](int i, int j) { return latlong_direction((i + 0.5f) / W, (j + 0.5f) / H); };
    const vec3 peak = dir(int(best % W), int(best / W));
    const float cos_cone = std::cos(cone_deg / float(kDeg));
    dvec3 sum(0.0);
    for (int j = 0; j < H; ++j) {
        double sin_theta = std::sin(std::numbers::pi * (j + 0.5) / H);
        for (int i = 0; i < W; ++i) {
            float l = luminance(map.at(i, j));
            if (!(l >= fraction * best_lum) || !std::isfinite(l)) continue;
            vec3 d = dir(i, j);
            if (glm::dot(d, peak) < cos_cone) continue;
            sum += dvec3(d) * (double(l) * sin_theta);
        }
    }
    if (!(glm::length(sum) > 0)) return peak;
    return vec3(glm::normalize(sum));
}

ProbeYaw align_probe_yaw(const vec3& bright_probe, const vec3& rotation_deg,
                         const vec3& target_world) {
    const glm::mat3 R = euler_xyz_deg(rotation_deg);
    const vec3 a = glm::normalize(R * bright_probe), b = glm::normalize(target_world);
    const double ha = std::hypot(a.x, a.z), hb = std::hypot(b.x, b.z);
    if (ha < 1e-4)
        throw InputError("", "probe",
                         "the probe's brightest region is straight up or down: it has no azimuth");
    if (hb < 1e-4) throw InputError("", "sun", "the sun direction is vertical: it has no azimuth");
    // Turn about +Y taking a's azimuth to b's: sine from the Y component of the cross product.
    double s = double(a.z) * b.x - double(a.x) * b.z, c = double(a.x) * b.x + double(a.z) * b.z;
    double yaw = std::atan2(s, c) * kDeg;

    ProbeYaw out;
    out.yaw_deg = float(wrap_deg(yaw));
    const glm::mat3 turned = euler_xyz_deg(vec3(0, out.yaw_deg, 0)) * R;
    if (rotation_deg.x == 0 && rotation_deg.z == 0) {
        out.rotation_deg = vec3(0, float(wrap_deg(double(rotation_deg.y) + out.yaw_deg)), 0);
    } else {
        out.rotation_deg = euler_xyz_from_matrix(turned);
    }
    out.bright_world = glm::normalize(turned * bright_probe);
    out.elevation_mismatch_deg =
        float((std::asin(std::clamp(double(out.bright_world.y), -1.0, 1.0)) -
               std::asin(std::clamp(double(b.y), -1.0, 1.0))) *
              kDeg);
    return out;
}

namespace {

/// What tracing a grey card's pixels gives: the photographed radiance and the irradiance the
/// probe delivers there, summed per channel over the card.
struct CardSums {
    dvec3 L{0.0}, E{0.0};
    std::vector<double> ratios;  ///< per pixel, pi L / (rho E) in luminance, where E > 0
};

CardSums trace_card(const RenderScene& scene, const GreyCard& card, float clip_level,
                    int probe_samples, uint64_t seed) {
    const Image& photo = scene.photo();
    if (!(card.reflectance > 0 && card.reflectance <= 1))
        throw InputError("", "reflectance", "the card's reflectance must be in (0, 1]");
    int x0 = std::min(card.x0, card.x1), x1 = std::max(card.x0, card.x1);
    int y0 = std::min(card.y0, card.y1), y1 = std::max(card.y0, card.y1);
    if (x0 < 0 || y0 < 0 || x1 >= photo.width() || y1 >= photo.height())
        throw InputError("", "card",
                         "the card rectangle (" + std::to_string(x0) + ", " + std::to_string(y0) +
                             ") - (" + std::to_string(x1) + ", " + std::to_string(y1) +
                             ") is not inside the photo (" + std::to_string(photo.width()) + "x" +
                             std::to_string(photo.height()) + ")");
    const Camera& camera = scene.camera();
    CardSums sums;
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            Hit hit = scene.intersect_real(camera.generate_ray(float(x), float(y)));
            if (!hit)
                throw InputError("", "card",
                                 "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                     ") of the card shows no real proxy; put the card on one");
            vec3 L = photo.at(x, y);
            if (std::max({L.x, L.y, L.z}) >= clip_level)
                throw InputError("", "card",
                                 "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                     ") of the card is clipped in the photo");
            vec3 n = glm::dot(hit.ng, camera.position() - hit.p) >= 0 ? hit.ng : -hit.ng;
            Rng rng = rng_stream::probe_alignment(seed, size_t(y) * photo.width() + x);
            const dvec3 E(real_irradiance(scene, hit.p, n, rng, probe_samples).E);
            sums.L += dvec3(L);
            sums.E += E;
            if (luminance(E) > 0)
                sums.ratios.push_back(double(kPi) * luminance(L) /
                                      (card.reflectance * luminance(E)));
        }
    if (!(luminance(sums.E) > 0))
        throw InputError(
            "", "card",
            "the probe gives the card no light (probe intensity 0, or the card in full shadow)");
    if (!(luminance(sums.L) > 0)) throw InputError("", "card", "the card is black in the photo");
    return sums;
}

/// The coefficient of variation of `ratios`.
float spread_of(const std::vector<double>& ratios) {
    double mean = 0, var = 0;
    for (double r : ratios) mean += r / ratios.size();
    for (double r : ratios) var += (r - mean) * (r - mean) / ratios.size();
    return mean > 0 ? float(std::sqrt(var) / mean) : 0.0f;
}

vec3 chromaticity(const dvec3& c) {
    const double sum = c.x + c.y + c.z;
    return sum > 0 ? vec3(c / sum) : vec3(1.0f / 3.0f);
}

}  // namespace

ExposureMatch match_exposure_grey_card(const RenderScene& scene, const GreyCard& card,
                                       float clip_level, int probe_samples, uint64_t seed) {
    const CardSums sums = trace_card(scene, card, clip_level, probe_samples, seed);
    ExposureMatch out;
    out.pixels = int(sums.ratios.size());
    out.scale = float(double(kPi) * luminance(sums.L) / (card.reflectance * luminance(sums.E)));
    out.intensity = scene.project().probe.intensity * out.scale;
    out.spread = spread_of(sums.ratios);
    return out;
}

WhiteBalanceMatch match_white_balance_grey_card(const RenderScene& scene, const GreyCard& card,
                                                float clip_level, int probe_samples,
                                                uint64_t seed) {
    const CardSums sums = trace_card(scene, card, clip_level, probe_samples, seed);
    const char* channel[] = {"red", "green", "blue"};
    for (int c = 0; c < 3; ++c) {
        if (!(sums.E[c] > 0))
            throw InputError("", "card",
                             std::string("the probe gives the card no ") + channel[c] +
                                 " light: its white balance cannot be matched");
        if (!(sums.L[c] > 0))
            throw InputError("", "card",
                             std::string("the card is black in the photo's ") + channel[c] +
                                 " channel: its white balance cannot be matched");
    }
    const ProbeSpec& probe = scene.project().probe;
    WhiteBalanceMatch out;
    out.pixels = int(sums.ratios.size());
    out.spread = spread_of(sums.ratios);
    const dvec3 gain = double(kPi) * sums.L / (double(card.reflectance) * sums.E);
    out.channel_scale = vec3(gain);
    // The new gain per channel, split into a brightness and a colour of luminance 1.
    const dvec3 total = dvec3(probe.gain()) * gain;
    const double lum = luminance(total);
    out.intensity = float(lum);
    out.white_balance = vec3(total / lum);
    out.scale = probe.intensity > 0 ? float(lum / probe.intensity) : 0.0f;
    out.photo_chromaticity = chromaticity(sums.L);
    out.before_chromaticity = chromaticity(sums.E);
    out.after_chromaticity = chromaticity(sums.E * gain);
    return out;
}

}  // namespace dp
