#include "calibration/auto_lines.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <random>

#include "base/error.h"
#include "image/image_io.h"

namespace dp {

namespace {


/// A segment as the clustering uses it.
struct Seg {
    glm::dvec2 mid{0.0}, dir{0.0};  ///< dir: unit
    double len = 0;
    glm::dvec3 line{0.0};  ///< homogeneous, through both ends
};

Seg make_seg(const LineSegment& s) {
    Seg g;
    g.mid = 0.5 * (s.a + s.b);
    g.len = glm::length(s.b - s.a);
    g.dir = g.len > 0 ? (s.b - s.a) / g.len : glm::dvec2(1, 0);
    g.line = glm::cross(glm::dvec3(s.a, 1.0), glm::dvec3(s.b, 1.0));
    return g;
}

/// `v` as a finite point, or nullopt where it is at infinity for an image of `size` pixels.
std::optional<glm::dvec2> finite(const glm::dvec3& v, double size) {
    if (std::abs(v.z) * 1e7 * size <= glm::length(glm::dvec2(v))) return std::nullopt;
    return glm::dvec2(v) / v.z;
}

/// The direction in the image from `from` towards `v` (a point, or a direction at infinity).
glm::dvec2 towards(const glm::dvec3& v, glm::dvec2 from, double size) {
    if (const auto p = finite(v, size)) return *p - from;
    return glm::dvec2(v);
}

/// Whether segment `s` runs to `v`: the line from its midpoint to `v` within `sin_max` of its
/// direction and passing within `end_px` of its end points (a long segment is held to a tighter
/// angle: edges near a direction but not along it would bias the fit), `v` not on the segment.
bool supports(const Seg& s, const glm::dvec3& v, double sin_max, double end_px, double size) {
    const glm::dvec2 d = towards(v, s.mid, size);
    const double n = glm::length(d);
    if (!(n > 0.5 * s.len)) return false;
    const double sin = std::abs(s.dir.x * d.y - s.dir.y * d.x) / n;
    return sin <= sin_max && sin * 0.5 * s.len <= end_px;
}

/// Length-weighted steepness of a cluster's segments: 1 for vertical in the image, 0 flat.
double steepness(const std::vector<LineSegment>& segments, const VanishingCluster& c) {
    double sum = 0, w = 0;
    for (int i : c.members) {
        const glm::dvec2 d = segments[size_t(i)].b - segments[size_t(i)].a;
        const double len = glm::length(d);
        if (len > 0) sum += std::abs(d.y), w += len;
    }
    return w > 0 ? sum / w : 0;
}

std::vector<LineSegment> members_of(const std::vector<LineSegment>& segments, const VanishingCluster& c) {
    std::vector<LineSegment> out;
    for (int i : c.members) out.push_back(segments[size_t(i)]);
    return out;
}

/// One way of reading clusters as orthogonal directions: cluster index per axis (-1 unused).
struct Reading {
    int axis[3] = {-1, -1, -1};
    double support = 0;
    bool focal_known = false;  ///< the vanishing points (or a given focal) fix the focal length
    double focal = 0;
};

/// Whether the clusters of `r` can be orthogonal directions of one camera with its principal
/// point at `c`; sets r.focal_known and r.focal.
bool consistent(Reading& r, const std::vector<VanishingCluster>& cl, glm::dvec2 c, double size,
                std::optional<double> focal_px) {
    const double f_lo = 0.13 * size, f_hi = 5.7 * size;  // fields of view of 150 to 10 degrees
    const double sin_tol = std::sin(3.0 * kPi / 180);
    std::vector<double> focals;
    for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b) {
            if (r.axis[a] < 0 || r.axis[b] < 0) continue;
            const glm::dvec3 &va = cl[size_t(r.axis[a])].vp, &vb = cl[size_t(r.axis[b])].vp;
            const auto pa = finite(va, size), pb = finite(vb, size);
            if (pa && pb) {
                const double f2 = -glm::dot(*pa - c, *pb - c);
                if (!(f2 > f_lo * f_lo && f2 < f_hi * f_hi)) return false;
                focals.push_back(std::sqrt(f2));
            } else {
                // At infinity: the direction lies in the image plane, orthogonal in the image to
                // the other's direction from the centre.
                const glm::dvec2 da = pa ? *pa - c : glm::dvec2(va), db = pb ? *pb - c : glm::dvec2(vb);
                const double cross = std::abs(glm::dot(da, db)) / (glm::length(da) * glm::length(db));
                if (!(cross < sin_tol)) return false;
            }
        }
    if (focal_px) {
        for (double f : focals)
            if (std::abs(f / *focal_px - 1) > 0.25) return false;
        r.focal_known = true;
        r.focal = *focal_px;
        return true;
    }
    if (focals.empty()) return true;
    const auto [lo, hi] = std::minmax_element(focals.begin(), focals.end());
    if (*hi > 1.25 * *lo) return false;
    r.focal_known = true;
    r.focal = std::accumulate(focals.begin(), focals.end(), 0.0) / double(focals.size());
    return true;
}

/// The segments of each direction `r` reads, the rest as `other`, with notes after `first`.
LineProposal proposal_of(const Reading& r, const std::vector<LineSegment>& segments,
                         const std::vector<VanishingCluster>& clusters, const std::string& first) {
    static const char* const kNames[3] = {"X (ground)", "Y (vertical)", "Z (ground)"};
    LineProposal p;
    p.notes.push_back(first);
    std::vector<bool> used(segments.size());
    for (int a = 0; a < 3; ++a) {
        if (r.axis[a] < 0) continue;
        const VanishingCluster& cl = clusters[size_t(r.axis[a])];
        p.axis[a] = members_of(segments, cl);
        for (int i : cl.members) used[size_t(i)] = true;
        char line[120];
        std::snprintf(line, sizeof line, "%s: %zu segments", kNames[a], cl.members.size());
        p.notes.push_back(line);
    }
    for (size_t i = 0; i < segments.size(); ++i)
        if (!used[i]) p.other.push_back(segments[i]);
    return p;
}

}  // namespace

