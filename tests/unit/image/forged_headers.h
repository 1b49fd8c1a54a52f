// Image files whose headers are complete and well formed (the decoders' header readers accept
// them) but which hold far fewer bytes than the size they declare: forged or truncated files.
#pragma once
#include <cstdint>
#include <string>

namespace dp::test {

inline std::string be16(uint16_t v) { return {char(v >> 8), char(v)}; }
inline std::string be32(uint32_t v) { return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }
inline std::string le16(uint16_t v) { return {char(v), char(v >> 8)}; }
inline std::string le32(uint32_t v) { return {char(v), char(v >> 8), char(v >> 16), char(v >> 24)}; }

/// CRC-32 as PNG chunks carry it (ISO 3309), over `bytes`.
inline uint32_t png_crc(const std::string& bytes) {
    uint32_t c = 0xFFFFFFFFu;
    for (const unsigned char b : bytes) {
        c ^= b;
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
}

/// A PNG signature, an IHDR of width x height 8-bit RGB (with its CRC), and an IDAT chunk
/// that starts but holds only `fill` zeros.
inline std::string png_declaring(uint32_t width, uint32_t height, size_t fill) {
    const std::string ihdr = "IHDR" + be32(width) + be32(height) + std::string("\x08\x02\x00\x00\x00", 5);
    return std::string("\x89PNG\r\n\x1a\n", 8) + be32(13) + ihdr + be32(png_crc(ihdr)) + be32(uint32_t(fill)) +
           "IDAT" + std::string(fill, '\0');
}

/// A baseline JPEG's start declaring width x height in three components (4:2:0), its scan's
/// header, then `fill` zeros and the end marker: about `fill` bytes, whatever size it declares.
inline std::string jpeg_declaring(uint16_t width, uint16_t height, size_t fill) {
    std::string b("\xFF\xD8\xFF\xC0", 4);
    b += be16(17) + std::string("\x08", 1) + be16(height) + be16(width) +
         std::string("\x03\x01\x22\x00\x02\x11\x01\x03\x11\x01", 10);
    b += std::string("\xFF\xDA", 2) + be16(12) + std::string("\x03\x01\x00\x02\x11\x03\x11\x00\x3F\x00", 10);
    return b + std::string(fill, '\0') + std::string("\xFF\xD9", 2);
}

/// A little-endian TIFF whose first IFD declares width x height, 8-bit grey, uncompressed, in
/// one strip that the file does not hold.
inline std::string tiff_declaring(uint32_t width, uint32_t height) {
    auto entry = [](uint16_t tag, uint16_t type, uint32_t value) {
        return le16(tag) + le16(type) + le32(1) + (type == 3 ? le16(uint16_t(value)) + le16(0) : le32(value));
    };
    const uint16_t n = 9;
    const uint32_t data = 8 + 2 + 12 * n + 4;
    return std::string("II*\0", 4) + le32(8) + le16(n) + entry(256, 4, width) + entry(257, 4, height) +
           entry(258, 3, 8) + entry(259, 3, 1) + entry(262, 3, 1) + entry(273, 4, data) + entry(277, 3, 1) +
           entry(278, 4, height) + entry(279, 4, width * height) + le32(0);
}

}  // namespace dp::test
