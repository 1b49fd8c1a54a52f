#include "render/photon_map.h"

#include <cmath>

namespace dp {

namespace {
// Surfaces count as facing the same way within ~45 degrees: keeps both sides of a thin wall
// apart while tolerating interpolated normals.
constexpr float kNormalAgreement = 0.7f;
}

void PhotonMap::cell_of(const vec3& p, int64_t& cx, int64_t& cy, int64_t& cz) const {
    cx = int64_t(std::floor(double(p.x) * inv_cell_));
    cy = int64_t(std::floor(double(p.y) * inv_cell_));
    cz = int64_t(std::floor(double(p.z) * inv_cell_));
}

uint32_t PhotonMap::bucket_of(int64_t cx, int64_t cy, int64_t cz) const {
    uint64_t h = uint64_t(cx) * 73856093ull ^ uint64_t(cy) * 19349663ull ^ uint64_t(cz) * 83492791ull;
    h ^= h >> 29;
    h *= 0xbf58476d1ce4e5b9ull;
    h ^= h >> 32;
    return uint32_t(h) & bucket_mask_;
}

void PhotonMap::build(std::vector<Photon> photons, float radius) {
    radius_ = radius;
    inv_cell_ = 1.0f / (2.0f * radius);
    size_t buckets = 1024;
    while (buckets < 2 * photons.size()) buckets <<= 1;
    bucket_mask_ = uint32_t(buckets - 1);
    // Counting sort by bucket: stable, so the order (and the double sums) stay deterministic.
    std::vector<uint32_t> key(photons.size());
    bucket_start_.assign(buckets + 1, 0);
    for (size_t i = 0; i < photons.size(); ++i) {
        int64_t cx, cy, cz;
        cell_of(photons[i].position, cx, cy, cz);
        key[i] = bucket_of(cx, cy, cz);
        ++bucket_start_[key[i] + 1];
    }
    for (size_t b = 0; b < buckets; ++b) bucket_start_[b + 1] += bucket_start_[b];
    std::vector<uint32_t> cursor(bucket_start_.begin(), bucket_start_.end() - 1);
    photons_.resize(photons.size());
    for (size_t i = 0; i < photons.size(); ++i) photons_[cursor[key[i]]++] = photons[i];
}

dvec3 PhotonMap::gather(const vec3& x, const vec3& normal) const {
    dvec3 sum(0);
    if (photons_.empty()) return sum;
    // The 2x2x2 block of cells nearest to x covers the whole sphere of radius r.
    double fx = double(x.x) * inv_cell_ - 0.5, fy = double(x.y) * inv_cell_ - 0.5, fz = double(x.z) * inv_cell_ - 0.5;
    int64_t x0 = int64_t(std::floor(fx)), y0 = int64_t(std::floor(fy)), z0 = int64_t(std::floor(fz));
    float r2 = radius_ * radius_;
    uint32_t visited[8];
    int nvisited = 0;
    for (int dz = 0; dz <= 1; ++dz)
        for (int dy = 0; dy <= 1; ++dy)
            for (int dx = 0; dx <= 1; ++dx) {
                uint32_t b = bucket_of(x0 + dx, y0 + dy, z0 + dz);
                bool seen = false;  // two cells may share a bucket: count its photons once
                for (int k = 0; k < nvisited; ++k) seen |= visited[k] == b;
                if (seen) continue;
                visited[nvisited++] = b;
                for (uint32_t i = bucket_start_[b]; i < bucket_start_[b + 1]; ++i) {
                    const Photon& p = photons_[i];
                    vec3 d = p.position - x;
                    if (glm::dot(d, d) > r2) continue;
                    if (glm::dot(p.normal, normal) < kNormalAgreement) continue;
                    sum += dvec3(p.flux);
                }
            }
    return sum;
}

bool PhotonMap::reaches(const vec3& x) const {
    if (photons_.empty()) return false;
    int64_t cx, cy, cz;
    cell_of(x, cx, cy, cz);
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                uint32_t b = bucket_of(cx + dx, cy + dy, cz + dz);
                if (bucket_start_[b + 1] > bucket_start_[b]) return true;
            }
    return false;
}

}  // namespace dp
