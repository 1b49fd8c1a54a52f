#pragma once
// Materials from mesh files mapped onto the project's kinds (docs/project-format.md,
// "Materials from the file"), and the textures stored inside mesh files decoded.
#include <string>

#include "geometry/mesh.h"
#include "image/image.h"
#include "image/image_io.h"
#include "scene/project.h"

namespace dp {

/// A file's material as one of ours. With a roughness (every glTF material; MTL's Pr): the
/// principled material, base colour the colour or `texture_label` as its texture, metallic,
/// roughness, transmission and ior (KHR_materials_ior, 1.5 without it) from the file. Without
/// one: transmission > 0 is glass (tint the colour), else metallic >= 0.5 a mirror
/// (reflectance the colour), else diffuse with the colour or the texture. The decoded texture
/// travels beside it (FileMaterialAsset). Colours and factors are clamped to their ranges.
Material material_from_file(const FileMaterial& file, const std::string& texture_label = "");

/// Decodes a texture stored inside mesh file `mesh_path`, as load_image decodes a file (the
/// same size limits, sRGB PNG and JPEG linearised unless `options` say otherwise). Throws InputError naming the mesh file,
/// `field` and the texture's index.
Image decode_embedded_texture(const EmbeddedTexture& texture, int index,
                              const std::string& mesh_path, const std::string& field,
                              ImageLoadReport* report = nullptr, const ImageLoadOptions& options = {});

}  // namespace dp
