#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "base/error.h"
#include "image/image.h"
#include "image/image_io.h"

// Helpers shared by the image_io*.cpp files; not part of the public image API.
namespace dp::image_io_detail {

/// One image format the reader accepts (docs/project-format.md, "Image files").
struct ImageFormat {
    const char* name;           ///< as messages say it: "PNG", "OpenEXR"
    const char* a_name;         ///< with its article: "a PNG", "an OpenEXR"
    const char* oiio;           ///< OpenImageIO's reader of it: "png", "openexr"
    const char* extensions[2];  ///< lower case with the dot, the usual one first; null where unused
    const char* magic_text;     ///< how its first bytes read, for messages
    bool (*matches)(const unsigned char* bytes, size_t n);  ///< whether a file's first bytes are its
};

/// The format the file's extension names (case-insensitive); null for any other extension.
const ImageFormat* format_by_extension(const std::string& path);
/// The format whose magic number starts `bytes`; null for none of them.
const ImageFormat* format_by_content(const unsigned char* bytes, size_t n);

/// Throws InputError unless `path` names a non-empty regular file of at most
/// kMaxImageFileBytes whose extension names an accepted format and whose first bytes are that
/// format's ("not a PNG file (its first bytes are ...)"). Returns the format.
const ImageFormat& check_image_format(const std::string& path, const std::string& field);

/// What an image's header declares, read without decoding.
struct DeclaredSize {
    int64_t width = 0, height = 0;  ///< as the picture loads (EXIF orientation 5 to 8 swaps them)
    /// The fewest bytes a complete file of that size takes in its coding (0: no bound known),
    /// and why, for the message ("one bit per 8 x 8 block at the least").
    uint64_t min_file_bytes = 0;
    const char* min_bytes_why = "";
    const char* format = "";  ///< the format's name, by its magic number
};

/// The size an EXR, PNG, JPEG, Radiance HDR, BMP or TIFF header declares (64-bit: a corrupt
/// header may declare anything); false for other content or an unreadable header.
/// `known_format` tells the two apart: true when the magic number is one of those formats.
bool header_size(const std::string& path, DeclaredSize& size, bool* known_format = nullptr);

/// Refuses from the header alone, before anything is allocated, an image whose header gives
/// no size, declares more than check_image_size allows, or declares more pixels than the file
/// can hold in its coding (a truncated or forged file): InputError naming `path`, `field`, the
/// declared size and the limit.
void check_declared_size(const std::string& path, const std::string& field);

/// Throws the InputError used for every undecodable file, with `detail` saying why.
[[noreturn]] inline void throw_unreadable(const std::string& path, const std::string& field,
                                          const std::string& detail) {
    throw InputError(path, field, "cannot read image (corrupt or unsupported format): " + detail);
}

/// Loads an EXR through OpenEXR's RGBA interface, which rebuilds the subsampled channels of
/// luminance/chroma files that OpenImageIO refuses. Values are returned as stored.
Image load_exr_main(const std::string& path, const std::string& field);

/// Decodes `path` with OpenImageIO's reader of `format` alone, as load_image documents
/// (options, report).
Image load_with_oiio(const std::string& path, const std::string& field, const ImageFormat& format,
                     const ImageLoadOptions& options, ImageLoadReport& report);

/// Throws std::runtime_error naming `path` when the folder it would be written to is missing;
/// output folders are never created implicitly, so a mistyped path fails loudly.
void check_output_folder(const std::string& path);

}  // namespace dp::image_io_detail
