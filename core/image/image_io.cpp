// Format dispatch, OpenCV-decoded formats (PNG, JPEG, TIFF, BMP, Radiance HDR) and sRGB coding.
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

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

namespace {

using image_io_detail::throw_unreadable;

std::string lower_extension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

bool is_known_opencv_extension(const std::string& ext) {
    static const char* const known[] = {".png", ".jpg", ".jpeg", ".tif", ".tiff",
                                        ".bmp", ".hdr", ".pic"};
    return std::any_of(std::begin(known), std::end(known),
                       [&](const char* k) { return ext == k; });
}

// Decoding table for every code value of an integer depth; 16-bit files make per-pixel pow costly.
std::vector<float> srgb_decode_table(int max_code) {
    std::vector<float> table(size_t(max_code) + 1);
    for (int i = 0; i <= max_code; ++i) table[i] = srgb_to_linear(float(i) / float(max_code));
    return table;
}

template <typename Code>
Image decode_srgb(const cv::Mat& bgr, const std::vector<float>& table, size_t& clipped) {
    const Code max_code = Code(table.size() - 1);
    Image image(bgr.cols, bgr.rows);
    for (int y = 0; y < bgr.rows; ++y) {
        const Code* row = bgr.ptr<Code>(y);
        for (int x = 0; x < bgr.cols; ++x) {
            const Code b = row[3 * x], g = row[3 * x + 1], r = row[3 * x + 2];
            image.at(x, y) = vec3(table[r], table[g], table[b]);
            if (r == max_code || g == max_code || b == max_code) ++clipped;
        }
    }
    return image;
}

Image load_with_opencv(const std::string& path, const std::string& field,
                       ImageLoadReport& report) {
    cv::Mat bgr;
    try {
        // ANYDEPTH keeps 16-bit and float data; COLOR expands grey and drops alpha. Without
        // IMREAD_IGNORE_ORIENTATION a JPEG's EXIF orientation is applied (the TIFF decoder
        // applies its own always): the picture comes upright, and read_image_size agrees.
        bgr = cv::imread(path, cv::IMREAD_ANYDEPTH | cv::IMREAD_COLOR);
    } catch (const std::bad_alloc&) {
        throw;  // out of memory is said as such, not as a corrupt file
    } catch (const cv::Exception& e) {
        if (e.code == cv::Error::StsNoMem) throw OutOfMemory("the pixels of '" + shorten_path(path) + "'");
        throw_unreadable(path, field, e.err);
    } catch (const std::exception& e) {
        throw_unreadable(path, field, e.what());
    }
    if (bgr.empty()) {
        const std::string ext = lower_extension(path);
        if (is_known_opencv_extension(ext))
            throw_unreadable(path, field, "the " + ext.substr(1) + " decoder rejected the file");
        throw_unreadable(path, field,
                         "unrecognised extension '" + ext + "' and no decoder accepts the content");
    }
    if (bgr.channels() != 3)
        throw_unreadable(path, field, std::to_string(bgr.channels()) + " channels after decoding");

    switch (bgr.depth()) {
        case CV_8U: {
            static const std::vector<float> table = srgb_decode_table(255);
            return decode_srgb<uint8_t>(bgr, table, report.clipped);
        }
        case CV_16U: {
            static const std::vector<float> table = srgb_decode_table(65535);
            return decode_srgb<uint16_t>(bgr, table, report.clipped);
        }
        case CV_32F:
        case CV_64F: {
            // Float data (Radiance HDR, float TIFF) is linear by convention.
            report.linear_source = true;
            cv::Mat f;
            bgr.convertTo(f, CV_32F);
            Image image(f.cols, f.rows);
            for (int y = 0; y < f.rows; ++y) {
                const float* row = f.ptr<float>(y);
                for (int x = 0; x < f.cols; ++x)
                    image.at(x, y) = vec3(row[3 * x + 2], row[3 * x + 1], row[3 * x]);
            }
            return image;
        }
        default:
            throw_unreadable(path, field,
                             "unsupported pixel depth (OpenCV depth " +
                                 std::to_string(bgr.depth()) + ")");
    }
}

}  // namespace

Image load_image(const std::string& path, const std::string& field, ImageLoadReport* report) {
    ImageLoadReport local;
    ImageLoadReport& out = report ? *report : local;
    out = ImageLoadReport{};

    // The magic number catches EXRs whatever their extension; OpenCV sniffs the rest itself.
    const bool exr_magic = image_io_detail::check_image_file(path, field);
    int64_t width = 0, height = 0;
    bool known_format = false;
    if (image_io_detail::header_size(path, width, height, &known_format)) {
        check_image_size(path, field, width, height);
    } else if (known_format) {
        // A decoder handed a header it cannot size would guess, and may allocate gigabytes.
        throw InputError(path, field, "corrupt image: its header gives no valid size");
    }
    Image image;
    if (exr_magic || lower_extension(path) == ".exr") {
        image = image_io_detail::load_exr_main(path, field);
        out.linear_source = true;
    } else {
        image = load_with_opencv(path, field, out);
    }
    if (image.empty()) throw InputError(path, field, "image has zero size");
    out.non_finite_replaced = replace_non_finite(image);
    return image;
}

void save_ldr(const std::string& path, const Image& image, float exposure) {
    const std::string ext = lower_extension(path);
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg")
        throw std::invalid_argument("save_ldr '" + shorten_path(path) + "': extension must be .png, .jpg or "
                                    ".jpeg");
    if (image.empty()) throw std::invalid_argument("save_ldr '" + shorten_path(path) + "': empty image");
    image_io_detail::check_output_folder(path);

    const float scale = std::exp2(exposure);
    cv::Mat bgr(image.height(), image.width(), CV_8UC3);
    for (int y = 0; y < image.height(); ++y) {
        uint8_t* row = bgr.ptr<uint8_t>(y);
        for (int x = 0; x < image.width(); ++x) {
            const vec3 c = image.at(x, y) * scale;
            for (int k = 0; k < 3; ++k) {
                float v = c[k];
                v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
                row[3 * x + (2 - k)] = uint8_t(std::lround(linear_to_srgb(v) * 255.0f));
            }
        }
    }
    std::vector<int> params;
    if (ext != ".png") params = {cv::IMWRITE_JPEG_QUALITY, 95};
    write_atomically(path, [&](const std::string& temp) {
        bool ok = false;
        std::string detail = "the encoder failed";
        try {
            ok = cv::imwrite(temp, bgr, params);
        } catch (const std::exception& e) {
            detail = e.what();
        }
        if (!ok) throw std::runtime_error("cannot write image '" + shorten_path(path) + "': " + detail);
    });
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
