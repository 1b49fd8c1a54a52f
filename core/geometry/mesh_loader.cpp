#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <exception>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <new>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "base/error.h"
#include "base/input_file.h"
#include "base/text.h"
#include "geometry/checked_io_system.h"
#include "geometry/mesh.h"
#include "geometry/mesh_file_checks.h"
#include "geometry/mesh_limits.h"
#include "geometry/mesh_materials.h"

namespace dp {

namespace {

glm::mat4 to_glm(const aiMatrix4x4& a) {
    // Assimp stores row-major (a[row][col]); glm indexes m[col][row].
    glm::mat4 m;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m[c][r] = a[r][c];
    return m;
}

/// True when the triangle has no usable area: a non-finite corner, or twice its area is below
/// what float coordinates can resolve relative to its longest edge.
bool is_degenerate(const vec3& a, const vec3& b, const vec3& c) {
    if (!is_finite(a) || !is_finite(b) || !is_finite(c)) return true;
    const dvec3 e0 = dvec3(b) - dvec3(a), e1 = dvec3(c) - dvec3(a), e2 = dvec3(c) - dvec3(b);
    const double twice_area = glm::length(glm::cross(e0, e1));
    const double longest_sq = std::max({glm::dot(e0, e0), glm::dot(e1, e1), glm::dot(e2, e2)});
    return !(twice_area > 1e-7 * longest_sq);
}

struct Collector {
    const aiScene* scene;
    std::vector<bool> made_up;  ///< per Assimp material: one Assimp invented (no file material)
    TriangleMesh out;
    bool any_uvs = false;
    size_t total_triangles = 0;
    size_t dropped = 0;

