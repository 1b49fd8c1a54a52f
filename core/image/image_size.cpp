// An image's size from its header, without decoding the pixels: the studio asks for the photo's
// size on the UI thread, where a 12 MP decode would stall the window, and load_image refuses an
// image too large to decode before any pixel is allocated (a tiny file may declare any size).
#include <ImfHeader.h>
#include <ImfStdIO.h>
#include <ImfXdr.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "base/memory.h"
#include "base/text.h"
#include "image/image_io.h"
#include "image/image_io_internal.h"

namespace dp {

namespace {

uint32_t be32(const unsigned char* b) { return uint32_t(b[0]) << 24 | uint32_t(b[1]) << 16 | uint32_t(b[2]) << 8 | b[3]; }
uint16_t be16(const unsigned char* b) { return uint16_t(b[0] << 8 | b[1]); }
uint32_t le32(const unsigned char* b) {
    return uint32_t(b[3]) << 24 | uint32_t(b[2]) << 16 | uint32_t(b[1]) << 8 | b[0];
}

bool png_size(std::ifstream& f, int64_t& w, int64_t& h) {
    unsigned char b[24];
    if (!f.read(reinterpret_cast<char*>(b), 24)) return false;
    if (b[0] != 0x89 || b[1] != 'P' || b[2] != 'N' || b[3] != 'G') return false;
    w = be32(b + 16);
    h = be32(b + 20);
    return w > 0 && h > 0;
}

/// The Orientation tag (0x0112, 1 to 8) of the first IFD of the TIFF structure at `base` in
/// `f`, reading no further than `limit` bytes from `base`; 1 where it is absent or unreadable.
int tiff_orientation(std::istream& f, std::streamoff base, std::streamoff limit) {
    unsigned char h[8];
    f.clear();
    f.seekg(base);
    if (!f.read(reinterpret_cast<char*>(h), 8)) return 1;
    const bool little = h[0] == 'I' && h[1] == 'I' && h[2] == 42 && h[3] == 0;
    if (!little && !(h[0] == 'M' && h[1] == 'M' && h[2] == 0 && h[3] == 42)) return 1;
    auto u16 = [&](const unsigned char* b) { return little ? uint16_t(b[0] | b[1] << 8) : be16(b); };
    auto u32 = [&](const unsigned char* b) { return little ? le32(b) : be32(b); };
    const uint32_t ifd = u32(h + 4);
    unsigned char n[2];
    if (ifd < 8 || std::streamoff(ifd) + 2 > limit) return 1;
    f.seekg(base + std::streamoff(ifd));
    if (!f.read(reinterpret_cast<char*>(n), 2)) return 1;
    const int entries = std::min<int>(u16(n), int((limit - std::streamoff(ifd) - 2) / 12));
    for (int i = 0; i < entries; ++i) {
        unsigned char e[12];
        if (!f.read(reinterpret_cast<char*>(e), 12)) return 1;
        // A SHORT value sits in the first two bytes of the entry's value field.
        if (u16(e) == 0x0112 && u16(e + 2) == 3 && u32(e + 4) >= 1) {
            const int v = u16(e + 8);
            return v >= 1 && v <= 8 ? v : 1;
        }
    }
    return 1;
}

/// The size as the decoder shows the picture: a JPEG's EXIF orientation 5 to 8 turns it a
/// quarter (OpenCV applies the tag as it decodes, as viewers do), so width and height swap.
bool jpeg_size(std::ifstream& f, int64_t& w, int64_t& h) {
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
            unsigned char s[5];
            if (!f.read(reinterpret_cast<char*>(s), 5)) return false;
            h = be16(s + 1);
            w = be16(s + 3);
            if (orientation >= 5) std::swap(w, h);
            return w > 0 && h > 0;
        }
        if (length < 2) return false;
        const std::streamoff next = std::streamoff(f.tellg()) + length - 2;
        // The first APP1 "Exif" segment holds the tags, as the decoder reads them.
        unsigned char id[6];
        if (marker == 0xE1 && !exif_seen && length >= 16 && f.read(reinterpret_cast<char*>(id), 6) &&
            std::memcmp(id, "Exif\0\0", 6) == 0) {
            exif_seen = true;
            orientation = tiff_orientation(f, next - (length - 8), length - 8);
        }
        f.clear();
        f.seekg(next);
    }
    return false;
}

/// Radiance HDR: text lines up to an empty one, then the resolution line, e.g. "-Y 512 +X 1024"
/// (the first axis runs over rows; either may be X).
bool hdr_size(std::ifstream& f, int64_t& w, int64_t& h) {
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
    w = rows_are_y ? n2 : n1;
    h = rows_are_y ? n1 : n2;
    return w > 0 && h > 0;
}

bool bmp_size(std::ifstream& f, int64_t& w, int64_t& h) {
    unsigned char b[26];
    if (!f.read(reinterpret_cast<char*>(b), 26) || b[0] != 'B' || b[1] != 'M') return false;
    w = int32_t(le32(b + 18));
    h = int32_t(le32(b + 22));
    h = h < 0 ? -h : h;  // negative: rows stored top-down
    return w > 0 && h > 0;
}

/// The header alone: OpenEXR's InputFile would read the chunk offset table too, whose size
/// follows the declared height.
bool exr_size(const std::string& path, int64_t& w, int64_t& h) {
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
        w = int64_t(dw.max.x) - dw.min.x + 1;
        h = int64_t(dw.max.y) - dw.min.y + 1;
        if (w <= 0 || h <= 0) return false;
        if (uint64_t(w) * uint64_t(h) > max_decoded_image_pixels()) return true;
        w = int64_t(display.max.x) - display.min.x + 1;
        h = int64_t(display.max.y) - display.min.y + 1;
        return w > 0 && h > 0;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace

namespace image_io_detail {

bool header_size(const std::string& path, int64_t& width, int64_t& height, bool* known_format) {
    std::ifstream f(path, std::ios::binary);
    if (known_format) *known_format = false;
    if (!f) return false;
    unsigned char magic[4] = {0, 0, 0, 0};
    f.read(reinterpret_cast<char*>(magic), 4);
    f.clear();
    f.seekg(0);
    bool (*reader)(std::ifstream&, int64_t&, int64_t&) = nullptr;
    const bool exr = magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01;
    if (magic[0] == 0x89) reader = png_size;
    if (magic[0] == 0xFF && magic[1] == 0xD8) reader = jpeg_size;
    if (magic[0] == '#' && magic[1] == '?') reader = hdr_size;
    if (magic[0] == 'B' && magic[1] == 'M') reader = bmp_size;
    if (known_format) *known_format = exr || reader;
    if (exr) return exr_size(path, width, height);
    return reader && reader(f, width, height);
}

}  // namespace image_io_detail

bool read_image_size(const std::string& path, int& width, int& height) {
    // A FIFO or a device would block or feed the header reader; load_image refuses them by name.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return false;
    int64_t w = 0, h = 0;
    if (!image_io_detail::header_size(path, w, h) || w > std::numeric_limits<int>::max() ||
        h > std::numeric_limits<int>::max())
        return false;
    width = int(w);
    height = int(h);
    return true;
}

uint64_t max_decoded_image_pixels() {
    const uint64_t ram = physical_memory_bytes();
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
                  format_bytes(double(physical_memory_bytes())).c_str());
    throw InputError(path, field, buf);
}

}  // namespace dp
