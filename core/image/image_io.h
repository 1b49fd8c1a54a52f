#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "image/image.h"

namespace dp {

/// What loading found in the file besides the pixels.
struct ImageLoadReport {
    size_t non_finite_replaced = 0;  ///< NaN/Inf pixels (per channel) replaced by 0
    size_t clipped = 0;              ///< LDR pixels with a channel at the maximum code value
    bool linear_source = false;      ///< EXR/HDR (true) or sRGB-encoded LDR (false)
};

/// Loads EXR or Radiance HDR as linear float, PNG/JPEG/TIFF/BMP as sRGB decoded to linear.
/// JPEG and TIFF come upright by their EXIF Orientation tag, as viewers show them (a phone's
/// portrait photo, stored landscape with orientation 6 or 8, loads portrait); a PNG's tag is
/// not applied (OpenCV does not), so a PNG loads as stored.
/// Throws InputError naming `path` and `field` when the file is missing, unreadable, corrupt,
/// empty or over check_image_size (measured from the header for EXR, PNG, JPEG, HDR and BMP: a
/// tiny file declaring a huge size allocates nothing). NaN/Inf become 0, counted in `report`.
Image load_image(const std::string& path, const std::string& field = "",
                 ImageLoadReport* report = nullptr);

/// One named layer of a multi-layer EXR; "" is the main RGB layer (channels R, G, B),
/// anything else writes channels "<name>.R", "<name>.G", "<name>.B".
struct ExrLayer {
    std::string name;
    const Image* image;
    /// An alpha channel ("A", or "<name>.A") from this image's red channel; null for none.
    const Image* alpha = nullptr;
};

/// Reads an image's size from its header (EXR, PNG, JPEG, HDR, BMP) without decoding it, as
/// load_image returns the picture (a JPEG's EXIF orientation 5 to 8 swaps width and height);
/// false for other formats or an unreadable header (decode the image then).
bool read_image_size(const std::string& path, int& width, int& height);

/// The most pixels load_image decodes: 2^28 (16384 x 16384, 3.2 GB as linear float), fewer
/// where that would take more than half of this machine's memory or where the environment's
/// DP_MAX_IMAGE_PIXELS asks for fewer (max_decoded_image_pixels).
inline constexpr uint64_t kMaxImagePixels = uint64_t(1) << 28;
/// Peak bytes per pixel while decoding: the decoder's buffer and the linear float image.
inline constexpr double kDecodeBytesPerPixel = 24;
uint64_t max_decoded_image_pixels();

/// Throws InputError naming `path` and `field` when an image of width x height would be more
/// than max_decoded_image_pixels to decode; the message gives the size, the memory it would take
/// and the limit. load_image calls it with the size from the file's header, before decoding.
void check_image_size(const std::string& path, const std::string& field, int64_t width, int64_t height);

/// Writes a 32-bit float EXR with the given layers (all the same size).
void save_exr(const std::string& path, const std::vector<ExrLayer>& layers);
/// Reads one layer of an EXR written by save_exr ("" for the main one).
Image load_exr_layer(const std::string& path, const std::string& layer);

/// Writes an 8-bit sRGB PNG/JPEG (by extension): linear * 2^exposure, clamped to [0, 1].
void save_ldr(const std::string& path, const Image& image, float exposure = 0.0f);

/// sRGB transfer functions (IEC 61966-2-1).
float srgb_to_linear(float v);
float linear_to_srgb(float v);

}  // namespace dp
