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

uint64_t PhotonMap::key_of(const glm::i64vec3& c) const {
    if (!exact_) {
        // Wrapped 21-bit coordinates: distant cells may share a key (and a run); every
        // photon's distance is checked, so that costs time, never correctness.
        const int64_t m = (int64_t(1) << 21) - 1;
        return uint64_t(c.x & m) | (uint64_t(c.y & m) << 21) | (uint64_t(c.z & m) << 42);
    }
    glm::i64vec3 o = c - lo_;
    if (o.x < 0 || o.y < 0 || o.z < 0 || o.x > span_.x || o.y > span_.y || o.z > span_.z) return kEmpty;
    return uint64_t(o.x) | (uint64_t(o.y) << shift_y_) | (uint64_t(o.z) << shift_z_);
}

const PhotonMap::Cell* PhotonMap::find(const glm::i64vec3& cell) const {
    if (table_.empty()) return nullptr;
    const uint64_t key = key_of(cell);
    if (key == kEmpty) return nullptr;
    for (uint64_t slot = mix64(key) & table_mask_;; slot = (slot + 1) & table_mask_) {
        const Cell& c = table_[slot];
        if (c.key == key) return &c;
        if (c.key == kEmpty) return nullptr;
    }
}

namespace {

int bits_for(uint64_t v) {
    int b = 0;
    while (b < 64 && (v >> b) != 0) ++b;
    return b;
}

/// Stable LSD radix sort of (key, index) pairs by key, 8 bits a pass over `bits` bits.
void radix_sort(std::vector<uint64_t>& keys, std::vector<uint32_t>& index, int bits) {
    std::vector<uint64_t> keys2(keys.size());
    std::vector<uint32_t> index2(index.size());
    for (int shift = 0; shift < bits; shift += 8) {
        size_t count[257] = {};
        for (uint64_t k : keys) ++count[((k >> shift) & 0xFF) + 1];
        for (int d = 0; d < 256; ++d) count[d + 1] += count[d];
        for (size_t i = 0; i < keys.size(); ++i) {
            size_t at = count[(keys[i] >> shift) & 0xFF]++;
            keys2[at] = keys[i];
            index2[at] = index[i];
        }
        keys.swap(keys2);
        index.swap(index2);
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
    glm::i64vec3 lo(INT64_MAX), hi(INT64_MIN);
    for (const Photon& p : photons) {
        glm::i64vec3 c = cell_of(p.position);
        lo = glm::min(lo, c);
        hi = glm::max(hi, c);
    }
    // Exact keys (offsets from the lowest cell) when they fit in 63 bits: the usual case.
    lo_ = lo;
    span_ = hi - lo;
    const int bx = bits_for(uint64_t(span_.x)), by = bits_for(uint64_t(span_.y)), bz = bits_for(uint64_t(span_.z));
    exact_ = bx + by + bz <= 63;
    shift_y_ = bx;
    shift_z_ = bx + by;
    std::vector<uint64_t> keys(n);
    std::vector<uint32_t> index(n);
    for (size_t i = 0; i < n; ++i) {
        keys[i] = key_of(cell_of(photons[i].position));
        index[i] = uint32_t(i);
    }
    // Stable: photons of one cell keep their emission order, so sums are deterministic.
    radix_sort(keys, index, exact_ ? bx + by + bz : 63);
    photons_.resize(n);
    size_t distinct = 0;
    for (size_t i = 0; i < n; ++i) {
        photons_[i] = photons[index[i]];
        distinct += (i == 0 || keys[i] != keys[i - 1]);
    }
    size_t size = 16;
    while (size < 2 * distinct) size <<= 1;
    table_.assign(size, Cell{});
    table_mask_ = size - 1;
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j < n && keys[j] == keys[i]) ++j;
        uint64_t slot = mix64(keys[i]) & table_mask_;
        while (table_[slot].key != kEmpty) slot = (slot + 1) & table_mask_;
        table_[slot] = Cell{keys[i], uint32_t(i), uint32_t(j)};
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
