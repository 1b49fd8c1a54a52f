// `diffphoton make-test-image` (hidden): small inputs for the shell tests, which have no other
// way to write EXR files.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "base/error.h"
#include "base/rng.h"
#include "commands.h"
#include "common.h"
#include "outputs.h"
#include "image/image_io.h"
#include "probe/probe.h"
#include "probe/synthetic_probe.h"

namespace dp::cli {

namespace {

struct TestImageOptions {
    std::string output;
    std::vector<int> size;
    std::vector<float> value{0.5f, 0.5f, 0.5f};
    std::vector<float> sun_dir{0.3f, 0.9f, 0.3f};
    float sun_irradiance = 3.0f;
    bool probe_sun = false, force = false;
    float sun_radius_deg = 0;
    std::vector<float> sky_zenith;
    int checker = 0;
    std::vector<int> box;  ///< x0 y0 x1 y1: a rectangle of value2 over the image
    float noise = 0;       ///< standard deviation of Gaussian grain added to every channel
    std::vector<float> value2{0.1f, 0.1f, 0.1f};
    size_t nan_pixels = 0;
};

/// A sun-and-sky probe: a sun disk of the given angular radius whose radiance makes the given
/// irradiance at normal incidence, over a sky graded from `horizon` to `zenith`.
Image sun_disk_probe(int w, int h, vec3 dir, float radius_deg, float irradiance, vec3 zenith,
                     vec3 horizon) {
    const double omega = 2.0 * kPi * (1.0 - std::cos(double(radius_deg) * kPi / 180.0));
    return make_sun_sky_probe(w, h, dir, vec3(float(irradiance / omega)), radius_deg, zenith, horizon);
}

/// `cells` x `cells` squares alternating between `a` and `b`, starting with `a` at the top left.
Image checker_image(int w, int h, int cells, vec3 a, vec3 b) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            img.at(x, y) = ((x * cells / w + y * cells / h) % 2 == 0) ? a : b;
    return img;
}

/// A lat-long sky of constant `sky` radiance with a one-pixel sun whose radiance makes the
/// given irradiance on a surface facing it.
Image sun_probe(int w, int h, vec3 dir, vec3 sky, float irradiance) {
    dir = glm::normalize(dir);
    const size_t pixel = latlong_pixel(dir, w, h);
    const int row = int(pixel / size_t(w));
    const double theta0 = kPi * row / h, theta1 = kPi * (row + 1) / h;
    const double omega = 2.0 * kPi / w * (std::cos(theta0) - std::cos(theta1));
    const float sun = float(irradiance / omega);
    Image img = make_sun_sky_probe(w, h, dir, vec3(sun), 0.0f, sky, sky);
    return img;
}

int run_make_test_image(const TestImageOptions& o) {
    const ImageKind kind = check_output_path(o.output, "output");
    const int w = o.size[0], h = o.size[1];
    check_outputs({{o.output, "output", image_output_bytes(o.output, {}, w, h)}}, {}, o.force);
    const vec3 value(o.value[0], o.value[1], o.value[2]);
    const vec3 sun_dir(o.sun_dir[0], o.sun_dir[1], o.sun_dir[2]);
    const vec3 zenith = o.sky_zenith.empty() ? value : vec3(o.sky_zenith[0], o.sky_zenith[1], o.sky_zenith[2]);
    Image img;
    if (o.probe_sun && o.sun_radius_deg > 0)
        img = sun_disk_probe(w, h, sun_dir, o.sun_radius_deg, o.sun_irradiance, zenith, value);
    else if (o.probe_sun)
        img = sun_probe(w, h, sun_dir, value, o.sun_irradiance);
    else if (o.checker > 0)
        img = checker_image(w, h, o.checker, value, vec3(o.value2[0], o.value2[1], o.value2[2]));
    else
        img = Image(w, h, value);
    if (!o.box.empty())
        for (int y = std::max(0, o.box[1]); y < std::min(h, o.box[3]); ++y)
            for (int x = std::max(0, o.box[0]); x < std::min(w, o.box[2]); ++x)
                img.at(x, y) = vec3(o.value2[0], o.value2[1], o.value2[2]);
    if (o.noise > 0) {
        Rng rng(17, 3);
        for (size_t i = 0; i < img.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                const float u1 = std::max(rng.uniform(), 1e-12f), u2 = rng.uniform();
                img[i][c] += o.noise * std::sqrt(-2.0f * std::log(u1)) * std::cos(2.0f * kPi * u2);
            }
    }
    if (o.nan_pixels > img.size())
        throw InputError(o.output, "--nan", "more NaN pixels than the image has");
    // Deliberately non-finite input: one NaN channel per pixel, spread over the image.
    for (size_t i = 0; i < o.nan_pixels; ++i)
        img[i * img.size() / o.nan_pixels].x = std::numeric_limits<float>::quiet_NaN();
    if (kind == ImageKind::Exr)
        save_exr(o.output, {{"", &img}});
    else
        save_ldr(o.output, img);
    return 0;
}

}  // namespace

Command add_make_test_image_command(CLI::App& app) {
    auto o = std::make_shared<TestImageOptions>();
    CLI::App* sub = app.add_subcommand("make-test-image", "Write a synthetic test image");
    sub->group("");  // hidden from --help
    sub->add_option("output", o->output, "Output .exr or .png")->required();
    sub->add_option("--size", o->size, "Width and height")
        ->expected(2)
        ->required()
        ->check(CLI::Range(1, 1 << 14));
    sub->add_option("--value", o->value, "Constant linear RGB (the sky with --probe-sun)")
        ->expected(3)
        ->check(kFinite);
    sub->add_flag("--probe-sun", o->probe_sun, "Lat-long probe: constant sky and a one-pixel sun");
    sub->add_option("--sun-dir", o->sun_dir, "Direction towards the sun")->expected(3);
    sub->add_option("--sun-irradiance", o->sun_irradiance, "Sun irradiance")->check(kFinite);
    sub->add_option("--sun-radius-deg", o->sun_radius_deg,
                    "With --probe-sun: a sun disk of this angular radius instead of one pixel")
        ->check(CLI::Range(0.0f, 45.0f));
    sub->add_option("--sky-zenith", o->sky_zenith, "With --probe-sun: zenith radiance (--value is the horizon)")
        ->expected(3)
        ->check(kFinite);
    sub->add_option("--checker", o->checker, "A checkerboard of this many cells a side (--value, --value2)")
        ->check(CLI::Range(1, 4096));
    sub->add_option("--value2", o->value2, "The checkerboard's (or the box's) second colour")->expected(3)->check(kFinite);
    sub->add_option("--noise", o->noise, "Gaussian grain of this standard deviation on every channel (a photo's)")
        ->check(CLI::Range(0.0f, 1.0f));
    sub->add_option("--box", o->box, "X0 Y0 X1 Y1: a rectangle of --value2 over the image (a board in a photo)")
        ->expected(4);
    sub->add_option("--nan", o->nan_pixels, "Number of pixels whose red channel is NaN");
    add_force_flag(sub, o->force);
    return {sub, [o] { return run_make_test_image(*o); }, [o] { check_output_path(o->output, "output"); }};
}

}  // namespace dp::cli
