// An image's size from its header, without decoding the pixels: the studio asks for the photo's
// size on the UI thread, where a 12 MP decode would stall the window.
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <cstdint>
#include <fstream>
#include <vector>

#include "image/image_io.h"

namespace dp {

namespace {

uint32_t be32(const unsigned char* b) { return uint32_t(b[0]) << 24 | uint32_t(b[1]) << 16 | uint32_t(b[2]) << 8 | b[3]; }
uint16_t be16(const unsigned char* b) { return uint16_t(b[0] << 8 | b[1]); }

bool png_size(std::ifstream& f, int& w, int& h) {
    unsigned char b[24];
    if (!f.read(reinterpret_cast<char*>(b), 24)) return false;
    if (b[0] != 0x89 || b[1] != 'P' || b[2] != 'N' || b[3] != 'G') return false;
    w = int(be32(b + 16));
    h = int(be32(b + 20));
    return w > 0 && h > 0;
}

bool jpeg_size(std::ifstream& f, int& w, int& h) {
    unsigned char b[2];
    if (!f.read(reinterpret_cast<char*>(b), 2) || b[0] != 0xFF || b[1] != 0xD8) return false;
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
            return w > 0 && h > 0;
        }
        if (length < 2) return false;
        f.seekg(length - 2, std::ios::cur);
    }
    return false;
}

}  // namespace

bool read_image_size(const std::string& path, int& width, int& height) {
    std::ifstream f(path, std::ios::binary);
    if (!f) return false;
    unsigned char magic[4] = {0, 0, 0, 0};
    f.read(reinterpret_cast<char*>(magic), 4);
    f.clear();
    f.seekg(0);
    if (magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01) {
        try {
            Imf::InputFile exr(path.c_str());
            const Imath::Box2i dw = exr.header().dataWindow();
            width = dw.max.x - dw.min.x + 1;
            height = dw.max.y - dw.min.y + 1;
            return width > 0 && height > 0;
        } catch (const std::exception&) {
            return false;
        }
    }
    if (magic[0] == 0x89) return png_size(f, width, height);
    if (magic[0] == 0xFF && magic[1] == 0xD8) return jpeg_size(f, width, height);
    return false;
}

}  // namespace dp