std::vector<LineSegment> detect_line_segments(const Image& photo, double min_length_px) {
    const int w = photo.width(), h = photo.height();
    if (w < 8 || h < 8) return {};
    // Detected at no more than 1600 pixels across: finer detail adds texture, not lines.
    const double scale = std::min(1.0, 1600.0 / std::max(w, h));
    cv::Mat grey(h, w, CV_8U);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const vec3 p = photo.at(x, y);
            const float lum = std::clamp(0.2126f * p.x + 0.7152f * p.y + 0.0722f * p.z, 0.0f, 1.0f);
            grey.at<uint8_t>(y, x) = uint8_t(std::lround(255.0f * linear_to_srgb(lum)));
        }
    if (scale < 1) cv::resize(grey, grey, cv::Size(), scale, scale, cv::INTER_AREA);
    std::vector<cv::Vec4f> lines;
    cv::createLineSegmentDetector(cv::LSD_REFINE_STD)->detect(grey, lines);
    std::vector<LineSegment> out;
    for (const cv::Vec4f& l : lines) {
        // Back to photo pixels (pixel centres at integers).
        LineSegment s{ImagePoint((l[0] + 0.5) / scale - 0.5, (l[1] + 0.5) / scale - 0.5),
                      ImagePoint((l[2] + 0.5) / scale - 0.5, (l[3] + 0.5) / scale - 0.5)};
        if (glm::length(s.b - s.a) >= min_length_px) out.push_back(s);
    }
    std::sort(out.begin(), out.end(), [](const LineSegment& p, const LineSegment& q) {
        return glm::length(p.b - p.a) > glm::length(q.b - q.a);
    });
    return out;
}

