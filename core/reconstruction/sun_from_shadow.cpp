#include "reconstruction/sun_from_shadow.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/rng.h"
#include "base/sampling.h"
#include "probe/probe_sun.h"

namespace dp {

namespace {

const char* kField = "sun_from_shadow";
/// Real-to-real bounces followed (albedo 0.5: what is left after three is 6%).
constexpr int kBounces = 3;

std::string pixel_text(const vec2& p) {
    return "(" + std::to_string(int(std::lround(p.x))) + ", " + std::to_string(int(std::lround(p.y))) + ")";
}

/// The real hit a patch centre shows, its normal turned to the camera, and the patch's mean
/// photographed luminance.
struct Patch {
    Hit hit;
    vec3 n{0};
    double luminance = 0;
};

Patch read_patch(const RenderScene& scene, const vec2& centre, int radius, const char* which) {
    const Image& photo = scene.photo();
    const int cx = int(std::lround(centre.x)), cy = int(std::lround(centre.y));
    if (cx - radius < 0 || cy - radius < 0 || cx + radius >= photo.width() || cy + radius >= photo.height())
        throw InputError("", kField,
                         std::string("the ") + which + " patch around " + pixel_text(centre) +
                             " is not inside the photo (" + std::to_string(photo.width()) + "x" +
                             std::to_string(photo.height()) + ")");
    Patch p;
    const Camera& camera = scene.camera();
    p.hit = scene.intersect_real(camera.generate_ray(float(cx), float(cy)));
    if (!p.hit)
        throw InputError("", kField,
                         std::string("the ") + which + " patch " + pixel_text(centre) +
                             " shows no real proxy; click a surface that has one");
    p.n = glm::dot(p.hit.ng, camera.position() - p.hit.p) >= 0 ? p.hit.ng : -p.hit.ng;
    double sum = 0;
    for (int y = cy - radius; y <= cy + radius; ++y)
        for (int x = cx - radius; x <= cx + radius; ++x) sum += luminance(photo.at(x, y));
    p.luminance = sum / double((2 * radius + 1) * (2 * radius + 1));
    return p;
}

/// A patch's luminance irradiance, in the parts that the sun's scale multiplies or not.
struct Irradiance {
    double sky = 0;         ///< the sky, directly and off one real proxy
    double sun_direct = 0;  ///< the sun, directly
    double sun_bounce = 0;  ///< the sun off one real proxy
};

/// The sun's pixels as world directions, with their radiance times solid angle.
struct SunPixel {
    vec3 dir;
    double flux;
};

}  // namespace

SunFromShadow match_sun_to_shadow(const RenderScene& scene, const SunShadowPatches& patches, int sky_samples,
                                  uint64_t seed) {
    const Probe& probe = scene.probe();
    const ProbeSun sun = find_probe_sun(probe.image());
    if (!sun.found)
        throw InputError("", kField, "the probe has no compact sun to restore (no small bright region stands alone)");
    const int w = probe.width(), h = probe.height();
    std::vector<bool> in_sun(size_t(w) * h, false);
    std::vector<SunPixel> sun_pixels;
    for (uint32_t k : sun.pixels) {
        in_sun[k] = true;
        sun_pixels.push_back({probe.to_world(latlong_pixel_direction(k, w, h)), luminance(probe.pixel_radiance(k)) *
                                                     probe.pixel_solid_angle(int(k / uint32_t(w)))});
    }

    const Patch lit = read_patch(scene, patches.lit, patches.radius, "lit");
    const Patch shadow = read_patch(scene, patches.shadow, patches.radius, "shadowed");
    if (lit.hit.surface != shadow.hit.surface)
        throw InputError("", kField,
                         "the lit and the shadowed patch lie on two real proxies; click two patches of one "
                         "surface, which share its albedo");
    double sun_total = 0;
    std::vector<double> sun_cdf;
    for (const SunPixel& sp : sun_pixels) sun_cdf.push_back(sun_total += sp.flux);
    auto visible = [&](const Hit& hit, const vec3& n, const vec3& d) {
        Hit at = hit;
        at.ng = n;
        return glm::dot(n, d) > 0 && !scene.occluded_real(Ray{scene.offset_origin(at, d), d});
    };
    auto sky_radiance = [&](const vec3& d) {
        return in_sun[latlong_pixel(probe.to_probe(d), w, h)] ? 0.0 : double(luminance(probe.radiance(d)));
    };
    // One sun pixel drawn by its flux: an estimate of the sun's irradiance at (hit, n).
    auto sun_sample = [&](const Hit& hit, const vec3& n, Rng& rng) {
        const double u = rng.uniform() * sun_total;
        const size_t k = std::min(sun_pixels.size() - 1,
                                  size_t(std::lower_bound(sun_cdf.begin(), sun_cdf.end(), u) - sun_cdf.begin()));
        const vec3& d = sun_pixels[k].dir;
        return visible(hit, n, d) ? sun_total * double(glm::dot(n, d)) : 0.0;
    };
    // A patch's irradiance as sky + s * sun, each directly and after bounces off the real
    // proxies: the sunlit floor lights a slab's underside, which lights the slab's shadow.
    auto irradiance = [&](const Patch& p, uint64_t stream) {
        Rng rng = rng_stream::probe_alignment(seed, stream);
        Irradiance e;
        for (const SunPixel& sp : sun_pixels)
            if (visible(p.hit, p.n, sp.dir)) e.sun_direct += sp.flux * double(glm::dot(p.n, sp.dir));
        double sky = 0, bounce_sun = 0;
        for (int k = 0; k < sky_samples; ++k) {
            // A cosine-weighted walk: each real vertex adds its sun (one pixel drawn by flux)
            // times the albedos so far; what escapes adds the sky.
            Hit at = p.hit;
            vec3 n = p.n;
            double weight = 1;  // product of rho over the bounces (cosine and pi cancel)
            for (int bounce = 0; bounce <= kBounces; ++bounce) {
                const vec3 d = Frame(n).to_world(sample_cosine_hemisphere(vec2(rng.uniform(), rng.uniform())));
                at.ng = n;
                const Hit y = scene.intersect_real(Ray{scene.offset_origin(at, d), d});
                if (!y) {
                    sky += weight * sky_radiance(d);
                    break;
                }
                if (bounce == kBounces) break;
                n = glm::dot(y.ng, d) < 0 ? y.ng : -y.ng;
                weight *= luminance(y.surface->reflectance_at(y.uv));
                bounce_sun += weight * double(kInvPi) * sun_sample(y, n, rng);
                at = y;
            }
        }
        e.sky = double(kPi) * sky / std::max(1, sky_samples);
        e.sun_bounce = double(kPi) * bounce_sun / std::max(1, sky_samples);
        return e;
    };

    SunFromShadow out;
    const Irradiance el = irradiance(lit, 0), es = irradiance(shadow, 1);
    out.sun_lit = el.sun_direct;
    out.sky_lit = el.sky;
    out.sky_shadow = es.sky;
    if (!(el.sun_direct > 0))
        throw InputError("", kField,
                         "the probe's sun does not reach the lit patch " + pixel_text(patches.lit) +
                             " (it faces away, or a real proxy hides it): click a sunlit patch");
    if (!(shadow.luminance > 0) || !(es.sky > 0))
        throw InputError("", kField, "the shadowed patch " + pixel_text(patches.shadow) + " is black or gets no sky");
    out.photo_contrast = lit.luminance / shadow.luminance;
    const double R = out.photo_contrast;
    const double a_l = el.sky, b_l = el.sun_direct + el.sun_bounce;
    const double a_s = es.sky, b_s = es.sun_direct + es.sun_bounce;
    out.probe_contrast = (a_l + b_l) / (a_s + b_s);
    // (a_l + s b_l) / (a_s + s b_s) = R, the albedo cancelling.
    const double s = (R * a_s - a_l) / (b_l - R * b_s);
    if (!(s > 0) || !std::isfinite(s) || !(b_l - R * b_s > 0))
        throw InputError("", kField,
                         "the photo's contrast between the patches (" + std::to_string(out.photo_contrast) +
                             ") is not one the probe's sky and a stronger or weaker sun can give: is the lit "
                             "patch in sunlight and the other in shadow, on one surface? (the sky alone gives " +
                             std::to_string(a_l / a_s) + ")");
    out.scale = float(s);
    out.sun_scale = scene.project().probe.sun_scale * out.scale;
    return out;
}

}  // namespace dp
