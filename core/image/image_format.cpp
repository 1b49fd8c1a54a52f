// The image formats the reader accepts, named by the file's extension and confirmed by its first
// bytes. OpenImageIO alone picks a reader by trying each of its plugins on the content when the
// extension's reader declines the file: a large zero-filled "photo.png" then ends in its DICOM
// reader for minutes. Here the extension decides, the magic bytes must agree, and only that
// one reader is ever asked.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "base/input_file.h"
#include "base/text.h"
#include "image/image_io.h"
#include "image/image_io_internal.h"

namespace dp {

namespace image_io_detail {

namespace {

bool starts_with(const unsigned char* bytes, size_t n, const char* magic, size_t m) {
    return n >= m && std::memcmp(bytes, magic, m) == 0;
}

bool exr_magic(const unsigned char* b, size_t n) { return starts_with(b, n, "\x76\x2f\x31\x01", 4); }
bool png_magic(const unsigned char* b, size_t n) { return starts_with(b, n, "\x89PNG\r\n\x1a\n", 8); }
bool jpeg_magic(const unsigned char* b, size_t n) { return starts_with(b, n, "\xff\xd8\xff", 3); }
bool hdr_magic(const unsigned char* b, size_t n) { return starts_with(b, n, "#?", 2); }
bool bmp_magic(const unsigned char* b, size_t n) { return starts_with(b, n, "BM", 2); }
/// Classic TIFF (42) and BigTIFF (43), either byte order.
bool tiff_magic(const unsigned char* b, size_t n) {
    return starts_with(b, n, "II*\0", 4) || starts_with(b, n, "MM\0*", 4) || starts_with(b, n, "II+\0", 4) ||
           starts_with(b, n, "MM\0+", 4);
}

// The documented formats (docs/project-format.md, "Image files"); the first extension is the
// one a misnamed file is told to take.
const ImageFormat kFormats[] = {
    {"OpenEXR", "an OpenEXR", "openexr", {".exr"}, "76 2f 31 01", exr_magic},
    {"Radiance HDR", "a Radiance HDR", "hdr", {".hdr"}, "\"#?\"", hdr_magic},
    {"PNG", "a PNG", "png", {".png"}, "89 50 4e 47 0d 0a 1a 0a", png_magic},
    {"JPEG", "a JPEG", "jpeg", {".jpg", ".jpeg"}, "ff d8 ff", jpeg_magic},
    {"TIFF", "a TIFF", "tiff", {".tif", ".tiff"}, "\"II*\" or \"MM*\"", tiff_magic},
    {"BMP", "a BMP", "bmp", {".bmp"}, "\"BM\"", bmp_magic},
};


std::string hex_bytes(const unsigned char* bytes, size_t n) {
    std::string out;
    char buf[4];
    for (size_t i = 0; i < n; ++i) {
        std::snprintf(buf, sizeof buf, "%02x", bytes[i]);
        out += (i ? " " : "") + std::string(buf);
    }
    return out;
}

std::string extension_list() {
    std::string out;
    for (const ImageFormat& f : kFormats)
        for (const char* e : f.extensions)
            if (e) out += (out.empty() ? "" : ", ") + std::string(e);
    return out;
}

}  // namespace

const ImageFormat* format_by_extension(const std::string& path) {
    const std::string ext = lower_extension(path);
    for (const ImageFormat& f : kFormats)
        for (const char* e : f.extensions)
            if (e && ext == e) return &f;
    return nullptr;
}

const ImageFormat* format_by_content(const unsigned char* bytes, size_t n) {
    for (const ImageFormat& f : kFormats)
        if (f.matches(bytes, n)) return &f;
    return nullptr;
}

const ImageFormat& check_image_format(const std::string& path, const std::string& field) {
    if (path.empty()) throw InputError(path, field, "no image file given");
    const uint64_t bytes = check_input_file(path, field, "an image", kMaxImageFileBytes);
    if (bytes == 0) throw InputError(path, field, "image has zero size (the file is empty)");
    const ImageFormat* format = format_by_extension(path);
    if (!format)
        throw_unreadable(path, field, "unrecognised extension '" + lower_extension(path) +
                                          "': images are read as " + extension_list());

    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, field, std::string("cannot open file: ") + std::strerror(errno));
    unsigned char head[8] = {};
    in.read(reinterpret_cast<char*>(head), sizeof head);
    const size_t n = size_t(in.gcount());
    if (format->matches(head, n)) return *format;
    std::string why = "not " + std::string(format->a_name) + " file (its first bytes are " + hex_bytes(head, n);
    if (const ImageFormat* actual = format_by_content(head, n))
        why += ", those of " + std::string(actual->a_name) + " file: name it " + actual->extensions[0] + ")";
    else
        why += "; " + std::string(format->a_name) + " file starts with " + format->magic_text + ")";
    throw InputError(path, field, why);
}

}  // namespace image_io_detail

std::string image_extension_for_content(const void* bytes, size_t size) {
    const auto* format = image_io_detail::format_by_content(static_cast<const unsigned char*>(bytes), size);
    return format ? std::string(format->extensions[0]).substr(1) : std::string();
}

void check_extension_for_content(const std::string& path, const std::string& field, const void* bytes, size_t size) {
    const auto* actual = image_io_detail::format_by_content(static_cast<const unsigned char*>(bytes), size);
    if (!actual) return;
    const auto* named = image_io_detail::format_by_extension(path);
    if (named == actual) return;
    const std::filesystem::path p(path);
    const std::string suggestion = (p.parent_path() / (p.stem().string() + actual->extensions[0])).string();
    throw InputError(path, field,
                     "the image is " + std::string(actual->a_name) + " file and is written as it is: name it " +
                         suggestion);
}

}  // namespace dp
