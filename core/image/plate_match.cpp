#include "image/plate_match.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numeric>

#include <opencv2/imgproc.hpp>

#include "base/math.h"
#include "base/rng.h"
#include "image/image_io.h"

namespace dp {

namespace {

constexpr int kPatch = 8;
constexpr int kDof = kPatch * kPatch - 3;  // a plane's three parameters fitted away

/// One flat-patch candidate: its mean luminance and per-channel residual variance.
struct PatchStat {
    int x = 0, y = 0;
    float level = 0;
    vec3 var{0.0f};
    float lum_var = 0;
};

/// The residual of `channel` of the 8x8 patch at (x0, y0) after a least-squares plane.
void plane_residual(const Image& im, int x0, int y0, int channel, float out[kPatch * kPatch]) {
    double sum = 0, sx = 0, sy = 0;
    for (int j = 0; j < kPatch; ++j)
        for (int i = 0; i < kPatch; ++i) {
            const double v = im.at(x0 + i, y0 + j)[channel];
            sum += v;
            sx += v * (i - 3.5);
            sy += v * (j - 3.5);
        }
    // Sum of (i - 3.5)^2 over the patch: 8 rows of 42.
    const double a = sum / (kPatch * kPatch), b = sx / 336.0, c = sy / 336.0;
    for (int j = 0; j < kPatch; ++j)
        for (int i = 0; i < kPatch; ++i)
            out[j * kPatch + i] = float(im.at(x0 + i, y0 + j)[channel] - (a + b * (i - 3.5) + c * (j - 3.5)));
}

/// The luminance residual of a patch, from the channel residuals.
void luminance_residual(const float r[3][kPatch * kPatch], float out[kPatch * kPatch]) {
    for (int k = 0; k < kPatch * kPatch; ++k) out[k] = luminance(vec3(r[0][k], r[1][k], r[2][k]));
}

double variance_of(const float* r) {
    double s = 0;
    for (int k = 0; k < kPatch * kPatch; ++k) s += double(r[k]) * r[k];
    return s / kDof;
}

std::vector<float> gaussian_kernel(float sigma) {
    const int r = std::max(1, int(std::ceil(3 * sigma)));
    std::vector<float> k(size_t(2 * r + 1));
    double sum = 0;
    for (int i = -r; i <= r; ++i) sum += k[size_t(i + r)] = std::exp(-0.5f * float(i * i) / (sigma * sigma));
    for (float& v : k) v = float(v / sum);
    return k;
}

/// The edge width figure of Zhuo and Sim: at the strongest edge pixels, the ratio R of the
/// gradient before and after a re-blur of known width s0 gives the edge's own width
/// s0 / sqrt(R^2 - 1); the median over those pixels. -1 with fewer than 50 edge pixels.
float raw_edge_sigma(const Image& image) {
    const int W = image.width(), H = image.height();
    if (W < 8 || H < 8) return -1;
    cv::Mat Y(H, W, CV_32F);
    std::vector<float> all;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) all.push_back(Y.at<float>(y, x) = luminance(image.at(x, y)));
    // Edges are found on the picture as shown: sRGB of luminance scaled to its bright end.
    std::nth_element(all.begin(), all.begin() + ptrdiff_t(all.size() * 99 / 100), all.end());
    const float top = std::max(all[all.size() * 99 / 100], 1e-6f);
    cv::Mat shown(H, W, CV_8U);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            shown.at<uint8_t>(y, x) = uint8_t(std::lround(255 * linear_to_srgb(std::clamp(Y.at<float>(y, x) / top, 0.0f, 1.0f))));
    cv::Mat gx, gy, mag;
    cv::Sobel(shown, gx, CV_32F, 1, 0);
    cv::Sobel(shown, gy, CV_32F, 0, 1);
    cv::magnitude(gx, gy, mag);
    std::vector<float> m(mag.begin<float>(), mag.end<float>());
    std::nth_element(m.begin(), m.begin() + ptrdiff_t(m.size() * 95 / 100), m.end());
    const double high = std::max(60.0, double(m[m.size() * 95 / 100]));
    cv::Mat edges;
    cv::Canny(shown, edges, 0.4 * high, high, 3, true);
    constexpr float kReblur = 1.0f;
    cv::Mat Yb;
    cv::GaussianBlur(Y, Yb, cv::Size(0, 0), kReblur, kReblur, cv::BORDER_REPLICATE);
    auto grad = [](const cv::Mat& I, int x, int y) {
        const float dx = 0.5f * (I.at<float>(y, x + 1) - I.at<float>(y, x - 1));
        const float dy = 0.5f * (I.at<float>(y + 1, x) - I.at<float>(y - 1, x));
        return std::sqrt(dx * dx + dy * dy);
    };
    struct Sample {
        float g, sigma;
    };
    std::vector<Sample> samples;
    for (int y = 2; y < H - 2; ++y)
        for (int x = 2; x < W - 2; ++x) {
            if (!edges.at<uint8_t>(y, x)) continue;
            const float g = grad(Y, x, y), gb = grad(Yb, x, y);
            if (!(gb > 0)) continue;
            const float R = g / gb;
            if (R > 1.001f) samples.push_back({g, kReblur / std::sqrt(R * R - 1)});
        }
    if (samples.size() < 50) return -1;
    // The stronger half: faint edges are the noisiest.
    std::sort(samples.begin(), samples.end(), [](const Sample& a, const Sample& b) { return a.g > b.g; });
    samples.resize(samples.size() / 2);
    std::vector<float> sig;
    for (const Sample& s : samples) sig.push_back(s.sigma);
    std::nth_element(sig.begin(), sig.begin() + ptrdiff_t(sig.size() / 2), sig.end());
    return sig[sig.size() / 2];
}

/// What raw_edge_sigma says of edges as sharp as a render's: squares at several angles, each
/// pixel the mean of 8x8 samples (the renderer's jittered samples make a one-pixel box filter).
float render_edge_sigma() {
    static const float value = [] {
        constexpr int N = 192, S = 8;
        Image im(N, N);
        for (int y = 0; y < N; ++y)
            for (int x = 0; x < N; ++x) {
                float sum = 0;
                for (int j = 0; j < S; ++j)
                    for (int i = 0; i < S; ++i) {
                        const float px = x + (i + 0.5f) / S, py = y + (j + 0.5f) / S;
                        bool in = false;
                        // Four squares turned by 0, 10, 25 and 40 degrees.
                        for (int k = 0; k < 4; ++k) {
                            const float a = glm::radians(std::array{0.0f, 10.0f, 25.0f, 40.0f}[size_t(k)]);
                            const float cx = 48.0f + 96.0f * float(k % 2), cy = 48.0f + 96.0f * float(k / 2);
                            const float u = std::cos(a) * (px - cx) + std::sin(a) * (py - cy);
                            const float v = -std::sin(a) * (px - cx) + std::cos(a) * (py - cy);
                            in |= std::abs(u) < 28 && std::abs(v) < 28;
                        }
                        sum += in ? 0.7f : 0.08f;
                    }
                im.at(x, y) = vec3(sum / (S * S));
            }
        return raw_edge_sigma(im);
    }();
    return value;
}

/// The mean correlation (across and down) of the luminance residuals of the 8x8 patches at
/// `at` of `im` with the next pixel (x) and the one after (y).
vec2 neighbour_correlation(const Image& im, const std::vector<std::pair<int, int>>& at) {
    double lag1 = 0, lag2 = 0, lag0 = 0;
    for (auto [x0, y0] : at) {
        float r[3][kPatch * kPatch], lum[kPatch * kPatch];
        for (int c = 0; c < 3; ++c) plane_residual(im, x0, y0, c, r[c]);
        luminance_residual(r, lum);
        for (int j = 0; j < kPatch; ++j)
            for (int i = 0; i < kPatch; ++i) {
                const double v = lum[j * kPatch + i];
                lag0 += v * v;
                // 56 pairs one apart and 48 two apart per direction, against 64 squares.
                if (i + 1 < kPatch) lag1 += 0.5 * v * lum[j * kPatch + i + 1] * (64.0 / 56.0);
                if (j + 1 < kPatch) lag1 += 0.5 * v * lum[(j + 1) * kPatch + i] * (64.0 / 56.0);
                if (i + 2 < kPatch) lag2 += 0.5 * v * lum[j * kPatch + i + 2] * (64.0 / 48.0);
                if (j + 2 < kPatch) lag2 += 0.5 * v * lum[(j + 2) * kPatch + i] * (64.0 / 48.0);
            }
    }
    return lag0 > 0 ? vec2(float(lag1 / lag0), float(lag2 / lag0)) : vec2(0.0f);
}

/// The 8x8 patches of a plate of grain alone that measure_grain would take for grain: green
/// residual variance at most twice its lower quartile.
std::vector<std::pair<int, int>> grain_like(const Image& im) {
    std::vector<std::pair<double, std::pair<int, int>>> v;
    for (int y0 = kPatch / 2; y0 + kPatch <= im.height(); y0 += kPatch)
        for (int x0 = kPatch / 2; x0 + kPatch <= im.width(); x0 += kPatch) {
            float r[kPatch * kPatch];
            plane_residual(im, x0, y0, 1, r);
            v.push_back({variance_of(r), {x0, y0}});
        }
    std::vector<double> vars;
    for (const auto& e : v) vars.push_back(e.first);
    std::nth_element(vars.begin(), vars.begin() + ptrdiff_t(vars.size() / 4), vars.end());
    const double limit = 2 * vars[vars.size() / 4];
    std::vector<std::pair<int, int>> out;
    for (const auto& e : v)
        if (e.first <= limit) out.push_back(e.second);
    return out;
}

/// The lower quartile of the plane-fit residual variance of 8x8 patches of unit grain with
/// `g`'s correlations, per channel.
vec3 quartile_ratio(const GrainProfile& g) {
    constexpr int N = 256;
    GrainProfile unit = g;
    unit.levels = {1.0f};
    unit.sigma = {vec3(1.0f)};
    const Image n = grain_field(unit, N, N, 0x9a1e);
    vec3 q;
    for (int c = 0; c < 3; ++c) {
        std::vector<double> v;
        for (int y0 = 0; y0 + kPatch <= N; y0 += kPatch)
            for (int x0 = 0; x0 + kPatch <= N; x0 += kPatch) {
                float r[kPatch * kPatch];
                plane_residual(n, x0, y0, c, r);
                v.push_back(variance_of(r));
            }
        std::nth_element(v.begin(), v.begin() + ptrdiff_t(v.size() / 4), v.end());
        q[c] = float(v[v.size() / 4]);
    }
    return q;
}

/// Replaces the bands' figures by a power law sigma = c L^p per channel, fitted in log-log as
/// a low quantile (30%) regression: grain grows smoothly with brightness (shot noise: p = 1/2;
/// noise of constant size in JPEG codes, decoded to linear: about 0.6), while a band whose
/// patches are all texture (none flat at that brightness: the edges of a checkerboard, the mid
/// greys of a busy room) only ever lies above it. The best line passes through two bands, so
/// every pair is tried.
void fit_power_law(GrainProfile& g) {
    const size_t n = g.levels.size();
    if (n < 2) return;
    constexpr double kTau = 0.3;
    for (int c = 0; c < 3; ++c) {
        std::vector<double> x, y;
        for (size_t i = 0; i < n; ++i)
            if (g.sigma[i][c] > 0) x.push_back(std::log(g.levels[i])), y.push_back(std::log(g.sigma[i][c]));
        if (x.size() < 2) continue;
        double best = INFINITY, p = 0.5, b = y[0] - 0.5 * x[0];
        for (size_t i = 0; i < x.size(); ++i)
            for (size_t j = i + 1; j < x.size(); ++j) {
                if (std::abs(x[j] - x[i]) < 1e-6) continue;
                const double slope = std::clamp((y[j] - y[i]) / (x[j] - x[i]), 0.0, 1.5);
                const double icpt = y[i] - slope * x[i];
                double loss = 0;
                for (size_t k = 0; k < x.size(); ++k) {
                    const double r = y[k] - (icpt + slope * x[k]);
                    loss += r >= 0 ? kTau * r : (kTau - 1) * r;
                }
                if (loss < best) best = loss, p = slope, b = icpt;
            }
        for (size_t i = 0; i < n; ++i) g.sigma[i][c] = float(std::exp(b + p * std::log(g.levels[i])));
    }
}

}  // namespace

