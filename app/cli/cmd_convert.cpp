// `diffphoton convert` (HDR to 8-bit) and `diffphoton compare` (difference figures).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "base/error.h"
#include "commands.h"
#include "common.h"
#include "outputs.h"
#include "image/image_io.h"
#include "image/image_metrics.h"
#include "render/progressive.h"

namespace dp::cli {

namespace {

Image load_input(const std::string& path, const std::string& field, const ImageLoadOptions& options = {},
                 ImageLoadReport* loaded = nullptr) {
    ImageLoadReport report;
    Image image = load_image(path, field, &report, options);
    if (report.non_finite_replaced > 0)
        warn(path + ": " + std::to_string(report.non_finite_replaced) +
             " NaN/Inf values replaced by 0");
    for (const std::string& w : report.warnings) warn(path + ": " + w);
    if (loaded) *loaded = std::move(report);
    return image;
}

struct ConvertOptions {
    std::string input, output;
    float exposure = 0;
    bool force = false;
    ImageLoadOptions read;
    OutputFormat format;
};

int run_convert(const ConvertOptions& o) {
    check_output_path(o.output, "output");
    const DisplayTransform view = output_view(o.format, o.exposure);
    ImageLoadReport report;
    std::optional<Image> image;
    int width = 0, height = 0;
    // The size from the header where the format says it there; decoded first where not.
    if (!read_image_size(o.input, width, height)) {
        image = load_input(o.input, "input", o.read, &report);
        width = image->width(), height = image->height();
    }
    ReadSet inputs;
    inputs.add(o.input, "the input image itself");
    check_outputs({{o.output, "output", image_output_bytes(o.output, o.format, width, height)}}, inputs, o.force);
    if (!image) image = load_input(o.input, "input", o.read, &report);
    // The plate's camera and exposure data travel with what is made of it.
    write_image(o.output, std::move(*image), view, write_options(o.format, report.metadata));
    return 0;
}

struct CompareOptions {
    std::string a, b, layer, layer_a, changed, only;
};

int run_compare(const CompareOptions& o) {
    auto load = [&](const std::string& path, const char* field, const std::string& layer) {
        return layer.empty() ? load_input(path, field) : load_exr_layer(path, layer);
    };
    const Image a = load(o.a, "first image", o.layer_a.empty() ? o.layer : o.layer_a),
                b = load(o.b, "second image", o.layer);
    if (a.width() != b.width() || a.height() != b.height())
        throw InputError(o.b, "second image",
                         "size " + std::to_string(b.width()) + "x" + std::to_string(b.height()) +
                             " differs from " + o.a + "'s " + std::to_string(a.width()) + "x" +
                             std::to_string(a.height()));
    // The pixels the objects change in b (the truth), and the ceiling values are clamped to, as
    // the benchmarks count them (a mirror showing the sun would otherwise decide the figure).
    std::vector<bool> mask;
    double ceiling = INFINITY;
    if (!o.changed.empty()) {
        const Image photo = load_input(o.changed, "--changed");
        if (photo.width() != b.width() || photo.height() != b.height())
            throw InputError(o.changed, "--changed", "differs in size from " + o.b);
        Image alpha;
        try {
            alpha = load_exr_layer(o.b, "alpha");
        } catch (const std::exception&) {  // no alpha layer: the luminance change alone decides
        }
        if (!o.only.empty() && alpha.size() != b.size())
            throw InputError(o.b, "--only", "needs the truth's alpha layer (render it with --layers)");
        mask = changed_pixels(photo, b, alpha.size() == b.size() ? alpha : Image());
        if (!o.only.empty())  // the objects' own pixels, or the real surfaces around them
            for (size_t i = 0; i < mask.size(); ++i) mask[i] = mask[i] && (alpha[i].x > 0) == (o.only == "objects");
        ceiling = kErrorCeilingFactor * luminance_quantile(photo, 0.999);
    }
    double sum_sq = 0, max_diff = 0;
    size_t differing = 0, compared = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!mask.empty() && !mask[i]) continue;
        ++compared;
        bool differs = false;
        for (int c = 0; c < 3; ++c) {
            double d = std::abs(std::min(double(a[i][c]), ceiling) - std::min(double(b[i][c]), ceiling));
            sum_sq += d * d;
            max_diff = std::max(max_diff, d);
            differs |= d > 0;
        }
        differing += differs;
    }
    const double rmse = compared ? std::sqrt(sum_sq / (3.0 * double(compared))) : 0.0;
    std::printf("rmse %.9g  max_diff %.9g  differing_pixels %zu/%zu", rmse, max_diff, differing,
                compared);
    if (!mask.empty()) std::printf("  ceiling %.6g", ceiling);
    std::printf("\n");
    return 0;
}

}  // namespace

Command add_convert_command(CLI::App& app) {
    auto o = std::make_shared<ConvertOptions>();
    CLI::App* sub = app.add_subcommand("convert", "Convert an image: EXR/HDR to PNG/JPEG/TIFF through a view, or between formats");
    sub->add_option("input", o->input, "Input image (EXR, HDR, TIFF, PNG, JPEG, ...)")->required();
    sub->add_option("output", o->output, "Output .png, .jpg, .jpeg, .tif, .tiff or .exr")->required();
    sub->add_option("--exposure", o->exposure, "Exposure in stops")->check(kFinite);
    sub->add_option("--layer", o->read.layer, "Layer of a multilayer input (e.g. ViewLayer.Combined, dL)");
    sub->add_option("--colorspace", o->read.colorspace,
                    "How the input's values are read: auto (default), srgb, linear, or an OpenColorIO colour space");
    add_output_format_options(sub, o->format);
    add_force_flag(sub, o->force);
    return {sub, [o] { return run_convert(*o); }, [o] { check_output_path(o->output, "output"); }};
}

Command add_compare_command(CLI::App& app) {
    auto o = std::make_shared<CompareOptions>();
    CLI::App* sub =
        app.add_subcommand("compare", "Print RMSE and maximum difference of two images");
    sub->add_option("a", o->a, "First image")->required();
    sub->add_option("b", o->b, "Second image")->required();
    sub->add_option("--layer", o->layer, "Compare this EXR layer of both (e.g. dL, alpha, shadow)");
    sub->add_option("--layer-a", o->layer_a,
                    "This EXR layer of the first image instead (e.g. denoised against a truth's main)");
    sub->add_option("--changed", o->changed,
                    "Only the pixels the objects change in the second image (the truth): its "
                    "luminance differs from this photo's by over 1%, or its alpha layer is above 0; "
                    "values clamped at 8x the photo's 99.9% luminance quantile, as in `bench`");
    sub->add_option("--only", o->only,
                    "With --changed: only the pixels an object covers in the truth (objects) or "
                    "the others (real)")
        ->check(CLI::IsMember({"objects", "real"}));
    return {sub, [o] { return run_compare(*o); }};
}

}  // namespace dp::cli
