// An image's size from its header, without decoding the pixels: the studio asks for the photo's
// size on the UI thread, where a 12 MP decode would stall the window, and load_image refuses an
// image too large to decode before any pixel is allocated (a tiny file may declare any size).
// Decoders allocate their buffers from the declared size before they find the data missing, so
// a header declaring more pixels than the file can hold is refused here too.
#include <ImfHeader.h>
#include <ImfStdIO.h>
#include <ImfXdr.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "base/input_file.h"
#include "base/memory.h"
#include "base/text.h"
#include "image/image_io.h"
#include "image/image_io_internal.h"
#include "base/byte_order.h"

namespace dp {

namespace {

using image_io_detail::DeclaredSize;


/// A byte count from a double, saturated: declared sizes may be absurd.
uint64_t to_bytes(double bytes) { return bytes >= 1.8e19 ? UINT64_MAX : uint64_t(std::ceil(bytes)); }

bool png_size(std::ifstream& f, DeclaredSize& s) {
    unsigned char b[26];
    if (!f.read(reinterpret_cast<char*>(b), 26)) return false;
    if (b[0] != 0x89 || b[1] != 'P' || b[2] != 'N' || b[3] != 'G') return false;
    s.width = be32(b + 16);
    s.height = be32(b + 20);
    // The rows (a filter byte each) deflated: deflate packs at most 1032 bytes into one (a
    // 258-byte match in two bits).
    const int depth = b[24], colour = b[25];
    const int channels = colour == 0 ? 1 : colour == 2 ? 3 : colour == 3 ? 1 : colour == 4 ? 2 : colour == 6 ? 4 : 0;
    if (channels > 0 && depth > 0) {
        const double row = 1.0 + std::ceil(double(s.width) * depth * channels / 8.0);
        s.min_file_bytes = to_bytes(double(s.height) * row / 1032.0);
        s.min_bytes_why = "deflate packs at most 1032 bytes of rows into one";
    }
    return s.width > 0 && s.height > 0;
}

/// The tags of a TIFF structure's first IFD that size the picture.
struct TiffTags {
    int64_t width = 0, height = 0;
    int orientation = 1;  ///< 1 to 8
    int64_t compression = 1, samples = 1;  ///< 1: none; samples per pixel
};

/// Reads the first IFD of the TIFF structure at `base` in `f` (classic TIFF or BigTIFF, either
/// byte order), reading no further than `limit` bytes from `base`; false where there is none.
bool read_tiff_ifd(std::istream& f, std::streamoff base, std::streamoff limit, TiffTags& tags) {
    unsigned char h[16];
    f.clear();
    f.seekg(base);
    if (!f.read(reinterpret_cast<char*>(h), 8)) return false;
    const bool little = h[0] == 'I' && h[1] == 'I';
    if (!little && !(h[0] == 'M' && h[1] == 'M')) return false;
    auto u16 = [&](const unsigned char* b) { return little ? le16(b) : be16(b); };
    auto u32 = [&](const unsigned char* b) { return little ? le32(b) : be32(b); };
    auto u64 = [&](const unsigned char* b) {
        return little ? uint64_t(le32(b + 4)) << 32 | le32(b) : uint64_t(be32(b)) << 32 | be32(b + 4);
    };
    const uint16_t version = u16(h + 2);
    const bool big = version == 43;
    if (version != 42 && !big) return false;
    if (big && (u16(h + 4) != 8 || !f.read(reinterpret_cast<char*>(h + 8), 8))) return false;
    const uint64_t ifd = big ? u64(h + 8) : u32(h + 4);
    const uint64_t count_size = big ? 8 : 2, entry_size = big ? 20 : 12;
    if (ifd < 8 || limit < 0 || ifd + count_size > uint64_t(limit)) return false;
    f.seekg(base + std::streamoff(ifd));
    unsigned char n[8];
    if (!f.read(reinterpret_cast<char*>(n), std::streamsize(count_size))) return false;
    const uint64_t fits = (uint64_t(limit) - ifd - count_size) / entry_size;
    const uint64_t entries = std::min<uint64_t>({big ? u64(n) : u16(n), fits, 4096});
    for (uint64_t i = 0; i < entries; ++i) {
        unsigned char e[20];
        if (!f.read(reinterpret_cast<char*>(e), std::streamsize(entry_size))) return false;
        const uint16_t tag = u16(e), type = u16(e + 2);
        const uint64_t count = big ? u64(e + 4) : u32(e + 4);
        const unsigned char* value = e + (big ? 12 : 8);
        // SHORT (3) values sit in the value field's first bytes; LONG (4) and LONG8 (16) fill it.
        const uint64_t v = type == 3 ? u16(value) : type == 4 ? u32(value) : big && type == 16 ? u64(value) : 0;
        if (count < 1 || v > uint64_t(std::numeric_limits<int64_t>::max())) continue;
        if (tag == 256) tags.width = int64_t(v);
        if (tag == 257) tags.height = int64_t(v);
        if (tag == 0x0112 && v >= 1 && v <= 8) tags.orientation = int(v);
        if (tag == 259) tags.compression = int64_t(v);
        if (tag == 277) tags.samples = int64_t(v);
    }
    return true;
}

/// A TIFF file: the size of its first image as it loads (orientation 5 to 8 turns it). Its
/// codings (CCITT fax above all) pack flat pictures too well for a bound on the file's size;
/// an uncompressed one holds at least a bit per sample.
bool tiff_size(std::ifstream& f, DeclaredSize& s) {
    f.seekg(0, std::ios::end);
    const std::streamoff size = f.tellg();
    TiffTags tags;
    if (!read_tiff_ifd(f, 0, size, tags)) return false;
    s.width = tags.width;
    s.height = tags.height;
    if (tags.compression == 1) {
        const double samples = double(s.width) * double(s.height) * double(std::max<int64_t>(tags.samples, 1));
        s.min_file_bytes = to_bytes(samples / 8.0);
        s.min_bytes_why = "uncompressed, it holds at least a bit per sample";
    }
    if (tags.orientation >= 5) std::swap(s.width, s.height);
    return s.width > 0 && s.height > 0;
}

/// A JPEG frame header (SOF, after its length): the size, and the least a complete file of it
/// takes. Huffman coding spends at least one bit on every 8 x 8 block of every component;
/// arithmetic coding (SOF9 to SOF15) may spend almost nothing on a flat picture.
bool jpeg_frame(std::ifstream& f, unsigned char marker, DeclaredSize& s) {
    unsigned char b[6];
    if (!f.read(reinterpret_cast<char*>(b), 6)) return false;
    s.height = be16(b + 1);
    s.width = be16(b + 3);
    const int components = b[5];
    unsigned char c[3 * 255];
    if (components < 1 || !f.read(reinterpret_cast<char*>(c), 3 * components)) return s.width > 0 && s.height > 0;
    int hmax = 1, vmax = 1;
    for (int i = 0; i < components; ++i) hmax = std::max(hmax, c[3 * i + 1] >> 4), vmax = std::max(vmax, c[3 * i + 1] & 15);
    double blocks = 0;
    for (int i = 0; i < components; ++i) {
        const int hi = std::max(1, c[3 * i + 1] >> 4), vi = std::max(1, c[3 * i + 1] & 15);
        blocks += std::ceil(std::ceil(double(s.width) * hi / hmax) / 8) * std::ceil(std::ceil(double(s.height) * vi / vmax) / 8);
    }
    if (marker < 0xC8) {
        s.min_file_bytes = to_bytes(blocks / 8);
        s.min_bytes_why = "Huffman coding spends one bit on each 8 x 8 block at the least";
    }
    return s.width > 0 && s.height > 0;
}

/// The size as the decoder shows the picture: a JPEG's EXIF orientation 5 to 8 turns it a
/// quarter (OpenCV applies the tag as it decodes, as viewers do), so width and height swap.
bool jpeg_size(std::ifstream& f, DeclaredSize& s) {
    unsigned char b[2];
    if (!f.read(reinterpret_cast<char*>(b), 2) || b[0] != 0xFF || b[1] != 0xD8) return false;
    int orientation = 1;
    bool exif_seen = false;
    for (int guard = 0; guard < 4096; ++guard) {
        unsigned char m[4];
        if (!f.read(reinterpret_cast<char*>(m), 2) || m[0] != 0xFF) return false;
        while (m[1] == 0xFF)
            if (!f.read(reinterpret_cast<char*>(m + 1), 1)) return false;
        const unsigned char marker = m[1];
        if (marker == 0xD8 || (marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) continue;
        if (!f.read(reinterpret_cast<char*>(m + 2), 2)) return false;
        const int length = be16(m + 2);
        // Start-of-frame markers (all but DHT C4, JPG C8 and DAC CC) carry the size.
        if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC) {
            const bool ok = jpeg_frame(f, marker, s);
            if (orientation >= 5) std::swap(s.width, s.height);
            return ok;
        }
        if (length < 2) return false;
        const std::streamoff next = std::streamoff(f.tellg()) + length - 2;
        // The first APP1 "Exif" segment holds the tags, as the decoder reads them.
        unsigned char id[6];
        TiffTags tags;
        if (marker == 0xE1 && !exif_seen && length >= 16 && f.read(reinterpret_cast<char*>(id), 6) &&
            std::memcmp(id, "Exif\0\0", 6) == 0) {
            exif_seen = true;
            if (read_tiff_ifd(f, next - (length - 8), length - 8, tags)) orientation = tags.orientation;
        }
        f.clear();
        f.seekg(next);
    }
    return false;
}

/// Radiance HDR: text lines up to an empty one, then the resolution line, e.g. "-Y 512 +X 1024"
/// (the first axis runs over rows; either may be X).
bool hdr_size(std::ifstream& f, DeclaredSize& s) {
    std::string line;
    if (!std::getline(f, line) || line.rfind("#?", 0) != 0) return false;
    for (int lines = 0; std::getline(f, line) && !(line.empty() || line == "\r");)
        if (++lines > 1024) return false;
    if (!std::getline(f, line)) return false;
    std::istringstream in(line);
    std::string axis1, axis2;
    int64_t n1 = 0, n2 = 0;
    if (!(in >> axis1 >> n1 >> axis2 >> n2) || axis1.size() != 2 || axis2.size() != 2) return false;
    const bool rows_are_y = std::toupper(axis1[1]) == 'Y';
    s.width = rows_are_y ? n2 : n1;
    s.height = rows_are_y ? n1 : n2;
    // n1 scanlines of n2 pixels: run-length coded (a 4-byte start, then runs of at most 127
    // pixels in two bytes, per channel) where n2 allows it, 4 bytes a pixel otherwise.
    const double row = n2 >= 8 && n2 <= 32767 ? 4.0 + 8.0 * std::ceil(double(n2) / 127) : 4.0 * double(n2);
    s.min_file_bytes = to_bytes(double(n1) * row);
    s.min_bytes_why = "run-length coding packs at most 127 pixels into two bytes a channel";
    return s.width > 0 && s.height > 0;
}

bool bmp_size(std::ifstream& f, DeclaredSize& s) {
    unsigned char b[34] = {};
    f.read(reinterpret_cast<char*>(b), 34);
    if (f.gcount() < 26 || b[0] != 'B' || b[1] != 'M') return false;
    const bool core = le32(b + 14) == 12;  // OS/2's header: 16-bit sizes, no compression
    s.width = core ? le16(b + 18) : int32_t(le32(b + 18));
    s.height = core ? le16(b + 20) : int32_t(le32(b + 22));
    s.height = s.height < 0 ? -s.height : s.height;  // negative: rows stored top-down
    const int bits = core ? le16(b + 24) : le16(b + 28);
    const uint32_t compression = core || f.gcount() < 34 ? 0 : le32(b + 30);
    // Uncompressed rows (BI_RGB, BI_BITFIELDS): each padded to 4 bytes but the last. Run-length
    // coded rows may end the picture at once, so they give no bound.
    if ((compression == 0 || compression == 3 || compression == 6) && bits > 0 && s.width > 0 && s.height > 0) {
        const double row = std::ceil(double(s.width) * bits / 32) * 4;
        s.min_file_bytes = to_bytes(double(le32(b + 10)) + row * double(s.height - 1) +
                                    std::ceil(double(s.width) * bits / 8));
        s.min_bytes_why = "its rows are stored uncompressed";
    }
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
    f.clear();
    f.seekg(0);
    const ImageFormat* format = format_by_content(magic, n);
    if (known_format) *known_format = format != nullptr;
    if (!format) return false;
    size.format = format->name;
    const std::string name = format->oiio;
    if (name == "openexr") return exr_size(path, size);
    bool (*reader)(std::ifstream&, DeclaredSize&) = name == "png"    ? png_size
                                                    : name == "jpeg" ? jpeg_size
                                                    : name == "hdr"  ? hdr_size
                                                    : name == "bmp"  ? bmp_size
                                                    : name == "tiff" ? tiff_size
                                                                     : nullptr;
    return reader && reader(f, size);
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
