#pragma once
#include <string>
#include <vector>

#include "base/math.h"

namespace dp {

/// Indexed triangle mesh. `normals` and `uvs` are either empty or one per position. UVs follow
/// the renderer's convention: texel row 0 (the top of the image) at v = 0 (Surface::reflectance_at).
struct TriangleMesh {
    std::vector<vec3> positions;
    std::vector<vec3> normals;
    std::vector<vec2> uvs;
    std::vector<glm::uvec3> triangles;

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
};

/// Loads every mesh in an OBJ, PLY, glTF 2.0, STL or FBX file through Assimp (node transforms applied),
/// merged into one mesh. The file's UVs (v = 0 at the bottom of the image, as Blender and OpenGL
/// have it) are turned to the renderer's (v = 0 at the top): u, 1 - v. Throws InputError naming the file (and `field`) when the file is missing,
/// unreadable, or has no non-degenerate triangle.
LoadedMesh load_mesh(const std::string& path, const std::string& field = "");

}  // namespace dp
