#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "base/error.h"
#include "image/image.h"
#include "image/image_io.h"

// Helpers shared by the image_io*.cpp files; not part of the public image API.
namespace dp::image_io_detail {

/// Throws InputError unless `path` names an existing, non-empty regular file that can be
/// opened. Returns whether the file starts with the OpenEXR magic number.
bool check_image_file(const std::string& path, const std::string& field);

/// The size an EXR, PNG, JPEG, Radiance HDR or BMP header declares (64-bit: a corrupt header
/// may declare anything); false for other formats or an unreadable header. `known_format` tells
/// the two apart: true when the magic number is one of those formats.
bool header_size(const std::string& path, int64_t& width, int64_t& height, bool* known_format = nullptr);

/// Throws the InputError used for every undecodable file, with `detail` saying why.
[[noreturn]] inline void throw_unreadable(const std::string& path, const std::string& field,
                                          const std::string& detail) {
    throw InputError(path, field, "cannot read image (corrupt or unsupported format): " + detail);
}

/// Loads an EXR through OpenEXR's RGBA interface, which rebuilds the subsampled channels of
/// luminance/chroma files that OpenImageIO refuses. Values are returned as stored.
Image load_exr_main(const std::string& path, const std::string& field);

/// Decodes any format OpenImageIO reads, as load_image documents (options, report).
Image load_with_oiio(const std::string& path, const std::string& field, const ImageLoadOptions& options,
                     ImageLoadReport& report);

/// Throws std::runtime_error naming `path` when the folder it would be written to is missing;
/// output folders are never created implicitly, so a mistyped path fails loudly.
void check_output_folder(const std::string& path);

}  // namespace dp::image_io_detail
