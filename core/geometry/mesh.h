#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "base/math.h"

namespace dp {

/// No material from the mesh file for a triangle (TriangleMesh::triangle_materials).
inline constexpr uint32_t kNoFileMaterial = ~uint32_t(0);

/// Indexed triangle mesh. `normals` and `uvs` are either empty or one per position. UVs follow
/// the renderer's convention: texel row 0 (the top of the image) at v = 0 (Surface::reflectance_at).
struct TriangleMesh {
    std::vector<vec3> positions;
    std::vector<vec3> normals;
    std::vector<vec2> uvs;
    std::vector<glm::uvec3> triangles;
    /// Empty, or per triangle the index of its material among the file's
    /// (LoadedMesh::materials); kNoFileMaterial where the file gives it none.
    std::vector<uint32_t> triangle_materials;

    size_t triangle_count() const { return triangles.size(); }
    /// Applies an affine transform (normals with the inverse transpose, renormalised).
    void transform(const glm::mat4& m);
    /// Axis-aligned bounds; returns false for an empty mesh.
    bool bounds(vec3& lo, vec3& hi) const;
};

/// Plane of size x by z in local XZ centred at the origin, normal +Y, UVs over [0,1]^2.
TriangleMesh make_plane(float size_x, float size_z);
/// Axis-aligned box centred at the origin, outward normals, per-face UVs, 24 vertices.
TriangleMesh make_box(const vec3& size);
/// UV sphere with smooth normals (used when a sphere is scaled non-uniformly).
TriangleMesh make_uv_sphere(float radius, int segments = 96, int rings = 48);

/// A texture a mesh file's material names: a file (its path resolved against the mesh file's
/// folder) or a texture stored inside the mesh file (an index into LoadedMesh::embedded_textures).
struct FileTexture {
    std::string path;
    int embedded = -1;
    bool empty() const { return path.empty() && embedded < 0; }
    bool operator==(const FileTexture&) const = default;
};

/// A material as a mesh file states it (glTF's metallic-roughness, MTL's Kd and map_Kd, FBX's
/// diffuse colour), before it is mapped onto the project's kinds (material_from_file in
/// core/assets).
struct FileMaterial {
    std::string name;
    vec3 colour{1.0f};          ///< glTF base colour, MTL Kd, FBX diffuse colour (linear)
    std::string texture;        ///< colour texture's path, resolved against the mesh file's folder
    int embedded_texture = -1;  ///< or an index into LoadedMesh::embedded_textures
    /// glTF multiplies its base colour texture by `colour`; MTL and FBX textures replace it.
    bool texture_times_colour = false;
    float metallic = 0;      ///< glTF metallicFactor
    float transmission = 0;  ///< glTF KHR_materials_transmission
    float ior = 0;           ///< glTF KHR_materials_ior; 0 where the file gives none
    /// glTF roughnessFactor or MTL Pr; -1 where the file gives none (the material is then
    /// mapped by today's thresholds, not onto the principled material).
    float roughness = -1;
    /// glTF's metallicRoughnessTexture: linear, roughness in green and metallic in blue, each
    /// multiplying its factor. Empty for none (MTL's map_Pr and map_Pm are not read).
    FileTexture metallic_roughness;
    /// A tangent-space normal map (glTF's normalTexture, MTL's norm): linear, +X along u, +Y
    /// towards the top of the image (OpenGL's and glTF's convention), its X and Y scaled by
    /// `normal_scale`. Empty for none.
    FileTexture normal;
    float normal_scale = 1;
    bool operator==(const FileMaterial&) const = default;
};

/// A texture stored inside a mesh file (GLB, FBX): its encoded bytes as they are (PNG, JPEG...).
struct EmbeddedTexture {
    std::string format;  ///< the format Assimp names ("png", "jpg"), "" if unknown
    std::vector<unsigned char> bytes;
};

/// Result of loading a mesh file: the mesh plus how many degenerate (zero-area) triangles were
/// dropped, and what the file says of its units and axes.
struct LoadedMesh {
    TriangleMesh mesh;
    size_t dropped_degenerate = 0;
    vec3 bounds_lo{0.0f}, bounds_hi{0.0f};  ///< the mesh's bounds, in the file's frame
    /// Metres per unit as the file declares it, 0 where it declares none (OBJ, PLY, STL). An FBX
    /// file's UnitScaleFactor (centimetres per unit) is applied on load, so its mesh is in metres
    /// whatever unit it was modelled in; glTF 2.0 is in metres by its specification.
    float declared_unit_m = 0;
    /// The up axis an FBX file declares ("y", "z", "-y", "-z"; also "x", "-x"), "" where the file
    /// declares none. Informative: the mesh is not turned.
    std::string declared_up;
    /// The materials the triangles use (TriangleMesh::triangle_materials indexes them); empty
    /// when the file gives none (PLY, STL, an OBJ without MTL).
    std::vector<FileMaterial> materials;
    std::vector<EmbeddedTexture> embedded_textures;
    /// What could not be read of the file's materials (a texture stored uncompressed...).
    std::vector<std::string> warnings;
    /// Some triangle has a material from the file.
    bool has_file_materials() const { return !materials.empty(); }
};

/// Loads every mesh in an OBJ, PLY, glTF 2.0, STL or FBX file through Assimp (node transforms applied),
/// merged into one mesh. The file's UVs (v = 0 at the bottom of the image, as Blender and OpenGL
/// have it) are turned to the renderer's (v = 0 at the top): u, 1 - v. Throws InputError naming the file (and `field`) when the file is missing,
/// unreadable, or has no non-degenerate triangle.
LoadedMesh load_mesh(const std::string& path, const std::string& field = "");

/// The file name extensions load_mesh reads, lower case without the dot, sorted: those of the
/// Assimp readers it keeps (OBJ, PLY, glTF 2.0, STL, FBX), as Assimp itself lists them, so that
/// what the studio offers is exactly what the loader takes.
const std::vector<std::string>& mesh_file_extensions();

}  // namespace dp