vec3 GrainProfile::sigma_at(float level) const {
    if (levels.empty()) return vec3(0.0f);
    if (level <= levels.front()) return sigma.front();
    if (level >= levels.back()) return sigma.back();
    const size_t i = size_t(std::upper_bound(levels.begin(), levels.end(), level) - levels.begin());
    const float t = std::log(level / levels[i - 1]) / std::log(levels[i] / levels[i - 1]);
    return glm::mix(sigma[i - 1], sigma[i], t);
}

GrainProfile measure_grain(const Image& photo, float clip_level) {
    if (clip_level < 0) {
        float top = 0;
        for (size_t i = 0; i < photo.size(); ++i) top = std::max({top, photo[i].x, photo[i].y, photo[i].z});
        size_t at_top = 0;
        for (size_t i = 0; i < photo.size(); ++i)
            at_top += std::max({photo[i].x, photo[i].y, photo[i].z}) >= 0.995f * top;
        clip_level = at_top >= photo.size() / 1000 + 1 ? 0.995f * top : INFINITY;
    }
    GrainProfile g;
    const int W = photo.width(), H = photo.height();
    std::vector<PatchStat> stats;
    // Patches straddle the 8x8 blocks of a JPEG: inside a block its quantisation leaves only
    // smooth terms, and the grain would be judged far smoother than the picture shows it.
    for (int y0 = kPatch / 2; y0 + kPatch <= H; y0 += kPatch)
        for (int x0 = kPatch / 2; x0 + kPatch <= W; x0 += kPatch) {
            bool usable = true;
            vec3 mean(0.0f);
            for (int j = 0; j < kPatch && usable; ++j)
                for (int i = 0; i < kPatch; ++i) {
                    const vec3 v = photo.at(x0 + i, y0 + j);
                    usable &= glm::all(glm::lessThan(v, vec3(clip_level))) && glm::all(glm::greaterThan(v, vec3(0.0f)));
                    mean += v;
                }
            if (!usable) continue;
            float r[3][kPatch * kPatch], lum[kPatch * kPatch];
            PatchStat s{x0, y0, luminance(mean / float(kPatch * kPatch)), vec3(0.0f), 0};
            for (int c = 0; c < 3; ++c) {
                plane_residual(photo, x0, y0, c, r[c]);
                s.var[c] = float(variance_of(r[c]));
            }
            luminance_residual(r, lum);
            s.lum_var = float(variance_of(lum));
            stats.push_back(s);
        }
    if (stats.size() < 16) return g;
    std::sort(stats.begin(), stats.end(), [](const PatchStat& a, const PatchStat& b) { return a.level < b.level; });
    // Brightness bands of equal width in log luminance between the 1% and 99% patches.
    const float lo = stats[stats.size() / 100].level, hi = stats[stats.size() * 99 / 100].level;
    constexpr int kBands = 12;
    std::vector<const PatchStat*> flat;  // the patches that speak for the grain
    size_t begin = 0;
    for (int b = 0; b < kBands; ++b) {
        const float top = b == kBands - 1 ? INFINITY : lo * std::pow(hi / lo, float(b + 1) / kBands);
        size_t end = begin;
        while (end < stats.size() && stats[end].level < top) ++end;
        if (end - begin >= 8) {
            std::vector<const PatchStat*> band;
            for (size_t k = begin; k < end; ++k) band.push_back(&stats[k]);
            std::sort(band.begin(), band.end(), [](auto* a, auto* b) { return a->lum_var < b->lum_var; });
            const size_t at = band.size() / 4;
            vec3 var;
            for (int c = 0; c < 3; ++c) {
                std::vector<float> v;
                for (auto* s : band) v.push_back(s->var[c]);
                std::nth_element(v.begin(), v.begin() + ptrdiff_t(at), v.end());
                var[c] = v[at];
            }
            g.levels.push_back(band[band.size() / 2]->level);
            g.sigma.push_back(glm::sqrt(var));  // the raw quartile, corrected below
        }
        begin = end;
    }
    if (g.levels.size() < 2) return GrainProfile{};
    // Levels ascend by construction (bands are in order); a band's median may tie another's.
    for (size_t i = 1; i < g.levels.size(); ++i) g.levels[i] = std::max(g.levels[i], g.levels[i - 1] * 1.0001f);
    fit_power_law(g);
    // The patches that speak for the grain: no busier than twice the fitted quartile of its
    // variance there (green, the channel luminance leans on; grain_like picks alike).
    for (const PatchStat& s : stats) {
        const float sg = g.sigma_at(s.level).y;
        if (s.var.y <= 2 * sg * sg) flat.push_back(&s);
    }
    g.patches = flat.size();
    if (flat.size() < 16) return GrainProfile{};

    // Channel correlation of the flattest patches' residuals.
    double cov[3][3] = {};
    std::vector<std::pair<int, int>> at;
    for (const PatchStat* s : flat) {
        float r[3][kPatch * kPatch];
        for (int c = 0; c < 3; ++c) plane_residual(photo, s->x, s->y, c, r[c]);
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
                for (int k = 0; k < kPatch * kPatch; ++k) cov[a][b] += double(r[a][k]) * r[b][k];
        at.emplace_back(s->x, s->y);
    }
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
            g.channel_correlation[a][b] = float(cov[a][b] / std::sqrt(std::max(cov[a][a] * cov[b][b], 1e-300)));
    // The residuals' correlation with the next pixel is lower than the grain's own (a plane
    // on 64 pixels takes some of it): the width whose simulated grain shows the same.
    const float rho = neighbour_correlation(photo, at).x;
    auto simulated = [&](float width) {
        GrainProfile sim = g;
        sim.correlation_px = width;
        const Image n = grain_field(sim, 128, 128, 0x5eed);
        return neighbour_correlation(n, grain_like(n)).x;
    };
    float lo_w = 0, hi_w = 3;
    g.correlation_px = 0;
    if (rho >= simulated(hi_w)) {
        g.correlation_px = hi_w;
    } else if (rho > simulated(0)) {
        for (int it = 0; it < 12; ++it) {
            const float mid = 0.5f * (lo_w + hi_w);
            (simulated(mid) < rho ? lo_w : hi_w) = mid;
        }
        g.correlation_px = 0.5f * (lo_w + hi_w);
    }
    // The quartile of pure grain's patch variance over its variance: below 1, the more so the
    // more its neighbours are correlated (fewer independent pixels, and a plane takes more of
    // it). Measured on grain of the correlation found, by the same patch statistic.
    const vec3 q = quartile_ratio(g);
    for (vec3& v : g.sigma) v /= glm::sqrt(q);
    return g;
}

