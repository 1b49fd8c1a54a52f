// File checks before decoding, the decoder dispatch and sRGB coding.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/image_io.h"
#include "base/text.h"
#include "base/atomic_file.h"
#include "image/image_io_internal.h"

namespace dp {

namespace fs = std::filesystem;

namespace image_io_detail {

void check_output_folder(const std::string& path) {
    const fs::path folder = fs::path(path).parent_path();
    std::error_code ec;
    if (!folder.empty() && !fs::is_directory(folder, ec))
        throw std::runtime_error("cannot write '" + shorten_path(path) + "': folder '" + shorten_path(folder.string()) +
                                 "' does not exist");
}

}  // namespace image_io_detail

Image load_image(const std::string& path, const std::string& field, ImageLoadReport* report,
                 const ImageLoadOptions& options) {
    ImageLoadReport local;
    ImageLoadReport& out = report ? *report : local;
    out = ImageLoadReport{};

    // The format from the name, confirmed by the magic number; the header's size before any
    // decoder sees the file.
    const image_io_detail::ImageFormat& format = image_io_detail::check_image_format(path, field);
    image_io_detail::check_declared_size(path, field);
    Image image;
    try {
        image = image_io_detail::load_with_oiio(path, field, format, options, out);
    } catch (const InputError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw;  // out of memory is said as such, not as a corrupt file
    } catch (const std::exception& e) {
        image_io_detail::throw_unreadable(path, field, e.what());
    }
    if (image.empty()) throw InputError(path, field, "image has zero size");
    out.non_finite_replaced = replace_non_finite(image);
    return image;
}

float srgb_to_linear(float v) {
    const double d = v;
    return float(d <= 0.04045 ? d / 12.92 : std::pow((d + 0.055) / 1.055, 2.4));
}

float linear_to_srgb(float v) {
    const double d = v;
    return float(d <= 0.0031308 ? d * 12.92 : 1.055 * std::pow(d, 1.0 / 2.4) - 0.055);
}

}  // namespace dp
