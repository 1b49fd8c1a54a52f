#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "base/math.h"
#include "image/image.h"
#include "probe/huge_pages.h"
#include "probe/latlong_table.h"

namespace dp {

/// Lat-long convention (documented in docs/project-format.md): pixel (i, j) of a W x H map
/// covers u in [i, i+1)/W and v in [j, j+1)/H; theta = pi v is the polar angle from +Y and
/// phi = 2 pi (u - 1/2); the probe-space direction is
///   (sin theta sin phi, cos theta, -sin theta cos phi),
/// so the image centre looks along -Z, u = 3/4 along +X, and the top row is straight up.
vec3 latlong_direction(float u, float v);
/// The direction through the centre of pixel `pixel` (row-major) of a width x height map.
vec3 latlong_pixel_direction(size_t pixel, int width, int height);
/// The exact solid angle of a pixel in row `row` of a width x height map.
double latlong_row_solid_angle(int row, int width, int height);
/// Inverse of latlong_direction: u, v in [0, 1).
vec2 latlong_uv(const vec3& dir);
/// Row-major index of the pixel of a width x height lat-long map that contains the probe-space
/// direction `dir` (need not be unit length).
size_t latlong_pixel(const vec3& dir, int width, int height);

/// Alias table (Walker/Vose) over non-negative weights: O(1) sampling with the exact pmf.
/// Negative and non-finite weights count as 0. When every weight is 0 (or there are none),
/// total() is 0, pmf() is 0 for every index and sample() returns 0.
class AliasTable {
public:
    AliasTable() = default;
    explicit AliasTable(const std::vector<double>& weights);
    /// Picks an index with probability weight/sum from one uniform number in [0,1).
    size_t sample(double u) const;
    /// As sample(u), and also returns in `u_remapped` the part of `u` that picking the index did
    /// not use, rescaled to a fresh uniform number in [0, 1).
    size_t sample(double u, double* u_remapped) const;
    double pmf(size_t i) const { return pmf_[i]; }
    double total() const { return total_; }
    size_t size() const { return pmf_.size(); }
    /// Column i of the table: sample() keeps index i when the fraction of u within the column
    /// is below prob(i), and returns alias(i) otherwise.
    double prob(size_t i) const { return prob_[i]; }
    uint32_t alias(size_t i) const { return alias_[i]; }

private:
    std::vector<double> pmf_, prob_;
    std::vector<uint32_t> alias_;
    double total_ = 0;
};

/// A direction drawn from the probe with its radiance and solid-angle pdf.
struct ProbeSample {
    vec3 dir;        ///< world space, towards the probe
    vec3 radiance;   ///< scaled radiance arriving from dir
    float pdf = 0;   ///< per unit solid angle
    size_t pixel = 0;
};

/// The distant light: a lat-long HDR map with a world rotation and a per-channel scale (the
/// project's intensity times its white balance).
/// Sampling is proportional to the luminance of each pixel's flux L_j * Omega_j, uniform in
/// solid angle within the pixel.
class Probe {
public:
    /// A black probe of no pixels.
    Probe();
    /// `rotation` maps probe space to world space; `gain` scales radiance per channel. Pixels
    /// with a non-finite channel are set to 0; pixels of negative luminance are never sampled.
    Probe(Image latlong, const glm::mat3& rotation, const vec3& gain);
    /// As above, sharing `latlong` rather than copying it where it holds no NaN/Inf (a decoded
    /// probe never does): several probes of one file (rotations, gains) and the file's cache then
    /// hold one copy of its pixels.
    Probe(std::shared_ptr<const Image> latlong, const glm::mat3& rotation, const vec3& gain);
    /// The same scale on every channel.
    Probe(Image latlong, const glm::mat3& rotation, float intensity)
        : Probe(std::move(latlong), rotation, vec3(intensity)) {}

    /// The lat-long map as given (before the gain).
    const Image& image() const { return *image_; }
    int width() const { return image_->width(); }
    int height() const { return image_->height(); }

    /// Radiance arriving from world direction `dir` (nearest pixel; piecewise constant).
    vec3 radiance(const vec3& dir) const;
    /// Solid angle of a pixel in row j: the exact area of its band on the sphere,
    /// (2 pi / W)(cos theta_top - cos theta_bottom), so that the pixels sum to 4 pi.
    double pixel_solid_angle(int row) const;
    /// Scaled radiance of pixel index (row-major).
    vec3 pixel_radiance(size_t pixel) const;

