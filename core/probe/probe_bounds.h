#pragma once
#include <vector>

#include "base/math.h"
#include "probe/probe.h"

namespace dp {

/// The brightest luminance of a probe within a cone of directions, from a coarse grid of
/// per-cell maxima: it tells how much light an object could block at a point from the cone it
/// subtends there, without sampling. Conservative: every probe pixel whose band overlaps the
/// cone counts.
class ProbeMaxGrid {
public:
    ProbeMaxGrid() = default;
    /// `columns` x `rows` cells over the lat-long map (each a block of probe pixels).
    explicit ProbeMaxGrid(const Probe& probe, int columns = 64, int rows = 32);

    /// Largest pixel luminance (radiance times the probe's gain) within `half_angle` radians of
    /// the world direction `axis` (unit length).
    float max_in_cone(const vec3& axis, float half_angle) const;
    float global_max() const { return global_max_; }

private:
    float cell(int column, int row) const { return cells_[size_t(row) * columns_ + column]; }

    const Probe* probe_ = nullptr;
    int columns_ = 0, rows_ = 0;
    std::vector<float> cells_;
    std::vector<float> row_max_;      ///< per cell row
    std::vector<double> row_theta_;   ///< rows + 1 polar angles: where each cell row starts
    float global_max_ = 0;
};

}  // namespace dp
