#include "render/photon_map.h"

#include <tbb/parallel_sort.h>

#include <cmath>
#include <utility>

#include "base/rng.h"

namespace dp {

namespace {
// Surfaces count as facing the same way within ~45 degrees: keeps both sides of a thin wall
// apart while tolerating interpolated normals.
constexpr float kNormalAgreement = 0.7f;
// 21 bits per axis; cells further apart than 2^21 alias, which costs time, never correctness
// (every photon's distance is checked).
constexpr int64_t kAxisMask = (int64_t(1) << 21) - 1;
}  // namespace

uint64_t PhotonMap::cell_key(int64_t cx, int64_t cy, int64_t cz) {
    return uint64_t(cx & kAxisMask) | (uint64_t(cy & kAxisMask) << 21) | (uint64_t(cz & kAxisMask) << 42);
}

const PhotonMap::Cell* PhotonMap::find(uint64_t key) const {
    if (table_.empty()) return nullptr;
    for (uint64_t slot = mix64(key) & table_mask_;; slot = (slot + 1) & table_mask_) {
        const Cell& c = table_[slot];
        if (c.key == key) return &c;
        if (c.key == kEmpty) return nullptr;
    }
}

void PhotonMap::build(std::vector<Photon> photons, float radius) {
    radius_ = radius;
    inv_cell_ = 1.0 / (2.0 * double(radius));
    std::vector<std::pair<uint64_t, uint32_t>> order(photons.size());
    for (size_t i = 0; i < photons.size(); ++i) {
        const vec3& p = photons[i].position;
        order[i] = {cell_key(int64_t(std::floor(p.x * inv_cell_)), int64_t(std::floor(p.y * inv_cell_)),
                             int64_t(std::floor(p.z * inv_cell_))),
                    uint32_t(i)};
    }
    // (key, index) pairs are unique, so the sorted order is the same for any thread count.
    tbb::parallel_sort(order.begin(), order.end());
    photons_.resize(photons.size());
    size_t cells = 0;
    for (size_t i = 0; i < order.size(); ++i) {
        photons_[i] = photons[order[i].second];
        cells += (i == 0 || order[i].first != order[i - 1].first);
    }
    size_t size = 16;
    while (size < 2 * cells) size <<= 1;
    table_.assign(size, Cell{});
    table_mask_ = size - 1;
    for (size_t i = 0; i < order.size();) {
        size_t j = i;
        while (j < order.size() && order[j].first == order[i].first) ++j;
        uint64_t slot = mix64(order[i].first) & table_mask_;
        while (table_[slot].key != kEmpty) slot = (slot + 1) & table_mask_;
        table_[slot] = Cell{order[i].first, uint32_t(i), uint32_t(j)};
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
                const Cell* c = find(cell_key(x0 + dx, y0 + dy, z0 + dz));
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
                if (find(cell_key(c.x + dx, c.y + dy, c.z + dz))) return true;
    return false;
}

}  // namespace dp
