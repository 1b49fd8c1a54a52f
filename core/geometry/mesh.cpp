#include "geometry/mesh.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace dp {

void TriangleMesh::transform(const glm::mat4& m) {
    for (vec3& p : positions) p = vec3(m * glm::vec4(p, 1.0f));

    // The cofactor matrix of the linear part equals det * inverse-transpose. Scaling it by
    // sign(det) gives the inverse transpose up to a positive factor (removed by renormalising)
    // without dividing by a possibly tiny determinant.
    const glm::mat3 l(m);
    const float det = glm::determinant(l);
    glm::mat3 normal_matrix(glm::cross(l[1], l[2]), glm::cross(l[2], l[0]),
                            glm::cross(l[0], l[1]));
    if (det < 0.0f) normal_matrix = -normal_matrix;
    for (vec3& n : normals) {
        n = normal_matrix * n;
        float len = glm::length(n);
        if (len > 0.0f && std::isfinite(len)) n /= len;
    }

    // A mirroring transform reverses the winding; swap two corners so the geometric normal keeps
    // pointing the same way as the shading normals (outward stays outward).
    if (det < 0.0f) {
        for (glm::uvec3& t : triangles) std::swap(t.y, t.z);
    }
}

bool TriangleMesh::bounds(vec3& lo, vec3& hi) const {
    if (positions.empty()) return false;
    lo = hi = positions.front();
    for (const vec3& p : positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return true;
}

namespace {

/// Appends a quad (corners in counter-clockwise order seen from the side `n` points to) as
/// two triangles, with UVs (0,0), (1,0), (1,1), (0,1).
void add_quad(TriangleMesh& mesh, const vec3 (&corners)[4], const vec3& n) {
    const auto base = static_cast<unsigned>(mesh.positions.size());
    const vec2 uvs[4] = {vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 1)};
    for (int i = 0; i < 4; ++i) {
        mesh.positions.push_back(corners[i]);
        mesh.normals.push_back(n);
        mesh.uvs.push_back(uvs[i]);
    }
    mesh.triangles.emplace_back(base, base + 1, base + 2);
    mesh.triangles.emplace_back(base, base + 2, base + 3);
}

}  // namespace

TriangleMesh make_plane(float size_x, float size_z) {
    const float hx = 0.5f * size_x, hz = 0.5f * size_z;
    TriangleMesh mesh;
    // u runs along +X and v along -Z; the renderer reads texel row 0 (the image's top) at v = 0,
    // so the image's top edge lies along +Z (docs/reconstruction.md, "Texture layout"). Mesh
    // files are turned to this convention on load, built-in shapes are written in it.
    // The order (-x,+z), (+x,+z), (+x,-z), (-x,-z) is counter-clockwise seen from +Y.
    const vec3 corners[4] = {vec3(-hx, 0, hz), vec3(hx, 0, hz), vec3(hx, 0, -hz),
                             vec3(-hx, 0, -hz)};
    add_quad(mesh, corners, vec3(0, 1, 0));
    return mesh;
}

TriangleMesh make_box(const vec3& size) {
    const vec3 h = 0.5f * size;
    TriangleMesh mesh;
    mesh.positions.reserve(24);
    mesh.normals.reserve(24);
    mesh.uvs.reserve(24);
    mesh.triangles.reserve(12);
    // Each face is spanned by tangents (u, v) with cross(u, v) == n, which makes the corner order
    // -u-v, +u-v, +u+v, -u+v counter-clockwise seen from outside.
    struct Face {
        vec3 n, u, v;
    };
    const Face faces[6] = {
        {vec3(1, 0, 0), vec3(0, 0, -1), vec3(0, 1, 0)},
        {vec3(-1, 0, 0), vec3(0, 0, 1), vec3(0, 1, 0)},
        {vec3(0, 1, 0), vec3(1, 0, 0), vec3(0, 0, -1)},
        {vec3(0, -1, 0), vec3(1, 0, 0), vec3(0, 0, 1)},
        {vec3(0, 0, 1), vec3(1, 0, 0), vec3(0, 1, 0)},
        {vec3(0, 0, -1), vec3(-1, 0, 0), vec3(0, 1, 0)},
    };
    for (const Face& f : faces) {
        const vec3 c = f.n * h, u = f.u * h, v = f.v * h;
        const vec3 corners[4] = {c - u - v, c + u - v, c + u + v, c - u + v};
        add_quad(mesh, corners, f.n);
    }
    return mesh;
}

TriangleMesh make_uv_sphere(float radius, int segments, int rings) {
    segments = std::max(segments, 3);
    rings = std::max(rings, 2);
    const auto seg = static_cast<unsigned>(segments);
    TriangleMesh mesh;

    // theta is the polar angle from +Y, phi the azimuth; v = 1 at the north pole.
    auto add_vertex = [&](const vec3& dir, float u, float v) {
        mesh.positions.push_back(radius * dir);
        mesh.normals.push_back(dir);
        mesh.uvs.emplace_back(u, v);
    };
    // Each pole gets one vertex per segment so every fan triangle has its own u at the tip.
    const unsigned north = 0;
    for (unsigned j = 0; j < seg; ++j) add_vertex(vec3(0, 1, 0), (float(j) + 0.5f) / segments, 1);
    // Interior rings repeat the seam column (j == segments) so u is continuous across it.
    const unsigned ring0 = seg;
    for (int r = 1; r < rings; ++r) {
        const float theta = kPi * float(r) / float(rings);
        const float st = std::sin(theta), ct = std::cos(theta);
        for (unsigned j = 0; j <= seg; ++j) {
            const float phi = 2.0f * kPi * float(j) / float(segments);
            const float sp = j == seg ? 0.0f : std::sin(phi), cp = j == seg ? 1.0f : std::cos(phi);
            add_vertex(vec3(st * cp, ct, st * sp), float(j) / segments, 1.0f - float(r) / rings);
        }
    }
    const unsigned south = static_cast<unsigned>(mesh.positions.size());
    for (unsigned j = 0; j < seg; ++j) add_vertex(vec3(0, -1, 0), (float(j) + 0.5f) / segments, 0);

    auto ring = [&](int r, unsigned j) { return ring0 + unsigned(r - 1) * (seg + 1) + j; };
    mesh.triangles.reserve(2 * seg * unsigned(rings - 1));
    // With phi growing from +X towards +Z, the orders below are counter-clockwise from outside.
    for (unsigned j = 0; j < seg; ++j) {
        mesh.triangles.emplace_back(north + j, ring(1, j + 1), ring(1, j));
    }
    for (int r = 1; r + 1 < rings; ++r) {
        for (unsigned j = 0; j < seg; ++j) {
            const unsigned a = ring(r, j), b = ring(r, j + 1);
            const unsigned c = ring(r + 1, j + 1), d = ring(r + 1, j);
            mesh.triangles.emplace_back(a, b, c);
            mesh.triangles.emplace_back(a, c, d);
        }
    }
    for (unsigned j = 0; j < seg; ++j) {
        mesh.triangles.emplace_back(south + j, ring(rings - 1, j), ring(rings - 1, j + 1));
    }
    return mesh;
}

}  // namespace dp
