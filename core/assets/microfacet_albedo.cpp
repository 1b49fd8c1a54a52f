#include "assets/microfacet_albedo.h"

#include <algorithm>
#include <array>

#include <tbb/parallel_for.h>

#include "assets/microfacet.h"
#include "assets/scattering.h"

namespace dp {

namespace {

constexpr int N = kGgxAlbedoSize, K = kGgxAlbedoIors;
constexpr int kStrata = 48;  // kStrata^2 quadrature points a node
constexpr float kMaxIor = 5.0f;

struct AlbedoTable {
    std::array<float, N * N> e;  // [j * N + i]: roughness j, mu i
    std::array<float, N> e_avg;
    std::array<float, K * N * N> ew;  // [(k * N + j) * N + i]: ior k, roughness j, mu i
    std::array<float, K * N> ew_avg;
};

float ior_node(int k) {
    const float t = (kMaxIor - 1) / (kMaxIor + 1) * k / (K - 1);  // (ior - 1) / (ior + 1)
    return (1 + t) / (1 - t);
}

// The mu nodes crowd towards grazing, where E changes fastest at low roughness.
float mu_node(int i) {
    const float x = float(i) / (N - 1);
    return x * x;
}

// The Fresnel weight w(c) = (F(c) - F0) / (1 - F0) of each ior node on a regular grid of
// c = wo.m, read linearly: F has a finite slope everywhere seen from outside, so 1024 steps
// hold it to 1e-6, and the quadrature below spends a lerp per point instead of a Fresnel.
struct FresnelWeights {
    static constexpr int kSteps = 1024;
    std::array<float, K * (kSteps + 1)> w;
    FresnelWeights() {
        for (int k = 0; k < K; ++k) {
            const float ior = ior_node(k), f0 = dielectric_f0(ior);
            for (int c = 0; c <= kSteps; ++c)
                w[k * (kSteps + 1) + c] = (fresnel_dielectric(float(c) / kSteps, 1 / ior) - f0) / (1 - f0);
        }
    }
    float at(int k, float c) const {
        const float s = std::clamp(c, 0.0f, 1.0f) * kSteps;
        const int i = std::min(int(s), kSteps - 1);
        const float* row = &w[k * (kSteps + 1)];
        return row[i] + (s - i) * (row[i + 1] - row[i]);
    }
};

// One node of both tables: midpoint quadrature over the visible-normal sample space, where the
// F = 1 lobe's weight is G2 / G1. u.y -> 1 maps to GGX's long tail of steep normals, whose
// reflections leave below the horizon: u.y = 1 - (1 - t)^2 puts strata there (0.2% of the
// albedo at roughness 0.2).
void node(float mu, float roughness, const FresnelWeights& fw, float& e, float* ew /* K values, stride N * N */) {
    const Ggx ggx(ggx_alpha(roughness));
    const vec3 wo(std::sqrt(std::max(0.0f, 1 - mu * mu)), 0.0f, mu);
    const float lambda_o = ggx.lambda(wo);
    double sum = 0, sum_w[K] = {};
    for (int b = 0; b < kStrata; ++b) {
        const float s = 1 - (b + 0.5f) / kStrata;  // 1 - t
        for (int a = 0; a < kStrata; ++a) {
            const vec3 m = ggx.sample_visible(wo, vec2((a + 0.5f) / kStrata, 1 - s * s));
            const vec3 wi = reflect_about(wo, m);
            if (wi.z <= 0) continue;
            const double g = 2 * s * (1 + lambda_o) / (1 + lambda_o + ggx.lambda(wi));  // times du.y/dt
            sum += g;
            const float c = glm::dot(wo, m);
            for (int k = 1; k < K; ++k) sum_w[k] += g * fw.at(k, c);  // ior 1 reflects nothing: w = 0
        }
    }
    constexpr double n = double(kStrata) * kStrata;
    e = float(std::min(1.0, sum / n));
    for (int k = 0; k < K; ++k) ew[k * N * N] = float(std::clamp(sum_w[k] / n, 0.0, 1.0));
}

// 2 * integral of E(mu) mu over [0, 1] for E linear between nodes: Simpson's rule is exact
// on each piece, whose integrand E(mu) mu is quadratic.
float row_average(const float* e) {
    double sum = 0;
    for (int i = 0; i + 1 < N; ++i) {
        const double a = mu_node(i), b = mu_node(i + 1), m = (a + b) / 2;
        sum += (b - a) / 6 * (e[i] * a + 4 * 0.5 * (e[i] + e[i + 1]) * m + e[i + 1] * b);
    }
    return float(2 * sum);
}

// Rows are independent, so the threads change nothing in the values.
AlbedoTable build_table() {
    AlbedoTable t;
    const FresnelWeights fw;
    tbb::parallel_for(0, N, [&](int j) {
        const float roughness = float(j) / (N - 1);
        for (int i = 0; i < N; ++i)
            node(std::max(1e-3f, mu_node(i)), roughness, fw, t.e[j * N + i], &t.ew[j * N + i]);
        t.e_avg[j] = row_average(&t.e[j * N]);
        for (int k = 0; k < K; ++k) t.ew_avg[k * N + j] = row_average(&t.ew[(k * N + j) * N]);
    });
    return t;
}

const AlbedoTable& table() {
    static const AlbedoTable t = build_table();
    return t;
}

// A position between two nodes: the lower index and the fraction towards the next.
struct Cell {
    int k;
    float f;
};

Cell roughness_cell(float r) {
    const float s = std::clamp(r, 0.0f, 1.0f) * (N - 1);
    const int j = std::min(int(s), N - 2);
    return {j, s - j};
}

// Linear in mu between nodes (row_average relies on it).
Cell mu_cell(float mu) {
    mu = std::clamp(mu, 0.0f, 1.0f);
    const int i = std::min(int(std::sqrt(mu) * (N - 1)), N - 2);
    const float a = mu_node(i), b = mu_node(i + 1);
    return {i, std::clamp((mu - a) / (b - a), 0.0f, 1.0f)};
}

Cell ior_cell(float ior) {
    ior = std::clamp(ior, 1.0f, kMaxIor);
    const float s = (ior - 1) / (ior + 1) / ((kMaxIor - 1) / (kMaxIor + 1)) * (K - 1);
    const int k = std::min(int(s), K - 2);
    return {k, s - k};
}

// Bilinear in (roughness, mu) on the N x N slice at `e`.
float bilinear(const float* e, Cell r, Cell mu) {
    auto row = [&](int j) { return (1 - mu.f) * e[j * N + mu.k] + mu.f * e[j * N + mu.k + 1]; };
    return (1 - r.f) * row(r.k) + r.f * row(r.k + 1);
}

float linear(const float* v, Cell c) { return (1 - c.f) * v[c.k] + c.f * v[c.k + 1]; }

}  // namespace

float ggx_albedo(float mu, float roughness) {
    return bilinear(table().e.data(), roughness_cell(roughness), mu_cell(mu));
}

float ggx_average_albedo(float roughness) { return linear(table().e_avg.data(), roughness_cell(roughness)); }

float ggx_dielectric_albedo(float mu, float roughness, float ior) {
    const AlbedoTable& t = table();
    const Cell r = roughness_cell(roughness), m = mu_cell(mu), c = ior_cell(ior);
    return (1 - c.f) * bilinear(&t.ew[c.k * N * N], r, m) + c.f * bilinear(&t.ew[(c.k + 1) * N * N], r, m);
}

float ggx_dielectric_average_albedo(float roughness, float ior) {
    const AlbedoTable& t = table();
    const Cell r = roughness_cell(roughness), c = ior_cell(ior);
    return (1 - c.f) * linear(&t.ew_avg[c.k * N], r) + c.f * linear(&t.ew_avg[(c.k + 1) * N], r);
}

}  // namespace dp
