#include "geometry/mesh_materials.h"

#include <assimp/GltfMaterial.h>
#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

namespace dp {

namespace {

namespace fs = std::filesystem;

bool has_key(const aiMaterial& m, const char* key) {
    const aiMaterialProperty* p = nullptr;
    return aiGetMaterialProperty(&m, key, 0, 0, &p) == aiReturn_SUCCESS;
}

vec3 colour_of(const aiMaterial& m, const char* key, unsigned type, unsigned index, vec3 fallback) {
    aiColor4D c;
    if (m.Get(key, type, index, c) != aiReturn_SUCCESS) return fallback;
    const vec3 v(c.r, c.g, c.b);
    return is_finite(v) ? v : fallback;
}

float number_of(const aiMaterial& m, const char* key, unsigned type, unsigned index,
                float fallback) {
    float v = 0;
    if (m.Get(key, type, index, v) != aiReturn_SUCCESS || !std::isfinite(v)) return fallback;
    return v;
}

/// Where an external texture path from a mesh file points: relative paths from the mesh file's
/// folder, Windows separators read as '/' (MTL files written on Windows), "file://" dropped.
std::string resolve_texture(const std::string& mesh_path, std::string path) {
    std::replace(path.begin(), path.end(), '\\', '/');
    if (path.rfind("file://", 0) == 0) path = path.substr(7);
    const fs::path p(path);
    if (p.is_absolute()) return p.lexically_normal().string();
    return (fs::path(mesh_path).parent_path() / p).lexically_normal().string();
}

/// The format name Assimp gives an embedded texture ("png", "jpg"), letters and digits only.
std::string format_hint(const aiTexture& t) {
    std::string hint;
    for (char c : std::string(t.achFormatHint, strnlen(t.achFormatHint, sizeof(t.achFormatHint))))
        if (std::isalnum(static_cast<unsigned char>(c)))
            hint += char(std::tolower(static_cast<unsigned char>(c)));
    return hint;
}

/// The texture of `type` a material names, as a file path or an embedded texture (added to
/// `embedded` the first time a material names it); empty, with a warning where the file names
/// one that cannot be used.
FileTexture texture_of(const aiScene& scene, const aiMaterial& m, aiTextureType type, const std::string& material,
                       const char* what, const std::string& mesh_path, std::vector<EmbeddedTexture>& embedded,
                       std::vector<int>& embedded_slot, std::vector<std::string>& warnings) {
    FileTexture out;
    aiString texture;
    if (m.GetTextureCount(type) == 0 || m.GetTexture(type, 0, &texture) != aiReturn_SUCCESS || texture.length == 0)
        return out;
    const std::string reference = texture.C_Str();
    const bool colour = std::string("colour") == what;
    const std::string ignored = colour ? "its colour is used" : "it is ignored";
    const std::string kind = colour ? "" : std::string(what) + " ";  // "texture" alone: the colour's
    if (const aiTexture* t = scene.GetEmbeddedTexture(texture.C_Str())) {
        const auto k = size_t(std::find(scene.mTextures, scene.mTextures + scene.mNumTextures, t) - scene.mTextures);
        if (k >= scene.mNumTextures) return out;
        if (t->mHeight != 0 || !t->pcData || t->mWidth == 0) {
            // Decoded texels (mHeight rows) rather than a PNG or JPEG: no exporter in use
            // writes these.
            warnings.push_back("material '" + material + "': its embedded " + kind +
                               "texture is stored uncompressed, which is not read; " + ignored);
            return out;
        }
        if (embedded_slot[k] < 0) {
            embedded_slot[k] = int(embedded.size());
            const auto* bytes = reinterpret_cast<const unsigned char*>(t->pcData);
            embedded.push_back({format_hint(*t), std::vector<unsigned char>(bytes, bytes + t->mWidth)});
        }
        out.embedded = embedded_slot[k];
    } else if (reference[0] == '*') {
        warnings.push_back("material '" + material + "' names embedded " + kind + "texture " + reference +
                           ", which the file does not hold; " + ignored);
    } else {
        out.path = resolve_texture(mesh_path, reference);
    }
    return out;
}

}  // namespace

std::vector<FileMaterial> read_file_materials(const aiScene& scene, const std::string& mesh_path,
                                              std::vector<EmbeddedTexture>& embedded,
                                              std::vector<bool>& made_up,
                                              std::vector<std::string>& warnings) {
    std::vector<FileMaterial> out(scene.mNumMaterials);
    made_up.assign(scene.mNumMaterials, false);
    aiString format_name;
    const std::string format =
        scene.mMetaData && scene.mMetaData->Get("SourceAsset_Format", format_name)
            ? format_name.C_Str()
            : "";
    const bool gltf = format.find("glTF") != std::string::npos;
    // Formats without materials: Assimp gives their faces a white one of its own.
    const bool no_materials =
        format.find("PLY") != std::string::npos || format.find("STL") != std::string::npos;
    std::vector<int> embedded_slot(scene.mNumTextures, -1);  // Assimp's texture index -> ours

    for (unsigned i = 0; i < scene.mNumMaterials; ++i) {
        const aiMaterial* m = scene.mMaterials[i];
        FileMaterial& f = out[i];
        if (!m) {
            made_up[i] = true;
            continue;
        }
        aiString name;
        if (m->Get(AI_MATKEY_NAME, name) == aiReturn_SUCCESS) f.name = name.C_Str();
        // Assimp's glTF reader appends a default material for primitives without one.
        made_up[i] = no_materials || f.name == AI_DEFAULT_MATERIAL_NAME ||
                     (gltf && i + 1 == scene.mNumMaterials);
        // glTF: the base colour, which the base colour texture is multiplied by. MTL and FBX: the
        // diffuse colour, which a texture replaces (Blender writes Kd 0.8 beside map_Kd).
        aiTextureType texture_type = aiTextureType_DIFFUSE;
        if (has_key(*m, "$clr.base")) {
            f.colour = colour_of(*m, AI_MATKEY_BASE_COLOR, vec3(1.0f));
            f.texture_times_colour = true;
            if (m->GetTextureCount(aiTextureType_BASE_COLOR) > 0)
                texture_type = aiTextureType_BASE_COLOR;
        } else {
            f.colour = colour_of(*m, AI_MATKEY_COLOR_DIFFUSE, vec3(0.8f));
        }
        f.metallic = number_of(*m, AI_MATKEY_METALLIC_FACTOR, 0.0f);
        f.transmission = number_of(*m, AI_MATKEY_TRANSMISSION_FACTOR, 0.0f);
        // glTF always has one (its default is 1); MTL's Pr only where the file writes it.
        if (has_key(*m, "$mat.roughnessFactor")) f.roughness = number_of(*m, AI_MATKEY_ROUGHNESS_FACTOR, 1.0f);
        // MTL's Ni is read into the same key; only a transmitting (glTF) material uses it.
        if (gltf) f.ior = number_of(*m, AI_MATKEY_REFRACTI, 0.0f);

        const auto read = [&](aiTextureType type, const char* what) {
            return texture_of(scene, *m, type, f.name, what, mesh_path, embedded, embedded_slot, warnings);
        };
        const FileTexture colour = read(texture_type, "colour");
        f.texture = colour.path;
        f.embedded_texture = colour.embedded;
        // Assimp 5.2 keeps glTF's metallicRoughnessTexture under the UNKNOWN type.
        if (gltf) f.metallic_roughness = read(aiTextureType_UNKNOWN, "metallic-roughness");
        f.normal = read(aiTextureType_NORMALS, "normal");
        if (!f.normal.empty())
            f.normal_scale = number_of(*m, AI_MATKEY_GLTF_TEXTURE_SCALE(aiTextureType_NORMALS, 0), 1.0f);
    }
    return out;
}

void keep_used_materials(LoadedMesh& loaded) {
    TriangleMesh& mesh = loaded.mesh;
    std::vector<uint32_t> renumber(loaded.materials.size(), kNoFileMaterial);
    std::vector<FileMaterial> kept;
    for (uint32_t& m : mesh.triangle_materials) {
        if (m >= renumber.size()) {
            m = kNoFileMaterial;
            continue;
        }
        if (renumber[m] == kNoFileMaterial) {
            renumber[m] = uint32_t(kept.size());
            kept.push_back(loaded.materials[m]);
        }
        m = renumber[m];
    }
    if (kept.empty()) {
        mesh.triangle_materials.clear();
        loaded.embedded_textures.clear();
    }
    // Embedded textures no kept material uses stay: they are few, and renumbering them would
    // gain nothing.
    loaded.materials = std::move(kept);
}

}  // namespace dp