float measure_softness(const Image& photo) {
    const float raw = raw_edge_sigma(photo);
    if (raw < 0) return -1;
    const float ref = render_edge_sigma();
    // Widths of Gaussians add in quadrature: what the plate has beyond a render's edge.
    return std::sqrt(std::max(0.0f, raw * raw - ref * ref));
}

Image gaussian_blur(const Image& image, float sigma) {
    if (!(sigma > 0.05f)) return image;
    const std::vector<float> k = gaussian_kernel(sigma);
    const int r = int(k.size() / 2), W = image.width(), H = image.height();
    Image tmp(W, H), out(W, H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            vec3 s(0.0f);
            for (int i = -r; i <= r; ++i) s += k[size_t(i + r)] * image.at(std::clamp(x + i, 0, W - 1), y);
            tmp.at(x, y) = s;
        }
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            vec3 s(0.0f);
            for (int i = -r; i <= r; ++i) s += k[size_t(i + r)] * tmp.at(x, std::clamp(y + i, 0, H - 1));
            out.at(x, y) = s;
        }
    return out;
}

Image grain_field(const GrainProfile& profile, int width, int height, uint64_t seed) {
    Image white(width, height);
    for (int y = 0; y < height; ++y) {
        Rng rng(seed, uint64_t(y));
        for (int x = 0; x < width; ++x) {
            // Box-Muller: three normals per pixel.
            vec3 n;
            for (int c = 0; c < 3; ++c) {
                const float u1 = std::max(rng.uniform(), 1e-12f), u2 = rng.uniform();
                n[c] = std::sqrt(-2.0f * std::log(u1)) * std::cos(2.0f * kPi * u2);
            }
            white.at(x, y) = n;
        }
    }
    // Shared and separate grain between the channels: a Cholesky factor of their correlation.
    glm::mat3 L(0.0f);
    const glm::mat3& C = profile.channel_correlation;
    bool ok = true;
    for (int i = 0; i < 3 && ok; ++i)
        for (int j = 0; j <= i; ++j) {
            float s = C[i][j];
            for (int k = 0; k < j; ++k) s -= L[i][k] * L[j][k];
            if (i == j) {
                ok = s > 1e-4f;
                L[i][i] = ok ? std::sqrt(s) : 0.0f;
            } else {
                L[i][j] = s / L[j][j];
            }
        }
    if (!ok) L = glm::mat3(1.0f);
    for (size_t i = 0; i < white.size(); ++i) {
        const vec3 n = white[i];
        white[i] = vec3(L[0][0] * n.x, L[1][0] * n.x + L[1][1] * n.y, L[2][0] * n.x + L[2][1] * n.y + L[2][2] * n.z);
    }
    if (profile.correlation_px > 0.3f) {
        const std::vector<float> k = gaussian_kernel(profile.correlation_px);
        double k2 = 0;
        for (float v : k) k2 += double(v) * v;
        white = gaussian_blur(white, profile.correlation_px);
        // A blur of white noise keeps sum(k^2) of its variance, per axis.
        for (size_t i = 0; i < white.size(); ++i) white[i] *= float(1.0 / k2);
    }
    return white;
}

