// An image's size from its header, without decoding the pixels: the studio asks for the photo's
// size on the UI thread, where a 12 MP decode would stall the window, and load_image refuses an
// image too large to decode before any pixel is allocated (a tiny file may declare any size).
// Decoders allocate their buffers from the declared size before they find the data missing, so
// a header declaring more pixels than the file can hold is refused here too. OpenImageIO reads
// the headers, but for EXR (OpenEXR's header reader: OpenImageIO's would read the chunk table
// too, as long as the declared height) and JPEG (Exiv2: below).
#include <OpenImageIO/imageio.h>
#include <exiv2/exiv2.hpp>
#include <ImfHeader.h>
#include <ImfStdIO.h>
#include <ImfXdr.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <utility>

#include "base/input_file.h"
#include "base/memory.h"
#include "base/text.h"
#include "image/image_io.h"
#include "image/image_io_internal.h"

namespace dp {

namespace {

using image_io_detail::DeclaredSize;

/// A byte count from a double, saturated: declared sizes may be absurd.
uint64_t to_bytes(double bytes) { return bytes >= 1.8e19 ? UINT64_MAX : uint64_t(std::ceil(bytes)); }

/// The least a complete file of `spec`'s size takes in `format`'s coding (0: no bound), from
/// what OpenImageIO read of its header. Each bound holds for the leanest variant of the coding
/// (a palette, a bit a pixel), so no complete file falls under it.
void min_file_bytes(const std::string& format, const OIIO::ImageSpec& spec, DeclaredSize& s) {
    const double w = double(spec.width), h = double(spec.height);
    if (format == "png") {
        // Rows of at least a bit a pixel (and a filter byte each), deflated: deflate packs at
        // most 1032 bytes into one (a 258-byte match in two bits).
        s.min_file_bytes = to_bytes(h * (1.0 + std::ceil(w / 8.0)) / 1032.0);
        s.min_bytes_why = "deflate packs at most 1032 bytes of rows into one";
    } else if (format == "hdr") {
        // Scanlines run-length coded (a 4-byte start, then runs of at most 127 pixels in two
        // bytes, per channel) where their width allows it, 4 bytes a pixel otherwise.
        const double row = w >= 8 && w <= 32767 ? 4.0 + 8.0 * std::ceil(w / 127) : 4.0 * w;
        s.min_file_bytes = to_bytes(h * row);
        s.min_bytes_why = "run-length coding packs at most 127 pixels into two bytes a channel";
    } else if (format == "bmp" && spec.get_string_attribute("compression", "none") == "none") {
        // Uncompressed rows, each padded to 4 bytes but the last, after the smallest headers;
        // run-length coded rows may end the picture at once, so they give no bound.
        const double bits = spec.get_int_attribute("bmp:bitsperpixel", 8 * spec.nchannels);
        s.min_file_bytes = to_bytes(26.0 + std::ceil(w * bits / 32) * 4 * (h - 1) + std::ceil(w * bits / 8));
        s.min_bytes_why = "its rows are stored uncompressed";
    } else if (format == "tiff" && spec.get_string_attribute("compression") == "none") {
        // Other codings (CCITT fax above all) pack flat pictures too well for a bound. A palette
        // picture (photometric 3) is one sample a pixel, however many channels it loads as.
        const int samples = spec.get_int_attribute("tiff:PhotometricInterpretation") == 3 ? 1 : spec.nchannels;
        s.min_file_bytes = to_bytes(w * h * std::max(samples, 1) / 8.0);
        s.min_bytes_why = "uncompressed, it holds at least a bit per sample";
    }
}

/// A JPEG through Exiv2, which reads the markers up to the frame header and the EXIF tags. Not
/// OpenImageIO: its open() starts the decompressor, and for a progressive JPEG libjpeg then
/// allocates the whole picture's coefficients (740 MB for a forged 1 kB file declaring 16000 x
/// 16000) before anything here could refuse it.
bool jpeg_size(const std::string& path, DeclaredSize& s) {
    try {
        auto image = Exiv2::ImageFactory::open(path);
        if (!image.get()) return false;
        image->readMetadata();
        s.width = image->pixelWidth();
        s.height = image->pixelHeight();
        // Huffman coding spends at least a bit on each 8 x 8 block of the luma plane at least
        // (arithmetic coding, which no camera writes, could spend less on a flat picture).
        s.min_file_bytes = to_bytes(std::ceil(double(s.width) / 8) * std::ceil(double(s.height) / 8) / 8);
        s.min_bytes_why = "Huffman coding spends one bit on each 8 x 8 block at the least";
        const Exiv2::ExifData& exif = image->exifData();
        const auto it = exif.findKey(Exiv2::ExifKey("Exif.Image.Orientation"));
        if (it != exif.end() && it->count() > 0 && it->toLong() >= 5 && it->toLong() <= 8) std::swap(s.width, s.height);
    } catch (const Exiv2::AnyError&) {
        return false;
    }
    return s.width > 0 && s.height > 0;
}

/// A PNG, HDR, BMP or TIFF header through OpenImageIO, which reads it without decoding the
/// pixels: the size as the picture loads (a TIFF's orientation 5 to 8 turns it a quarter, as
/// the decoder does) and the least its file takes.
bool oiio_size(const std::string& path, const std::string& format, DeclaredSize& s) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        (void)OIIO::geterror();  // not left pending for the next caller
        return false;
    }
    const OIIO::ImageSpec& spec = in->spec();
    s.width = spec.width;
    s.height = spec.height;
    min_file_bytes(format, spec, s);
    if (format == "tiff" && spec.get_int_attribute("Orientation", 1) >= 5)
        std::swap(s.width, s.height);
    in->close();
    return s.width > 0 && s.height > 0;
}