std::vector<VanishingCluster> find_vanishing_clusters(const std::vector<LineSegment>& segments, int width,
                                                      int height, unsigned seed, int max_clusters,
                                                      double max_angle_deg) {
    const double size = std::max(width, height);
    const double sin_max = std::sin(max_angle_deg * kPi / 180);
    // A pixel at the resolution the segments were detected at (detect_line_segments: at most
    // 1600 across).
    const double end_px = std::max(1.0, size / 1600);
    std::vector<Seg> segs;
    double total = 0;
    for (const LineSegment& s : segments) {
        segs.push_back(make_seg(s));
        total += segs.back().len;
    }
    std::vector<int> remaining(segs.size());
    std::iota(remaining.begin(), remaining.end(), 0);
    std::mt19937 rng(seed);
    std::vector<VanishingCluster> out;
    auto inliers_of = [&](const glm::dvec3& v) {
        std::vector<int> in;
        for (int i : remaining)
            if (supports(segs[size_t(i)], v, sin_max, end_px, size)) in.push_back(i);
        return in;
    };
    auto length_of = [&](const std::vector<int>& idx) {
        double s = 0;
        for (int i : idx) s += segs[size_t(i)].len;
        return s;
    };
    while (int(out.size()) < max_clusters && remaining.size() >= 3) {
        // Pairs drawn in proportion to length: long segments are the reliable ones.
        std::vector<double> weights;
        for (int i : remaining) weights.push_back(segs[size_t(i)].len);
        std::discrete_distribution<size_t> pick(weights.begin(), weights.end());
        glm::dvec3 best(0.0);
        double best_support = 0;
        for (int it = 0; it < 1500; ++it) {
            const size_t i = pick(rng), j = pick(rng);
            if (i == j) continue;
            glm::dvec3 v = glm::cross(segs[size_t(remaining[i])].line, segs[size_t(remaining[j])].line);
            const double n = glm::length(v);
            if (!(n > 0)) continue;
            v /= n;
            double support = 0;
            for (int k : remaining)
                if (supports(segs[size_t(k)], v, sin_max, end_px, size)) support += segs[size_t(k)].len;
            if (support > best_support) best_support = support, best = v;
        }
        std::vector<int> in = inliers_of(best);
        for (int refine = 0; refine < 2 && in.size() >= 2; ++refine) {
            std::vector<LineSegment> chosen;
            for (int i : in) chosen.push_back(segments[size_t(i)]);
            const glm::dvec3 v = vanishing_point(chosen);
            const std::vector<int> again = inliers_of(glm::normalize(v));
            if (length_of(again) < length_of(in)) break;
            best = glm::normalize(v);
            in = again;
        }
        if (in.size() < 3 || length_of(in) < 0.04 * total) break;
        VanishingCluster c;
        c.vp = best;
        c.members = in;
        c.support = length_of(in);
        out.push_back(c);
        std::vector<int> rest;
        std::set_difference(remaining.begin(), remaining.end(), in.begin(), in.end(), std::back_inserter(rest));
        remaining = rest;
    }
    // A segment that runs to two of the points says nothing of either (a line along the
    // horizon runs to every point on it): it leaves both, or it would bias the first found.
    for (size_t c = 0; c < out.size(); ++c) {
        std::vector<int> kept;
        for (int i : out[c].members) {
            bool shared = false;
            for (size_t d = 0; d < out.size() && !shared; ++d)
                shared = d != c && supports(segs[size_t(i)], out[d].vp, sin_max, end_px, size);
            if (!shared) kept.push_back(i);
        }
        out[c].members = kept;
        out[c].support = length_of(kept);
    }
    out.erase(std::remove_if(out.begin(), out.end(), [](const VanishingCluster& c) { return c.members.size() < 3; }),
              out.end());
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.support > b.support; });
    return out;
}

std::vector<LineProposal> propose_axes_ranked(const std::vector<LineSegment>& segments,
                                             const std::vector<VanishingCluster>& clusters, int width, int height,
                                             std::optional<double> focal_px, size_t max_proposals) {
    const double size = std::max(width, height);
    const glm::dvec2 c(0.5 * (width - 1), 0.5 * (height - 1));
    const int n = std::min<int>(int(clusters.size()), 6);
    std::vector<bool> is_vertical(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        const auto v = finite(clusters[size_t(i)].vp, size);
        const bool far = !v || glm::length(*v - c) > 2 * size;
        is_vertical[size_t(i)] = far && steepness(segments, clusters[size_t(i)]) > std::cos(25.0 * kPi / 180);
    }
    // Every reading of two or three clusters as orthogonal directions: the vertical (Y) only a
    // cluster that can be one, the others horizontal (X and Z).
    std::vector<Reading> readings;
    for (int y = -1; y < n; ++y) {
        if (y >= 0 && !is_vertical[size_t(y)]) continue;
        for (int x = 0; x < n; ++x)
            for (int z = -1; z < n; ++z) {
                // A steep bundle of nearly parallel lines is the vertical wherever it is used.
                if (x == y || z == y || (z >= 0 && z <= x)) continue;
                if (is_vertical[size_t(x)] || (z >= 0 && is_vertical[size_t(z)])) continue;
                if (y < 0 && z < 0) continue;
                Reading r;
                r.axis[0] = x, r.axis[1] = y, r.axis[2] = z;
                for (int a : r.axis)
                    if (a >= 0) r.support += clusters[size_t(a)].support;
                if (consistent(r, clusters, c, size, focal_px)) readings.push_back(r);
            }
    }
    // The vertical first (a Manhattan world's most reliable direction: two horizontal bundles
    // may be one facade's lines split by noise), then a determined focal length, then more
    // directions, then more length.
    std::stable_sort(readings.begin(), readings.end(), [](const Reading& a, const Reading& b) {
        const int ka = (a.axis[0] >= 0) + (a.axis[1] >= 0) + (a.axis[2] >= 0);
        const int kb = (b.axis[0] >= 0) + (b.axis[1] >= 0) + (b.axis[2] >= 0);
        if ((a.axis[1] >= 0) != (b.axis[1] >= 0)) return a.axis[1] >= 0;
        if (a.focal_known != b.focal_known) return a.focal_known;
        if (ka != kb) return ka > kb;
        return a.support > b.support;
    });
    if (readings.size() > max_proposals) readings.resize(max_proposals);
    char line[200];
    std::snprintf(line, sizeof line, "%zu line segments, %zu vanishing points", segments.size(), clusters.size());
    std::vector<LineProposal> out;
    for (const Reading& r : readings) out.push_back(proposal_of(r, segments, clusters, line));
    if (out.empty()) {
        LineProposal p;
        p.notes = {line, "no two vanishing points fit orthogonal directions of one camera"};
        p.other = segments;
        out.push_back(std::move(p));
    }
    return out;
}

