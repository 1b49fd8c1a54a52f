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
    size_t clipped = 0;              ///< integer-coded pixels with a channel at the maximum code
    bool linear_source = false;      ///< float data or a linear colour space (true), or encoded
    /// The layers the file holds ("" for the plain R, G, B one), in file order, and the one read.
    std::vector<std::string> layers;
    std::string layer;
    /// The data window, when it differs from the display window the image was loaded as
    /// (pixels outside the data window are 0; data outside the display window is dropped).
    bool window_differs = false;
    int data_x = 0, data_y = 0, data_width = 0, data_height = 0;
    std::string icc_profile;  ///< description of an embedded ICC profile, "" if none
    bool icc_converted = false;  ///< the pixels were converted from it to linear Rec.709
    std::string colorspace;      ///< the colour space the pixels were read as ("srgb", "linear", ...)
    /// Things a user should hear of (an ICC profile left unconverted, a chosen colour space
    /// that contradicts the data), one line each.
    std::vector<std::string> warnings;
    /// The file's metadata worth carrying into outputs (camera make/model, EXIF exposure).
    std::vector<std::pair<std::string, std::string>> metadata;
};

/// How to read an image's pixels.
struct ImageLoadOptions {
    /// The layer of a multilayer file (EXR: "ViewLayer.Combined", "dL"; a part's name); ""
    /// reads the plain R, G, B channels, or a lone "...Combined" layer when there are none.
    std::string layer;
    /// "" or "auto" (float data is linear, integer data sRGB, an ICC profile converted),
    /// "srgb", "linear", or a colour space of the OpenColorIO config (display_transform.h).
    std::string colorspace;
};

/// Loads the documented formats, picked by the file's extension and confirmed by its first
/// bytes: OpenEXR (.exr), Radiance HDR (.hdr), PNG, JPEG (.jpg, .jpeg), TIFF (.tif, .tiff) and
/// BMP, each through OpenImageIO's reader of that format alone (its other readers are never
/// tried on a file). Float data (EXR, HDR, float TIFF) loads as linear, integer data (PNG,
/// JPEG, 8/16-bit TIFF, BMP) as sRGB decoded to linear, unless `options` says otherwise; an
/// embedded RGB matrix/TRC ICC profile (Display P3, Adobe RGB) is converted to linear Rec.709.
/// An EXR loads as its display window.
/// JPEG and TIFF come upright by their EXIF Orientation tag, as viewers show them (a phone's
/// portrait photo, stored landscape with orientation 6 or 8, loads portrait); a PNG's tag is
/// not applied (OpenCV does not), so a PNG loads as stored.
/// Throws InputError naming `path` and `field` when the file is missing, not a regular file,
/// over kMaxImageFileBytes, of another extension, not what its extension says ("not a PNG
/// file (its first bytes are ...)"), unreadable, corrupt, empty, over check_image_size, or
/// smaller than a complete file of the size its header declares (all measured from the
/// header, before decoding: a tiny file declaring a huge size allocates nothing). NaN/Inf
/// become 0, counted in `report`.
Image load_image(const std::string& path, const std::string& field = "",
                 ImageLoadReport* report = nullptr, const ImageLoadOptions& options = {});

/// One named layer of a multi-layer EXR; "" is the main RGB layer (channels R, G, B),
/// anything else writes channels "<name>.R", "<name>.G", "<name>.B".
struct ExrLayer {
    std::string name;
    const Image* image;
    /// An alpha channel ("A", or "<name>.A") from this image's red channel; null for none.
    const Image* alpha = nullptr;
};

/// The metadata of an image worth carrying into outputs made from it (camera make and model,
/// EXIF exposure, lens, date) as name/value pairs, from its header alone; empty if unreadable.
std::vector<std::pair<std::string, std::string>> read_image_metadata(const std::string& path);

/// The layers with colour channels an image holds ("" for the plain R, G, B one), in file
/// order, from its headers alone: what a user chooses the photo from when a multilayer plate
/// holds several Combined layers. Empty for an unreadable file.
std::vector<std::string> read_image_layers(const std::string& path);

/// Reads an image's size from its header (EXR, PNG, JPEG, HDR, BMP, TIFF) without decoding it,
/// as load_image returns the picture (a JPEG's or TIFF's EXIF orientation 5 to 8 swaps width
/// and height); false for other content, an unreadable header, or a path that is not a regular
/// file (a FIFO is never opened: decode the image then, which says what is wrong).
bool read_image_size(const std::string& path, int& width, int& height);

/// The extension ("png", "jpg", "exr", "hdr", "tif", "bmp") of the accepted format whose magic
/// number starts `bytes`, "" for none: the name a texture embedded in a mesh file is decoded
/// under, whatever format the mesh file claims for it.
std::string image_extension_for_content(const void* bytes, size_t size);
/// Throws InputError naming `path` and `field` where `path`'s extension is not that of the image
/// whose encoded bytes are given (their first bytes decide): bytes written as they are would
/// carry one format under another's name. An unrecognised content passes.
void check_extension_for_content(const std::string& path, const std::string& field, const void* bytes, size_t size);

/// The largest image file load_image opens: 8 GiB, more than any file within the pixel limit
/// needs (an 8192 x 4096 multilayer EXR of 40 float channels is 5.4 GB).
inline constexpr uint64_t kMaxImageFileBytes = uint64_t(8) << 30;

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

/// Sample formats of written files.
enum class SampleFormat { Default, U8, U16, Half, Float };

/// How outputs are written; metadata goes into the file's header (EXR attributes, PNG text,
/// TIFF tags, JPEG EXIF).
struct ImageWriteOptions {
    SampleFormat format = SampleFormat::Default;  ///< EXR: Float; PNG, JPEG: U8; TIFF: U16
    int jpeg_quality = 95;
    /// Name/value pairs: "Software", "Make", "Model", "Exif:FNumber", "diffphoton:passes", ...
    std::vector<std::pair<std::string, std::string>> metadata;
};

/// Writes an EXR with the given layers (all the same size), 32-bit float or half.
void save_exr(const std::string& path, const std::vector<ExrLayer>& layers, const ImageWriteOptions& options = {});
/// Reads one layer of an EXR ("" for the main one).
Image load_exr_layer(const std::string& path, const std::string& layer);

class DisplayTransform;
/// Writes a PNG, JPEG or TIFF (by extension) of `image` through `view`: 8 or 16 bits per
/// channel of display code values; a TIFF asked for Float gets the linear values instead.
void save_display_image(const std::string& path, const Image& image, const DisplayTransform& view,
                        const ImageWriteOptions& options = {});
/// Writes an 8-bit sRGB PNG/JPEG (by extension): linear * 2^exposure, clamped to [0, 1].
void save_ldr(const std::string& path, const Image& image, float exposure = 0.0f);

/// sRGB transfer functions (IEC 61966-2-1).
float srgb_to_linear(float v);
float linear_to_srgb(float v);

}  // namespace dp
