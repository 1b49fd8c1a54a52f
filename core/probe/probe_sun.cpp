#include "probe/probe_sun.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "probe/probe.h"

namespace dp {

namespace {

constexpr double pi = std::numbers::pi;

double row_solid_angle(size_t pixel, int w, int h) { return latlong_row_solid_angle(int(pixel / size_t(w)), w, h); }

}  // namespace

ProbeSun find_probe_sun(const Image& latlong) {
    ProbeSun sun;
    const int w = latlong.width(), h = latlong.height();
    const size_t n = size_t(std::max(0, w)) * size_t(std::max(0, h));
    size_t brightest = 0;
    for (size_t k = 0; k < n; ++k)
        if (luminance(latlong.data()[k]) > luminance(latlong.data()[brightest])) brightest = k;
    sun.peak = n > 0 ? luminance(latlong.data()[brightest]) : 0.0f;
    if (!(sun.peak > 0) || !std::isfinite(sun.peak)) return sun;
    const vec3 towards = latlong_pixel_direction(brightest, w, h);
    float min_cos = 1;  // of the angle between the brightest pixel and another near its value
    for (size_t k = 0; k < n; ++k) {
        const float l = luminance(latlong.data()[k]);
        if (l >= 0.5f * sun.peak) sun.half_peak_solid_angle += row_solid_angle(k, w, h);
        if (l < kCeilingLevel * sun.peak) continue;
        ++sun.near_peak;
        min_cos = std::min(min_cos, glm::dot(latlong_pixel_direction(k, w, h), towards));
    }
    sun.near_peak_spread_deg = std::acos(std::clamp(double(min_cos), -1.0, 1.0)) * 180 / pi;
    const float cap_cos = float(std::cos(kSunCapDeg * pi / 180.0));
    for (float level : kSunLevels) {
        std::vector<uint32_t> pixels;
        bool compact = true;
        for (size_t k = 0; k < n && compact; ++k) {
            if (!(luminance(latlong.data()[k]) >= level * sun.peak)) continue;
            if (glm::dot(latlong_pixel_direction(k, w, h), towards) < cap_cos)
                compact = false;  // as bright out there: a bright sky, not a sun
            else
                pixels.push_back(uint32_t(k));
        }
        if (!compact) continue;
        sun.found = true;
        sun.level = level;
        sun.pixels = std::move(pixels);
        break;
    }
    if (!sun.found) return sun;
    dvec3 centre(0);
    std::vector<bool> in_sun(n, false);
    for (uint32_t k : sun.pixels) {
        const double flux = luminance(latlong.data()[k]) * row_solid_angle(k, w, h);
        centre += dvec3(latlong_pixel_direction(k, w, h)) * flux;
        sun.sun_irradiance += flux;
        sun.solid_angle += row_solid_angle(k, w, h);
        in_sun[k] = true;
    }
    sun.direction = glm::length(centre) > 0 ? vec3(glm::normalize(centre)) : towards;
    sun.elevation_deg = std::asin(std::clamp(double(sun.direction.y), -1.0, 1.0)) * 180.0 / pi;
    for (int j = 0; j < h; ++j) {
        const double up = std::cos(pi * (j + 0.5) / h);  // the row centre's height
        if (up <= 0) break;
        double row = 0;
        for (int i = 0; i < w; ++i) {
            const size_t k = size_t(j) * w + i;
            if (!in_sun[k]) row += std::max(0.0f, luminance(latlong.data()[k]));
        }
        sun.sky_irradiance += row * up * latlong_row_solid_angle(j, w, h);
    }
    return sun;
}

std::string clipped_sun_warning(const ProbeSun& sun, const std::string& field) {
    char text[512];
    if (sun.near_peak_spread_deg > kSunCapDeg && sun.half_peak_solid_angle < kMaxCeilingSolidAngle) {
        std::snprintf(text, sizeof(text),
                      "%s: the probe's %d brightest pixels lie up to %.0f deg from the brightest yet all within "
                      "5%% of its value (%.4g): separate lights do not match that closely, a camera's ceiling does. Its "
                      "lights are likely clipped, and shadows will come out too weak. Restore the sun from a "
                      "lit and a shadowed patch of one surface in the photo (the studio's Sun strength from a "
                      "shadow, or `calibrate probe --sun-from-shadow`; docs/probe-sun.md)",
                      field.c_str(), sun.near_peak, sun.near_peak_spread_deg, double(sun.peak));
        return text;
    }
    if (!sun.found || sun.elevation_deg < kCheckedElevationDeg || sun.sky_irradiance <= 0) return {};
    if (sun.ratio() >= kMinSunSkyRatio) return {};
    std::snprintf(text, sizeof(text),
                  "%s: the probe's sun (%.0f deg up, peak %.4g) gives a surface facing it %.2g times the "
                  "light the sky gives the ground, where a clear sun that high gives 3 to 10 times: it is "
                  "likely clipped, and shadows will come out too weak. Restore it from a lit and a shadowed "
                  "patch of one surface in the photo (the studio's Sun strength from a shadow, or `calibrate "
                  "probe --sun-from-shadow`; docs/probe-sun.md)",
                  field.c_str(), sun.elevation_deg, double(sun.peak), sun.ratio());
    return text;
}

void scale_probe_sun(Image& latlong, const ProbeSun& sun, float scale) {
    for (uint32_t k : sun.pixels) latlong.data()[k] *= scale;
}

}  // namespace dp