VanishingInput vanishing_input(const LineProposal& p, ImagePoint origin, double camera_height,
                               std::optional<double> focal_px) {
    VanishingInput in;
    in.x = p.axis[0];
    in.y = p.axis[1];
    in.z = p.axis[2];
    in.origin = origin;
    in.camera_height = camera_height;
    in.focal_px = focal_px;
    return in;
}

namespace {

/// The camera of one proposal, its origin tried lower and higher until it lies on the ground;
/// nullopt with `why` where the lines do not determine one.
std::optional<CalibrationResult> solve_proposal(const LineProposal& p, const AutoLinesOptions& o, int w, int h,
                                                const std::string& source, ImagePoint& origin, std::string& why) {
    for (double fy : {0.9, 0.98, 0.75, 0.6}) {
        origin = ImagePoint(0.5 * (w - 1), fy * (h - 1));
        try {
            return calibrate_vanishing(vanishing_input(p, origin, o.camera_height, o.focal_px), w, h, source);
        } catch (const InputError& e) {
            why = e.what();
            if (why.find("horizon") == std::string::npos) break;
        }
    }
    return std::nullopt;
}

}  // namespace

AutoLinesResult calibrate_from_lines(const Image& photo, const AutoLinesOptions& o, const std::string& source) {
    AutoLinesResult r;
    const int w = photo.width(), h = photo.height();
    r.segments = detect_line_segments(photo, o.min_length_fraction * std::hypot(double(w), double(h)));
    r.clusters = find_vanishing_clusters(r.segments, w, h, o.seed);
    const std::vector<LineProposal> proposals = propose_axes_ranked(r.segments, r.clusters, w, h, o.focal_px, 8);
    r.proposal = proposals[0];
    r.origin = ImagePoint(0.5 * (w - 1), 0.9 * (h - 1));
    const auto axes = [](const LineProposal& p) { return !p.axis[0].empty() + !p.axis[1].empty() + !p.axis[2].empty(); };
    if (axes(r.proposal) < 2) {
        r.failure = "the photo's lines give fewer than two orthogonal directions: draw lines along two directions "
                    "(the ground's edges, or one on the ground and a vertical)";
        return r;
    }
    // The readings in their order (the vertical first); the first the solver can place wins.
    // (Choosing the one the solver pins down best instead was tried: on the probe plates it
    // was more often confidently wrong.)
    std::string why;
    for (const LineProposal& p : proposals) {
        if (axes(p) < 2) continue;
        ImagePoint origin;
        std::string failure;
        std::optional<CalibrationResult> camera = solve_proposal(p, o, w, h, source, origin, failure);
        if (!camera) {
            if (why.empty()) why = failure;
            continue;
        }
        r.camera = std::move(camera);
        r.proposal = p;
        r.origin = origin;
        break;
    }
    if (!r.camera) {
        r.failure = why;
        return r;
    }
    char line[160];
    std::snprintf(line, sizeof line, "the lines give a focal length of %.0f px", r.camera->intrinsics.fx);
    if (!o.focal_px) r.proposal.notes.push_back(line);
    r.camera->warnings.push_back("the scale assumes a camera " + std::to_string(o.camera_height).substr(0, 4) +
                                 " m above the ground; give the camera height or a known length");
    return r;
}

}  // namespace dp
