#include "assets/file_materials.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "base/error.h"

namespace dp {

namespace fs = std::filesystem;

namespace {

/// A file with a roughness (glTF; MTL's Pr): the principled material, every factor clamped.
Material principled_from_file(const FileMaterial& f, const vec3& colour, const std::string& texture_label) {
    Material m;
    m.kind = Material::Kind::Principled;
    m.albedo.rgb = colour;
    if (!texture_label.empty()) {
        m.albedo.kind = Albedo::Kind::Texture;
        m.albedo.texture_path = texture_label;
    }
    PrincipledMaterial& p = m.principled;
    p.metallic = std::clamp(f.metallic, 0.0f, 1.0f);
    p.roughness = std::clamp(f.roughness, 0.0f, 1.0f);
    p.transmission = std::clamp(f.transmission, 0.0f, 1.0f);
    p.ior = f.ior > 0 ? std::clamp(f.ior, kMinPrincipledIor, kMaxPrincipledIor) : 1.5f;
    return m;
}

}  // namespace

Material material_from_file(const FileMaterial& f, const std::string& texture_label) {
    const vec3 colour = glm::clamp(f.colour, vec3(0.0f), vec3(1.0f));
    if (f.roughness >= 0) return principled_from_file(f, colour, texture_label);
    Material m;
    if (f.transmission > 0) {
        m.kind = Material::Kind::Glass;
        m.ior = f.ior > 0 ? f.ior : 1.5f;
        m.tint = colour;
    } else if (f.metallic >= 0.5f) {
        m.kind = Material::Kind::Mirror;
        m.reflectance = colour;
    } else {
        m.kind = Material::Kind::Diffuse;
        m.albedo.rgb = colour;
        if (!texture_label.empty()) {
            m.albedo.kind = Albedo::Kind::Texture;
            m.albedo.texture_path = texture_label;
        }
    }
    return m;
}

Image decode_embedded_texture(const EmbeddedTexture& texture, int index,
                              const std::string& mesh_path, const std::string& field,
                              ImageLoadReport* report, const ImageLoadOptions& options) {
    // The image decoders read files: the bytes go through a private temporary file, so that an
    // embedded texture meets every check a texture file meets (its header's size first).
    // The reader takes the format from the file's name: the name follows the bytes, as the
    // mesh file's own format hint may be missing or wrong.
    std::string ext = image_extension_for_content(texture.bytes.data(), texture.bytes.size());
    if (ext.empty()) ext = texture.format.empty() ? std::string("img") : texture.format;
    static std::atomic<unsigned> counter{0};
    const fs::path temp = fs::temp_directory_path() / ("dp_embedded_texture_" + std::to_string(::getpid()) + "_" +
                                                       std::to_string(counter++) + "." + ext);
    struct Remove {
        fs::path path;
        ~Remove() {
            std::error_code ec;
            fs::remove(path, ec);
        }
    } remove{temp};
    const std::string label = "embedded texture " + std::to_string(index);
    {
        std::ofstream out(temp, std::ios::binary);
        out.write(reinterpret_cast<const char*>(texture.bytes.data()),
                  std::streamsize(texture.bytes.size()));
        if (!out)
            throw InputError(mesh_path, field,
                             label + ": cannot be written to a temporary file to decode it");
    }
    try {
        return load_image(temp.string(), "", report, options);
    } catch (const InputError& e) {
        // Said of the mesh file, not of the temporary file.
        std::string why = e.what();
        const std::string prefix = shorten_path(temp.string()) + ": ";
        if (why.rfind(prefix, 0) == 0) why = why.substr(prefix.size());
        throw InputError(mesh_path, field, label + ": " + why);
    }
}

}  // namespace dp