    /// Appends one Assimp mesh placed by `world`; points, lines and faces indexing past the vertex
    /// array are skipped.
    void add_mesh(const aiMesh& src, const glm::mat4& world) {
        TriangleMesh part;
        part.positions.reserve(src.mNumVertices);
        for (unsigned i = 0; i < src.mNumVertices; ++i) {
            const aiVector3D& p = src.mVertices[i];
            part.positions.emplace_back(p.x, p.y, p.z);
        }
        if (src.HasNormals()) {
            part.normals.reserve(src.mNumVertices);
            for (unsigned i = 0; i < src.mNumVertices; ++i) {
                const aiVector3D& n = src.mNormals[i];
                part.normals.emplace_back(n.x, n.y, n.z);
            }
        }
        for (unsigned f = 0; f < src.mNumFaces; ++f) {
            const aiFace& face = src.mFaces[f];
            if (face.mNumIndices != 3) continue;
            const unsigned* idx = face.mIndices;
            if (std::max({idx[0], idx[1], idx[2]}) >= src.mNumVertices) continue;
            part.triangles.emplace_back(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
        }
        if (part.triangles.empty()) return;
        part.transform(world);

        const auto base = static_cast<unsigned>(out.positions.size());
        out.positions.insert(out.positions.end(), part.positions.begin(), part.positions.end());
        // Keep one normal per vertex even when this part has none; fill_missing_normals sets them.
        if (part.normals.empty()) part.normals.assign(part.positions.size(), vec3(0.0f));
        out.normals.insert(out.normals.end(), part.normals.begin(), part.normals.end());
        // Assimp hands over every format's UVs with v = 0 at the bottom of the image (OBJ's and
        // OpenGL's convention; it flips glTF's to match), while Surface::reflectance_at reads the
        // image's top row at v = 0: flipped here, once, so a texture painted in Blender reads
        // upright.
        for (unsigned i = 0; i < src.mNumVertices; ++i) {
            const aiVector3D uv = src.HasTextureCoords(0) ? src.mTextureCoords[0][i] : aiVector3D();
            out.uvs.emplace_back(uv.x, 1.0f - uv.y);
        }
        any_uvs = any_uvs || src.HasTextureCoords(0);
        const uint32_t material =
            src.mMaterialIndex < made_up.size() && !made_up[src.mMaterialIndex]
                ? uint32_t(src.mMaterialIndex)
                : kNoFileMaterial;

        for (const glm::uvec3& t : part.triangles) {
            ++total_triangles;
            if (is_degenerate(part.positions[t.x], part.positions[t.y], part.positions[t.z])) {
                ++dropped;
                continue;
            }
            out.triangles.push_back(t + glm::uvec3(base));
            out.triangle_materials.push_back(material);
        }
    }

    void visit(const aiNode& node, const glm::mat4& parent) {
        const glm::mat4 world = parent * to_glm(node.mTransformation);
        for (unsigned i = 0; i < node.mNumMeshes; ++i) {
            const unsigned idx = node.mMeshes[i];
            if (idx < scene->mNumMeshes && scene->mMeshes[idx]) {
                add_mesh(*scene->mMeshes[idx], world);
            }
        }
        for (unsigned i = 0; i < node.mNumChildren; ++i) {
            if (node.mChildren[i]) visit(*node.mChildren[i], world);
        }
    }
};

bool is_valid_normal(const vec3& n) {
    const float len = glm::length(n);
    return std::isfinite(len) && len > 1e-6f;
}

/// Fills missing (zero) or invalid vertex normals with smooth ones: the area-weighted sum of the
/// geometric normals of the kept triangles around every vertex at the same position, so that UV
/// seams do not show as creases. Unused vertices get +Y.
void fill_missing_normals(TriangleMesh& mesh) {
    if (std::all_of(mesh.normals.begin(), mesh.normals.end(), is_valid_normal)) return;
    std::vector<vec3> accum(mesh.positions.size(), vec3(0.0f));
    for (const glm::uvec3& t : mesh.triangles) {
        const vec3& a = mesh.positions[t.x];
        const vec3 g = glm::cross(mesh.positions[t.y] - a, mesh.positions[t.z] - a);
        accum[t.x] += g;
        accum[t.y] += g;
        accum[t.z] += g;
    }
    // Group vertices with identical positions by sorting their indices lexicographically.
    std::vector<unsigned> order(mesh.positions.size());
    for (unsigned i = 0; i < order.size(); ++i) order[i] = i;
    auto less = [&](unsigned i, unsigned j) {
        const vec3 &a = mesh.positions[i], &b = mesh.positions[j];
        return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
    };
    std::sort(order.begin(), order.end(), less);
    for (size_t begin = 0; begin < order.size();) {
        size_t end = begin + 1;
        while (end < order.size() && mesh.positions[order[end]] == mesh.positions[order[begin]]) {
            ++end;
        }
        vec3 sum(0.0f);
        for (size_t k = begin; k < end; ++k) sum += accum[order[k]];
        const vec3 smooth = is_valid_normal(sum) ? glm::normalize(sum) : vec3(0, 1, 0);
        for (size_t k = begin; k < end; ++k) {
            vec3& n = mesh.normals[order[k]];
            n = is_valid_normal(n) ? glm::normalize(n) : smooth;
        }
        begin = end;
    }
}

/// Sets each mesh's primitive types from its faces, as Assimp's post-processing steps assume
/// they are (importers of malformed files leave them claiming polygons that are not there).
/// Throws InputError for a face without vertices, which those steps cannot handle at all.
void restate_primitive_types(aiScene& scene, const std::string& path, const std::string& field) {
    for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
        aiMesh& mesh = *scene.mMeshes[m];
        unsigned types = 0;
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const unsigned n = mesh.mFaces[f].mNumIndices;
            if (n == 0) {
                throw InputError(path, field,
                                 "malformed mesh: face " + std::to_string(f) + " of mesh " + std::to_string(m) +
                                     " has no vertices");
            }
            types |= n == 1 ? aiPrimitiveType_POINT
                     : n == 2 ? aiPrimitiveType_LINE
                     : n == 3 ? aiPrimitiveType_TRIANGLE
                              : aiPrimitiveType_POLYGON;
        }
        mesh.mPrimitiveTypes = types;
    }
}

/// Leaves `importer` only the readers of the formats the project documents (OBJ, PLY, glTF
/// 2.0, STL, FBX). Assimp falls back to reading a file by its content when the reader for its
/// extension declines it, and some of its rarer readers overrun their buffers on what they are
/// handed then. The one list of the formats load_mesh reads (mesh_file_extensions asks the
/// readers kept here).
void keep_documented_readers(Assimp::Importer& importer) {
    static const char* const kKept[] = {"obj", "ply", "gltf", "glb", "stl", "fbx"};
    std::vector<Assimp::BaseImporter*> dropped;
    for (size_t i = 0; i < importer.GetImporterCount(); ++i) {
        const aiImporterDesc* info = importer.GetImporterInfo(i);
        std::istringstream extensions(info && info->mFileExtensions ? info->mFileExtensions : "");
        bool keep = false;
        for (std::string e; extensions >> e;)
            keep = keep || std::find(std::begin(kKept), std::end(kKept), e) != std::end(kKept);
        if (!keep) dropped.push_back(importer.GetImporter(i));
    }
    for (Assimp::BaseImporter* reader : dropped) {
        // The importer deletes only the readers it still holds.
        if (importer.UnregisterLoader(reader) == aiReturn_SUCCESS) delete reader;
    }
}

/// A number in the scene's metadata (FBX's global settings), whatever type the importer stored
/// it as; false when absent.
bool metadata_number(const aiScene& scene, const char* key, double& value) {
    const aiMetadata* meta = scene.mMetaData;
    if (!meta) return false;
    for (unsigned i = 0; i < meta->mNumProperties; ++i) {
        if (std::string(meta->mKeys[i].C_Str()) != key || !meta->mValues[i].mData) continue;
        const aiMetadataEntry& e = meta->mValues[i];
        switch (e.mType) {
            case AI_FLOAT: value = double(*static_cast<const float*>(e.mData)); return true;
            case AI_DOUBLE: value = *static_cast<const double*>(e.mData); return true;
            case AI_INT32: value = double(*static_cast<const int32_t*>(e.mData)); return true;
            case AI_UINT64: value = double(*static_cast<const uint64_t*>(e.mData)); return true;
            default: return false;
        }
    }
    return false;
}

/// The format's name as the importer recorded it ("glTF2 Importer", "Autodesk FBX Importer").
std::string source_format(const aiScene& scene) {
    const aiMetadata* meta = scene.mMetaData;
    aiString format;
    if (meta && meta->Get("SourceAsset_Format", format)) return format.C_Str();
    return "";
}

/// The triangles the scene's faces make once triangulated, before any post-processing step
/// allocates for them.
uint64_t triangle_count(const aiScene& scene) {
    uint64_t n = 0;
    for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
        const aiMesh* mesh = scene.mMeshes[m];
        for (unsigned f = 0; mesh && f < mesh->mNumFaces; ++f)
            if (mesh->mFaces[f].mNumIndices >= 3) n += mesh->mFaces[f].mNumIndices - 2;
    }
    return n;
}