    /// u.x picks the pixel, u.y and u.z the point inside it. u.y also refines u.x below float
    /// precision so that large maps are sampled with their exact pmf. A black probe returns
    /// pdf 0 and zero radiance.
    ProbeSample sample(float u0, float u1, float u2) const;
    /// The same distribution as sample() by inversion of the marginal (rows) and conditional
    /// (columns) CDFs: a monotone map of the unit square, so stratified or low-discrepancy
    /// points stay evenly spread over a bright region such as the sun's disk. u.x picks the
    /// column, u.y the row.
    /// Its tables are built on the first call (the renderer samples by sample() and by
    /// ProbeLights), so that a probe that is never inverted does not carry them.
    ProbeSample sample_inverse(vec2 u) const { return sample_table(inverse_table(), u); }
    /// A direction from `table` (a distribution over this probe's pixels, such as a part of
    /// it): its pixel by inversion, uniform in solid angle inside the pixel; the pdf is the
    /// table's pmf over the pixel's solid angle.
    ProbeSample sample_table(const LatLongTable& table, vec2 u) const;
    /// luminance(L_j) * Omega_j of a pixel as the sampling weights are built (0 unless positive).
    double pixel_weight(size_t pixel) const;
    /// Solid-angle pdf of sample() and sample_inverse() for a world direction.
    float pdf(const vec3& dir) const;
    /// Probability that sample() picks pixel `pixel` (its table realizes it to float precision:
    /// each alias coin is a float).
    double pixel_pmf(size_t pixel) const;
    /// Sum over pixels of luminance(L_j) * Omega_j (zero for a black probe).
    double total_luminance_power() const { return total_power_; }

    vec3 to_world(const vec3& probe_dir) const { return rotation_ * probe_dir; }
    vec3 to_probe(const vec3& world_dir) const { return inverse_rotation_ * world_dir; }

    /// Bytes this probe keeps per pixel beyond the image it shares: the alias table sample()
    /// reads (the table of sample_inverse() adds 8 more once built).
    static constexpr size_t kTableBytesPerPixel = 8;

private:
    /// One column of the alias table: the coin that sample() flips once it has picked the
    /// column. 8 bytes: a float coin keeps each pixel's probability to 2^-24 of itself (so a
    /// sky pixel a million times fainter than the sun keeps its own), and everything else
    /// sample() returns is computed from the image and the row.
    struct Column {
        float prob = 1;      ///< keep the column's own pixel when the in-column fraction is below
        uint32_t alias = 0;  ///< pixel picked otherwise
    };
    /// Per-row constants, so that no call evaluates trigonometry for the band.
    struct Row {
        double cos_top = 1;      ///< cos theta at the row's upper edge
        double cos_span = 0;     ///< cos theta at the lower edge minus cos_top
        double solid_angle = 0;  ///< pixel_solid_angle(row)
    };
    /// The pmf again as a LatLongTable for sample_inverse(), made on first use (thread-safe).
    struct InverseTable;

    void build();
    /// Solid-angle pdf of a pixel as sample() and pdf() return it: pmf / Omega, which is the
    /// pixel's luminance over the total power, rounded once so that both agree bit for bit.
    float pixel_pdf(size_t pixel) const;
    const LatLongTable& inverse_table() const;

    std::shared_ptr<const Image> image_ = std::make_shared<const Image>();
    glm::mat3 rotation_{1.0f}, inverse_rotation_{1.0f};
    vec3 gain_{1.0f};
    // Read at random once per call: huge pages spare most lookups a TLB miss as well.
    std::vector<Column, HugePageAllocator<Column>> columns_;  ///< one per pixel, row-major
    std::vector<Row> rows_;
    std::shared_ptr<InverseTable> inverse_;
    double total_power_ = 0;
};

/// Unwraps a mirror-ball photograph (the ball filling the square image) seen by a camera with
/// the given vertical field of view (0 = orthographic) into a lat-long map of the given size.
/// The ball's camera looks along -Z of probe space, image right being +X and up +Y; a perspective
/// camera sits 1 / sin(fov / 2) ball radii from the centre. A non-square photo is read as its
/// centred square. Directions hidden behind the ball, and those within 1.5 pixels of its rim,
/// take the value just inside the rim at the same azimuth. Throws std::invalid_argument for an
/// empty photo, a non-positive output size or a field of view outside [0, 180).
Image unwrap_mirror_ball(const Image& ball, int out_width, int out_height, float camera_fov_deg = 0);

}  // namespace dp
