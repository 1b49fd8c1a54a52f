#pragma once
// JPEGs with an EXIF orientation, written by hand (an APP1 "Exif" segment right after the SOI
// whose first IFD holds the Orientation tag), and a marked corner to see which way a picture
// was turned.
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

namespace dp::test {

/// `jpeg` with an APP1 "Exif" segment holding Orientation (0x0112) = `orientation`, in
/// little-endian ("II") or big-endian ("MM") byte order.
inline std::vector<uint8_t> with_exif_orientation(const std::vector<uint8_t>& jpeg, int orientation,
                                                  bool big_endian = false) {
    std::vector<uint8_t> tiff;
    auto u16 = [&](unsigned v) {
        if (big_endian) tiff.insert(tiff.end(), {uint8_t(v >> 8), uint8_t(v)});
        else tiff.insert(tiff.end(), {uint8_t(v), uint8_t(v >> 8)});
    };
    auto u32 = [&](uint32_t v) {
        if (big_endian) {
            u16(v >> 16);
            u16(v & 0xFFFF);
        } else {
            u16(v & 0xFFFF);
            u16(v >> 16);
        }
    };
    tiff.insert(tiff.end(), big_endian ? std::initializer_list<uint8_t>{'M', 'M', 0, 42}
                                       : std::initializer_list<uint8_t>{'I', 'I', 42, 0});
    u32(8);       // IFD0 right after the header
    u16(1);       // one entry:
    u16(0x0112);  // Orientation,
    u16(3);       // SHORT,
    u32(1);       // one value,
    u16(unsigned(orientation));  // in the first two bytes of the value field
    u16(0);
    u32(0);  // no next IFD
    const size_t length = 2 + 6 + tiff.size();
    std::vector<uint8_t> out(jpeg.begin(), jpeg.begin() + 2);  // SOI
    out.insert(out.end(), {0xFF, 0xE1, uint8_t(length >> 8), uint8_t(length), 'E', 'x', 'i', 'f', 0, 0});
    out.insert(out.end(), tiff.begin(), tiff.end());
    out.insert(out.end(), jpeg.begin() + 2, jpeg.end());
    return out;
}

/// A dark `width` x `height` picture with a bright square in its top-left corner.
inline cv::Mat marked_picture(int width, int height) {
    cv::Mat m(height, width, CV_8UC3, cv::Scalar(20, 20, 20));
    m(cv::Rect(0, 0, width / 4, height / 4)).setTo(cv::Scalar(230, 230, 230));
    return m;
}

/// marked_picture encoded as a JPEG.
inline std::vector<uint8_t> marked_jpeg(int width, int height) {
    std::vector<uint8_t> bytes;
    cv::imencode(".jpg", marked_picture(width, height), bytes);
    return bytes;
}

}  // namespace dp::test