/// Throws what Assimp failed with: out of memory as such (exit 1, with the mesh named), since
/// Assimp reports a failed allocation as text like any unreadable file; anything else as the
/// InputError "cannot read mesh".
[[noreturn]] void throw_read_failure(const Assimp::Importer& importer, const std::string& path,
                                     const std::string& field, uint64_t bytes) {
    bool out_of_memory = false;
    if (const std::exception_ptr failure = importer.GetException()) {
        try {
            std::rethrow_exception(failure);
        } catch (const std::bad_alloc&) {
            out_of_memory = true;
        } catch (...) {
        }
    }
    // The post-processing steps keep only the text of what they caught: a failed allocation's
    // text whole, since a reader's message quotes the file ("vn bad_alloc" is not one).
    const std::string error = importer.GetErrorString();
    if (out_of_memory || error == std::bad_alloc().what() || error == std::bad_array_new_length().what())
        throw OutOfMemory("the mesh of '" + shorten_path(path) + "' (a " + format_bytes(double(bytes)) + " file)");
    throw InputError(path, field, "cannot read mesh: " + error);
}

/// The first `n` bytes of the file (fewer if it is shorter).
std::string file_prefix(const std::string& path, size_t n) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes(n, '\0');
    in.read(bytes.data(), std::streamsize(n));
    bytes.resize(size_t(in.gcount()));
    return bytes;
}

}  // namespace

/// Keeps only the vertices the triangles use: the corners of dropped triangles (non-finite
/// ones among them) would otherwise still count in the mesh's bounds.
void drop_unused_vertices(TriangleMesh& m) {
    constexpr uint32_t kUnused = ~uint32_t(0);
    std::vector<uint32_t> remap(m.positions.size(), kUnused);
    for (const glm::uvec3& t : m.triangles)
        for (int k = 0; k < 3; ++k) remap[t[k]] = 0;
    if (std::find(remap.begin(), remap.end(), kUnused) == remap.end()) return;
    const bool normals = m.normals.size() == m.positions.size(), uvs = m.uvs.size() == m.positions.size();
    TriangleMesh out;
    for (size_t i = 0; i < m.positions.size(); ++i) {
        if (remap[i] == kUnused) continue;
        remap[i] = uint32_t(out.positions.size());
        out.positions.push_back(m.positions[i]);
        if (normals) out.normals.push_back(m.normals[i]);
        if (uvs) out.uvs.push_back(m.uvs[i]);
    }
    out.triangles = std::move(m.triangles);
    out.triangle_materials = std::move(m.triangle_materials);
    for (glm::uvec3& t : out.triangles) t = glm::uvec3(remap[t.x], remap[t.y], remap[t.z]);
    m = std::move(out);
}

const std::vector<std::string>& mesh_file_extensions() {
    static const std::vector<std::string> extensions = [] {
        Assimp::Importer importer;
        keep_documented_readers(importer);
        aiString list;  // "*.obj;*.ply;..."
        importer.GetExtensionList(list);
        std::vector<std::string> out;
        std::istringstream items(list.C_Str());
        for (std::string item; std::getline(items, item, ';');) {
            if (item.rfind("*.", 0) == 0) item = item.substr(2);
            std::transform(item.begin(), item.end(), item.begin(),
                           [](unsigned char ch) { return char(std::tolower(ch)); });
            if (!item.empty() && std::find(out.begin(), out.end(), item) == out.end())
                out.push_back(item);
        }
        std::sort(out.begin(), out.end());
        return out;
    }();
    return extensions;
}

