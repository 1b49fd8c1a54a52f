// `diffphoton convert` (HDR to 8-bit) and `diffphoton compare` (difference figures).
#include <filesystem>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "base/error.h"
#include "commands.h"
#include "common.h"
#include "image/image_io.h"

namespace dp::cli {

namespace {

Image load_input(const std::string& path, const std::string& field) {
    ImageLoadReport report;
    Image image = load_image(path, field, &report);
    if (report.non_finite_replaced > 0)
        warn(path + ": " + std::to_string(report.non_finite_replaced) +
             " NaN/Inf values replaced by 0");
    return image;
}

struct ConvertOptions {
    std::string input, output;
    float exposure = 0;
};

int run_convert(const ConvertOptions& o) {
    if (check_output_path(o.output, "output") != ImageKind::Ldr)
        throw InputError(o.output, "output", "convert writes PNG or JPEG (.png, .jpg, .jpeg)");
    std::error_code ec;
    if (std::filesystem::equivalent(o.input, o.output, ec))
        throw InputError(o.output, "output", "is the input image itself: choose another output");
    write_image(o.output, load_input(o.input, "input"), o.exposure);
    return 0;
}

struct CompareOptions {
    std::string a, b, layer;
};

int run_compare(const CompareOptions& o) {
    auto load = [&](const std::string& path, const char* field) {
        return o.layer.empty() ? load_input(path, field) : load_exr_layer(path, o.layer);
    };
    const Image a = load(o.a, "first image"), b = load(o.b, "second image");
    if (a.width() != b.width() || a.height() != b.height())
        throw InputError(o.b, "second image",
                         "size " + std::to_string(b.width()) + "x" + std::to_string(b.height()) +
                             " differs from " + o.a + "'s " + std::to_string(a.width()) + "x" +
                             std::to_string(a.height()));
    double sum_sq = 0, max_diff = 0;
    size_t differing = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        bool differs = false;
        for (int c = 0; c < 3; ++c) {
            double d = std::abs(double(a[i][c]) - double(b[i][c]));
            sum_sq += d * d;
            max_diff = std::max(max_diff, d);
            differs |= d > 0;
        }
        differing += differs;
    }
    const double rmse = a.size() ? std::sqrt(sum_sq / (3.0 * double(a.size()))) : 0.0;
    std::printf("rmse %.9g  max_diff %.9g  differing_pixels %zu/%zu\n", rmse, max_diff, differing,
                a.size());
    return 0;
}

}  // namespace

Command add_convert_command(CLI::App& app) {
    auto o = std::make_shared<ConvertOptions>();
    CLI::App* sub = app.add_subcommand("convert", "Convert an HDR image (EXR) to PNG/JPEG");
    sub->add_option("input", o->input, "Input image (EXR, HDR or LDR)")->required();
    sub->add_option("output", o->output, "Output .png, .jpg or .jpeg")->required();
    sub->add_option("--exposure", o->exposure, "Exposure in stops")->check(kFinite);
    return {sub, [o] { return run_convert(*o); }};
}

Command add_compare_command(CLI::App& app) {
    auto o = std::make_shared<CompareOptions>();
    CLI::App* sub =
        app.add_subcommand("compare", "Print RMSE and maximum difference of two images");
    sub->add_option("a", o->a, "First image")->required();
    sub->add_option("b", o->b, "Second image")->required();
    sub->add_option("--layer", o->layer, "Compare this EXR layer of both (e.g. dL, alpha, shadow)");
    return {sub, [o] { return run_compare(*o); }};
}

}  // namespace dp::cli