/// The header alone: OpenEXR's InputFile would read the chunk offset table too, whose size
/// follows the declared height.
bool exr_size(const std::string& path, DeclaredSize& s) {
    try {
        Imf::StdIFStream in(path.c_str());
        int magic = 0, version = 0;
        Imf::Xdr::read<Imf::StreamIO>(in, magic);
        Imf::Xdr::read<Imf::StreamIO>(in, version);
        Imf::Header header;
        header.readFrom(in, version);
        // The image loads as its display window; a data window too large to decode is what the
        // caller's size check must see, though (OpenImageIO allocates by it).
        const Imath::Box2i dw = header.dataWindow(), display = header.displayWindow();
        s.width = int64_t(dw.max.x) - dw.min.x + 1;
        s.height = int64_t(dw.max.y) - dw.min.y + 1;
        if (s.width <= 0 || s.height <= 0) return false;
        if (uint64_t(s.width) * uint64_t(s.height) > max_decoded_image_pixels()) return true;
        s.width = int64_t(display.max.x) - display.min.x + 1;
        s.height = int64_t(display.max.y) - display.min.y + 1;
        return s.width > 0 && s.height > 0;
    } catch (const std::exception&) {
        return false;
    }
}

/// "1046 bytes" for small counts, format_bytes beyond.
std::string byte_count(uint64_t bytes) {
    return bytes < 1000000 ? std::to_string(bytes) + " bytes" : format_bytes(double(bytes));
}

}  // namespace

namespace image_io_detail {

bool header_size(const std::string& path, DeclaredSize& size, bool* known_format) {
    std::ifstream f(path, std::ios::binary);
    if (known_format) *known_format = false;
    if (!f) return false;
    unsigned char magic[8] = {};
    f.read(reinterpret_cast<char*>(magic), sizeof magic);
    const size_t n = size_t(f.gcount());
    f.close();
    const ImageFormat* format = format_by_content(magic, n);
    if (known_format) *known_format = format != nullptr;
    if (!format) return false;
    size.format = format->name;
    const std::string name = format->oiio;
    if (name == "openexr") return exr_size(path, size);
    return name == "jpeg" ? jpeg_size(path, size) : oiio_size(path, name, size);
}

void check_declared_size(const std::string& path, const std::string& field) {
    DeclaredSize size;
    bool known = false;
    // A decoder handed a header it cannot size would guess, and may allocate gigabytes.
    if (!header_size(path, size, &known)) throw InputError(path, field, "corrupt image: its header gives no valid size");
    check_image_size(path, field, size.width, size.height);
    std::error_code ec;
    const uint64_t bytes = std::filesystem::file_size(path, ec);
    if (ec || size.min_file_bytes == 0 || bytes >= size.min_file_bytes) return;
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "the header declares %lld x %lld pixels, which a file of %s cannot hold: a complete "
                  "%s of that size takes at least %s (%s); the file is truncated or forged",
                  static_cast<long long>(size.width), static_cast<long long>(size.height), byte_count(bytes).c_str(),
                  size.format,
                  byte_count(size.min_file_bytes).c_str(), size.min_bytes_why);
    throw InputError(path, field, buf);
}

}  // namespace image_io_detail

bool read_image_size(const std::string& path, int& width, int& height) {
    try {
        check_input_file(path, "", "an image", kMaxImageFileBytes);  // a FIFO would block the caller
    } catch (const InputError&) {
        return false;
    }
    DeclaredSize size;
    if (!image_io_detail::header_size(path, size) || size.width > std::numeric_limits<int>::max() ||
        size.height > std::numeric_limits<int>::max())
        return false;
    width = int(size.width);
    height = int(size.height);
    return true;
}

uint64_t max_decoded_image_pixels() {
    const uint64_t ram = usable_memory_bytes();
    const uint64_t by_memory = ram > 0 ? uint64_t(0.5 * double(ram) / kDecodeBytesPerPixel) : kMaxImagePixels;
    uint64_t limit = std::min<uint64_t>(kMaxImagePixels, by_memory);
    // A lower limit from the environment (a shared render node, the image fuzzer); never higher.
    if (const char* env = std::getenv("DP_MAX_IMAGE_PIXELS")) {
        char* end = nullptr;
        const unsigned long long v = std::strtoull(env, &end, 10);
        if (end != env && *end == '\0' && v > 0) limit = std::min<uint64_t>(limit, v);
    }
    return limit;
}

void check_image_size(const std::string& path, const std::string& field, int64_t width, int64_t height) {
    const double pixels = double(width) * double(height);
    if (pixels <= double(max_decoded_image_pixels())) return;
    char buf[320];
    std::snprintf(buf, sizeof(buf),
                  "the image is %lld x %lld pixels; decoding it would take %s of memory, more than the limit of "
                  "%llu pixels (%s: at most 2^28 pixels and half of this machine's %s): "
                  "reduce it (a probe needs no more than 8192 x 4096)",
                  static_cast<long long>(width), static_cast<long long>(height),
                  format_bytes(pixels * kDecodeBytesPerPixel).c_str(),
                  static_cast<unsigned long long>(max_decoded_image_pixels()),
                  format_bytes(double(max_decoded_image_pixels()) * kDecodeBytesPerPixel).c_str(),
                  format_bytes(double(usable_memory_bytes())).c_str());
    throw InputError(path, field, buf);
}

}  // namespace dp
