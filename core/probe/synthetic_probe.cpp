#include "probe/synthetic_probe.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "probe/probe.h"

namespace dp {

namespace {
vec3 pixel_centre_direction(int i, int j, int w, int h) {
    return latlong_direction((i + 0.5f) / float(w), (j + 0.5f) / float(h));
}
}  // namespace

Image make_constant_probe(int w, int h, vec3 radiance) { return Image(w, h, radiance); }

Image make_sun_sky_probe(int w, int h, vec3 sun_dir_probe_space, vec3 sun_radiance,
                         float sun_angular_radius_deg, vec3 sky_zenith, vec3 sky_horizon) {
    Image img(w, h);
    if (img.empty()) return img;
    if (!(glm::length(sun_dir_probe_space) > 0))
        throw std::invalid_argument("make_sun_sky_probe: the sun direction has no length");
    vec3 sun = glm::normalize(sun_dir_probe_space);
    // Compare cosines in double: a sun of a fraction of a degree has cos(radius) within 1e-5 of 1.
    double cos_radius = std::cos(double(sun_angular_radius_deg) * std::numbers::pi / 180);
    bool any_sun = false;
    int best_i = 0, best_j = 0;
    double best_cos = -2;
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            vec3 d = pixel_centre_direction(i, j, w, h);
            double c = double(d.x) * sun.x + double(d.y) * sun.y + double(d.z) * sun.z;
            if (c > best_cos) {
                best_cos = c;
                best_i = i;
                best_j = j;
            }
            if (c >= cos_radius) {
                img.at(i, j) = sun_radiance;
                any_sun = true;
            } else if (d.y > 0) {
                img.at(i, j) = glm::mix(sky_horizon, sky_zenith, d.y);
            }
        }
    }
    if (!any_sun) img.at(best_i, best_j) = sun_radiance;
    return img;
}

Image make_single_pixel_probe(int w, int h, int px, int py, vec3 radiance) {
    if (px < 0 || py < 0 || px >= w || py >= h)
        throw std::out_of_range("make_single_pixel_probe: pixel outside the map");
    Image img(w, h);
    img.at(px, py) = radiance;
    return img;
}

}  // namespace dp