LoadedMesh load_mesh(const std::string& path, const std::string& field) {
    const uint64_t bytes = check_input_file(path, field, "a mesh file", kMaxMeshFileBytes);
    const std::string ext = lower_extension(path);
    // Assimp picks its reader by content when the extension's reader declines the file, so a
    // file that starts like PLY or GLB is checked as one whatever its name.
    const std::string magic = file_prefix(path, 4);
    if (ext == ".ply" || magic.rfind("ply", 0) == 0) check_ply_header(path, field);
    if (ext == ".gltf" || ext == ".glb" || magic == "glTF") check_gltf_buffers(path, field);

    Assimp::Importer importer;
    keep_documented_readers(importer);
    // Every file Assimp opens goes through the same checks as the mesh file (the importer owns
    // the handler and deletes it). Its OBJ reader takes .obj files, and by content files whose
    // extension's reader declines them (not so the PLY, STL and FBX readers: they take every
    // file so named, and a glTF reader any JSON glTF).
    const bool obj_reader = ext == ".obj" || (ext != ".ply" && ext != ".stl" && ext != ".fbx" && !is_gltf_json(path));
    auto* io = new CheckedIOSystem(path, field, obj_reader);
    importer.SetIOHandler(io);
    // Missing normals are generated by fill_missing_normals rather than aiProcess_GenSmoothNormals:
    // Assimp's step assumes one vertex per face corner and gives wrong normals for indexed
    // formats (a PLY cube gets +-X normals on every corner).
    // Read and validate first, post-process after: a malformed file (a face indexing past its
    // vertices, primitive types that disagree with the faces) otherwise reaches Assimp's
    // post-processing steps, whose assertions abort the whole process.
    const aiScene* scene = importer.ReadFile(path, aiProcess_ValidateDataStructure);
    io->rethrow_refusal();  // a refused MTL or buffer fails the mesh even where Assimp went on
    if (!scene || !scene->mRootNode) throw_read_failure(importer, path, field, bytes);
    check_mesh_triangles(path, field, triangle_count(*scene));
    restate_primitive_types(const_cast<aiScene&>(*scene), path, field);
    scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
    if (!scene || !scene->mRootNode) throw_read_failure(importer, path, field, bytes);

    // FBX files say how many centimetres a unit is; the mesh is brought to metres here so that
    // a project's unit_scale means the same for every format.
    LoadedMesh result;
    const std::string format = source_format(*scene);
    double unit_cm = 0;
    if (format.find("FBX") != std::string::npos && metadata_number(*scene, "UnitScaleFactor", unit_cm)) {
        if (!(std::isfinite(unit_cm) && unit_cm > 0 && unit_cm < 1e12)) {
            throw InputError(path, field,
                             "malformed FBX: UnitScaleFactor (" + std::to_string(unit_cm) +
                                 " centimetres per unit) is not a positive number");
        }
        result.declared_unit_m = float(unit_cm * 0.01);
        double axis = 0, sign = 1;
        if (metadata_number(*scene, "UpAxis", axis) && axis >= 0 && axis <= 2) {
            metadata_number(*scene, "UpAxisSign", sign);
            result.declared_up = std::string(sign < 0 ? "-" : "") + "xyz"[int(axis)];
        }
    } else if (format.find("glTF") != std::string::npos) {
        result.declared_unit_m = 1;
    }

    Collector c{scene, {}, {}};
    result.materials =
        read_file_materials(*scene, path, result.embedded_textures, c.made_up, result.warnings);
    const float to_metres = unit_cm > 0 ? result.declared_unit_m : 1.0f;
    c.visit(*scene->mRootNode, glm::mat4(glm::mat3(to_metres)));
    if (c.total_triangles == 0) throw InputError(path, field, "mesh file contains no triangles");
    if (c.out.triangles.empty()) {
        throw InputError(path, field,
                         "degenerate mesh: all " + std::to_string(c.total_triangles) +
                             " triangles have zero area");
    }
    if (!c.any_uvs) c.out.uvs.clear();
    drop_unused_vertices(c.out);
    fill_missing_normals(c.out);

    result.mesh = std::move(c.out);
    result.mesh.bounds(result.bounds_lo, result.bounds_hi);
    keep_used_materials(result);
    result.dropped_degenerate = c.dropped;
    return result;
}

}  // namespace dp