PlateMatch match_plate(const Image& augmented, const Image& photo, const Image& alpha, const Image& dL,
                       const GrainProfile& grain, float blur_px, uint64_t seed) {
    const int W = augmented.width(), H = augmented.height();
    Image objects(W, H), change(W, H);
    for (size_t i = 0; i < objects.size(); ++i) {
        const float a = alpha[i].x;
        // alpha objects + (1 - alpha) photo + dL = augmented (render/compositing.h). Where no
        // object is seen the change is the composite's own (a denoised one's, too).
        change[i] = a > 0 ? dL[i] : augmented[i] - photo[i];
        objects[i] = a > 0 ? augmented[i] - (1 - a) * photo[i] - dL[i] : vec3(0.0f);
    }
    const Image ob = gaussian_blur(objects, blur_px), ab = gaussian_blur(alpha, blur_px),
                db = gaussian_blur(change, blur_px);
    PlateMatch m{Image(W, H), Image(W, H)};
    const Image noise = grain.empty() ? Image() : grain_field(grain, W, H, seed);
    for (size_t i = 0; i < objects.size(); ++i) {
        const float a = std::clamp(ab[i].x, 0.0f, 1.0f);
        vec3 g(0.0f);
        if (!noise.empty() && a > 0) {
            // The object's own brightness picks the grain's strength, as the plate's did.
            const float level = luminance(ob[i] / a);
            g = a * grain.sigma_at(level) * noise[i];
        }
        m.grain[i] = g;
        m.beauty[i] = ob[i] + (1 - a) * photo[i] + db[i] + g;
    }
    return m;
}

