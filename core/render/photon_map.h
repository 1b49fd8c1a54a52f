#pragma once
#include <cstdint>
#include <vector>

#include "base/math.h"

namespace dp {

/// What a photon carries: light the virtual objects add (positive flux, after reflection or
/// refraction by them) or light they take away from the real surface behind them (a shadow
/// photon, negative flux; it dies when it meets a virtual object again).
enum class PhotonKind { Light, Shadow };

/// A stored photon: signed RGB flux (negative for shadow photons) and the normal of the side
/// of the surface it landed on.
struct Photon {
    vec3 position;
    vec3 flux;
    vec3 normal;
};

/// Signed photons in a spatial hash grid whose cells are one gather diameter wide, so a gather
/// of radius r touches at most 2x2x2 cells. Photons are radix-sorted by cell; an open-addressing
/// table keyed by the exact cell finds a cell's run, so empty cells are known to be empty.
class PhotonMap {
public:
    PhotonMap() = default;
    /// Builds the grid for gathers of radius `radius`.
    void build(std::vector<Photon> photons, float radius);

    size_t size() const { return photons_.size(); }
    bool empty() const { return photons_.empty(); }
    float radius() const { return radius_; }
    const std::vector<Photon>& photons() const { return photons_; }

    /// Sum of the flux of photons within `radius` of x on surfaces facing like `normal`.
    dvec3 gather(const vec3& x, const vec3& normal) const;
    /// True if some cell within one cell of x's holds a photon: pixels for which this is false
    /// everywhere can skip the gather.
    bool reaches(const vec3& x) const { return reaches_cell(cell_of(x)); }
    /// The integer cell of a point, so that callers can reuse reaches_cell() for points that
    /// share a cell (neighbouring pixels often do).
    glm::i64vec3 cell_of(const vec3& x) const;
    bool reaches_cell(const glm::i64vec3& cell) const;
    /// Edge length of a grid cell: one gather diameter.
    double cell_size() const { return 1.0 / inv_cell_; }
    /// Calls f(centre) once for every cell that holds a photon (order unspecified).
    template <class F>
    void for_each_cell(F&& f) const {
        const double size = cell_size();
        auto centre = [&](const glm::i64vec3& c) { return vec3((dvec3(c) + 0.5) * size); };
        for (const Cell& c : table_) {
            if (c.key == kEmpty) continue;
            glm::i64vec3 last = cell_of(photons_[c.begin].position);
            f(centre(last));
            if (exact_) continue;  // wrapped keys: one run may hold several distant cells
            for (uint32_t i = c.begin + 1; i < c.end; ++i) {
                const glm::i64vec3 cell = cell_of(photons_[i].position);
                if (cell != last) f(centre(cell)), last = cell;
            }
        }
    }

private:
    struct Cell {
        uint64_t key = kEmpty;
        uint32_t begin = 0, end = 0;
    };
    static constexpr uint64_t kEmpty = ~uint64_t(0);
    /// One 64-bit key per cell (see build()); kEmpty for cells outside the photons' range.
    uint64_t key_of(const glm::i64vec3& cell) const;
    const Cell* find(const glm::i64vec3& cell) const;

    std::vector<Photon> photons_;  ///< sorted by cell key (ties keep emission order)
    std::vector<Cell> table_;      ///< power-of-two size, linear probing
    uint64_t table_mask_ = 0;
    bool exact_ = true;  ///< keys are exact cell offsets (else wrapped coordinates)
    glm::i64vec3 lo_{0}, span_{0};
    int shift_y_ = 0, shift_z_ = 0;
    float radius_ = 0;
    double inv_cell_ = 0;
};

}  // namespace dp
