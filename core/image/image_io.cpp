// File checks before decoding, the decoder dispatch and sRGB coding.

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/image_io.h"
#include "base/text.h"
#include "base/input_file.h"
#include "base/atomic_file.h"
#include "image/image_io_internal.h"

namespace dp {

namespace fs = std::filesystem;

namespace image_io_detail {

bool check_image_file(const std::string& path, const std::string& field) {
    if (path.empty()) throw InputError(path, field, "no image file given");
    const uint64_t bytes = check_input_file(path, field, "an image");
    if (bytes == 0) throw InputError(path, field, "image has zero size (the file is empty)");

    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw InputError(path, field, std::string("cannot open file: ") + std::strerror(errno));
    unsigned char magic[4] = {};
    in.read(reinterpret_cast<char*>(magic), sizeof(magic));
    return in.gcount() == 4 && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 &&
           magic[3] == 0x01;
}

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

    // OpenImageIO sniffs the format from the content; the header's size is checked first.
    image_io_detail::check_image_file(path, field);
    int64_t width = 0, height = 0;
    bool known_format = false;
    if (image_io_detail::header_size(path, width, height, &known_format)) {
        check_image_size(path, field, width, height);
    } else if (known_format) {
        // A decoder handed a header it cannot size would guess, and may allocate gigabytes.
        throw InputError(path, field, "corrupt image: its header gives no valid size");
    }
    Image image;
    try {
        image = image_io_detail::load_with_oiio(path, field, options, out);
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
