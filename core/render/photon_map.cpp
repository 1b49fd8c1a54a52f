#include "render/photon_map.h"

#include <cmath>
#include <utility>

#include "base/rng.h"

namespace dp {

namespace {
// Surfaces count as facing the same way within ~45 degrees: keeps both sides of a thin wall
// apart while tolerating interpolated normals.
constexpr float kNormalAgreement = 0.7f;
}  // namespace

uint64_t PhotonMap::hash_cell(const glm::i64vec3& c) {
    return mix64(uint64_t(c.x) * 0x9e3779b97f4a7c15ull ^ mix64(uint64_t(c.y) + 0x632be59bd9b4e019ull) ^
                 (uint64_t(c.z) << 1));
}

const PhotonMap::Cell* PhotonMap::find(const glm::i64vec3& cell) const {
    if (table_.empty()) return nullptr;
    for (uint64_t slot = hash_cell(cell) & table_mask_;; slot = (slot + 1) & table_mask_) {
        const Cell& c = table_[slot];
        if (!c.used) return nullptr;
        if (c.cell == cell) return &c;
    }
}

namespace {

/// Stable LSD radix sort of `index` by cell, 8 bits a pass: x first, then y, then z, each over
/// the bits its offset from the lowest cell uses. Works for any scene extent.
void sort_by_cell(const std::vector<glm::i64vec3>& cells, glm::i64vec3 lo, glm::i64vec3 hi,
                  std::vector<uint32_t>& index) {
    std::vector<uint32_t> next(index.size());
    for (int axis = 0; axis < 3; ++axis) {
        const uint64_t range = uint64_t(hi[axis] - lo[axis]);
        for (int shift = 0; shift < 64 && (range >> shift) != 0; shift += 8) {
            auto digit = [&](uint32_t i) { return (uint64_t(cells[i][axis] - lo[axis]) >> shift) & 0xFF; };
            size_t count[257] = {};
            for (uint32_t i : index) ++count[digit(i) + 1];
            for (int d = 0; d < 256; ++d) count[d + 1] += count[d];
            for (uint32_t i : index) next[count[digit(i)]++] = i;
            index.swap(next);
        }
    }
}

}  // namespace

void PhotonMap::build(std::vector<Photon> photons, float radius) {
    radius_ = radius;
    inv_cell_ = 1.0 / (2.0 * double(radius));
    const size_t n = photons.size();
    photons_.clear();
    table_.clear();
    if (n == 0) return;
    std::vector<glm::i64vec3> cells(n);
    glm::i64vec3 lo(INT64_MAX), hi(INT64_MIN);
    for (size_t i = 0; i < n; ++i) {
        cells[i] = cell_of(photons[i].position);
        lo = glm::min(lo, cells[i]);
        hi = glm::max(hi, cells[i]);
    }
    std::vector<uint32_t> index(n);
    for (size_t i = 0; i < n; ++i) index[i] = uint32_t(i);
    // Stable: photons of one cell keep their emission order, so sums are deterministic.
    sort_by_cell(cells, lo, hi, index);
    photons_.resize(n);
    size_t distinct = 0;
    for (size_t i = 0; i < n; ++i) {
        photons_[i] = photons[index[i]];
        distinct += (i == 0 || cells[index[i]] != cells[index[i - 1]]);
    }
    size_t size = 16;
    while (size < 2 * distinct) size <<= 1;
    table_.assign(size, Cell{});
    table_mask_ = size - 1;
    for (size_t i = 0; i < n;) {
        const glm::i64vec3& c = cells[index[i]];
        size_t j = i;
        while (j < n && cells[index[j]] == c) ++j;
        uint64_t slot = hash_cell(c) & table_mask_;
        while (table_[slot].used) slot = (slot + 1) & table_mask_;
        table_[slot] = Cell{c, uint32_t(i), uint32_t(j), true};
        i = j;
    }
}

dvec3 PhotonMap::gather(const vec3& x, const vec3& normal) const {
    dvec3 sum(0);
    if (photons_.empty()) return sum;
    // The 2x2x2 block of cells nearest to x covers the whole sphere of radius r.
    int64_t x0 = int64_t(std::floor(x.x * inv_cell_ - 0.5));
    int64_t y0 = int64_t(std::floor(x.y * inv_cell_ - 0.5));
    int64_t z0 = int64_t(std::floor(x.z * inv_cell_ - 0.5));
    const float r2 = radius_ * radius_;
    for (int dz = 0; dz <= 1; ++dz)
        for (int dy = 0; dy <= 1; ++dy)
            for (int dx = 0; dx <= 1; ++dx) {
                const Cell* c = find(glm::i64vec3(x0 + dx, y0 + dy, z0 + dz));
                if (!c) continue;
                for (uint32_t i = c->begin; i < c->end; ++i) {
                    const Photon& p = photons_[i];
                    vec3 d = p.position - x;
                    if (glm::dot(d, d) > r2) continue;
                    if (glm::dot(p.normal, normal) < kNormalAgreement) continue;
                    sum += dvec3(p.flux);
                }
            }
    return sum;
}

glm::i64vec3 PhotonMap::cell_of(const vec3& x) const {
    return glm::i64vec3(int64_t(std::floor(x.x * inv_cell_)), int64_t(std::floor(x.y * inv_cell_)),
                        int64_t(std::floor(x.z * inv_cell_)));
}

bool PhotonMap::reaches_cell(const glm::i64vec3& c) const {
    if (photons_.empty()) return false;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (find(c + glm::i64vec3(dx, dy, dz))) return true;
    return false;
}

}  // namespace dp