PlateFigures measure_plate(const Image& photo) {
    return PlateFigures{measure_grain(photo), measure_softness(photo)};
}

std::string PlateFigures::summary() const {
    char line[200];
    if (grain.empty()) {
        std::snprintf(line, sizeof line, "no grain measured (too few flat patches), softness %.2f px",
                      double(std::max(softness_px, 0.0f)));
    } else {
        const size_t mid = grain.levels.size() / 2;
        std::snprintf(line, sizeof line, "grain %.3g at luminance %.3g (green; %zu levels, correlation %.2f px), softness %.2f px%s",
                      double(grain.sigma[mid].y), double(grain.levels[mid]), grain.levels.size(),
                      double(grain.correlation_px), double(std::max(softness_px, 0.0f)),
                      softness_px < 0 ? " (too few edges to measure)" : "");
    }
    return line;
}

PlateMatch match_plate(const Image& augmented, const Image& photo, const Image& alpha, const Image& dL,
                       const PlateFigures& figures, uint64_t seed) {
    return match_plate(augmented, photo, alpha, dL, figures.grain, std::max(figures.softness_px, 0.0f), seed);
}

std::vector<double> noise_power_bands(const Image& image, int x0, int y0, int size, int bands) {
    // The patch's luminance less a fitted plane.
    std::vector<double> v(size_t(size) * size);
    double sum = 0, sx = 0, sy = 0, sxx = 0;
    const double c = 0.5 * (size - 1);
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            const double l = luminance(image.at(x0 + i, y0 + j));
            v[size_t(j) * size + i] = l;
            sum += l;
            sx += l * (i - c);
            sy += l * (j - c);
        }
    for (int i = 0; i < size; ++i) sxx += (i - c) * (i - c);
    sxx *= size;
    const double a = sum / (double(size) * size), bx = sx / sxx, by = sy / sxx;
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) v[size_t(j) * size + i] -= a + bx * (i - c) + by * (j - c);
    // A plain 2D DFT by rows then columns (patches are small).
    std::vector<std::complex<double>> f(v.begin(), v.end()), t(f.size());
    auto dft = [&](bool rows) {
        for (int line = 0; line < size; ++line)
            for (int k = 0; k < size; ++k) {
                std::complex<double> s = 0;
                for (int n = 0; n < size; ++n) {
                    const size_t at = rows ? size_t(line) * size + n : size_t(n) * size + line;
                    s += f[at] * std::polar(1.0, -2.0 * double(kPi) * k * n / size);
                }
                t[rows ? size_t(line) * size + k : size_t(k) * size + line] = s;
            }
        f.swap(t);
    };
    dft(true);
    dft(false);
    std::vector<double> power(size_t(bands), 0.0);
    std::vector<int> count(size_t(bands), 0);
    for (int ky = 0; ky < size; ++ky)
        for (int kx = 0; kx < size; ++kx) {
            if (kx == 0 && ky == 0) continue;
            const double fx = (kx <= size / 2 ? kx : kx - size) / double(size);
            const double fy = (ky <= size / 2 ? ky : ky - size) / double(size);
            const double r = std::sqrt(fx * fx + fy * fy) / 0.5;  // 1 at the Nyquist frequency
            if (r > 1) continue;
            const int b = std::min(bands - 1, int(r * bands));
            power[size_t(b)] += std::norm(f[size_t(ky) * size + kx]) / (double(size) * size);
            ++count[size_t(b)];
        }
    for (int b = 0; b < bands; ++b) power[size_t(b)] /= std::max(1, count[size_t(b)]);
    return power;
}

}  // namespace dp
