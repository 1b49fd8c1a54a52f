// GGX and the principled (glTF metallic-roughness) BSDF: sample() follows pdf() (pbrt-v4 style
// chi-square over the sphere), the pdf integrates to at most 1, sample weights are eval/pdf,
// energy (white furnace), reciprocity, the adjoint that photons use, and the closed forms at the
// ends of the parameter ranges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <optional>
#include <vector>

#include "assets/microfacet.h"
#include "assets/microfacet_albedo.h"
#include "assets/principled.h"
#include "assets/scattering.h"
#include "base/rng.h"
#include "base/sampling.h"
#include "common/chi_square.h"

using namespace dp;

namespace {

constexpr double kPiD = std::numbers::pi;
const float kRoughnesses[] = {0.1f, 0.3f, 0.6f, 1.0f};
const float kAngles[] = {2.0f, 60.0f, 85.0f};  // incidence from the normal, degrees

vec3 direction(double theta, double phi) {
    return vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
}
vec3 incident(float degrees) { return direction(degrees * kPiD / 180, 0.3); }

// Adaptive Simpson's rule: halves [a, b] until the two halves agree with the whole.
double simpson(const std::function<double(double)>& f, double a, double b, double fa, double fm, double fb,
               double whole, double eps, int depth) {
    const double m = (a + b) / 2, lm = (a + m) / 2, rm = (m + b) / 2;
    const double flm = f(lm), frm = f(rm);
    const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
    const double delta = left + right - whole;
    if (depth <= 0 || std::abs(delta) <= 15 * eps) return left + right + delta / 15;
    return simpson(f, a, m, fa, flm, fm, left, eps / 2, depth - 1) +
           simpson(f, m, b, fm, frm, fb, right, eps / 2, depth - 1);
}

// Adaptive Simpson on [a, b] after a forced split into `pieces`, so that a lobe narrower than
// the interval is not stepped over.
double integrate(const std::function<double(double)>& f, double a, double b, double eps, int pieces = 2) {
    double sum = 0;
    for (int k = 0; k < pieces; ++k) {
        const double x0 = a + (b - a) * k / pieces, x1 = a + (b - a) * (k + 1) / pieces, xm = (x0 + x1) / 2;
        const double f0 = f(x0), fm = f(xm), f1 = f(x1);
        sum += simpson(f, x0, x1, f0, fm, f1, (x1 - x0) / 6 * (f0 + 4 * fm + f1), eps / pieces, 12);
    }
    return sum;
}

// Integral of a density over the patch [t0, t1] x [p0, p1] of (theta, phi): dw = sin(theta).
double patch_integral(const std::function<double(const vec3&)>& pdf, double t0, double t1, double p0, double p1) {
    return integrate(
        [&](double t) {
            return std::sin(t) * integrate([&](double p) { return pdf(direction(t, p)); }, p0, p1, 1e-6);
        },
        t0, t1, 1e-6);
}

struct SphereChiSquare {
    test::ChiSquare chi;
    double pdf_integral = 0;  // the bins' expectations summed: the pdf's integral
    int failures = 0;
};

// Pearson's test of n draws against the pdf over a 12 x 24 (theta, phi) grid of the sphere,
// plus a bin for the draws that failed, which expects the pdf's missing mass.
SphereChiSquare sphere_chi_square(const std::function<std::optional<vec3>(Rng&)>& draw,
                                  const std::function<double(const vec3&)>& pdf, int n, uint64_t seed) {
    constexpr int kTheta = 12, kPhi = 24;
    std::vector<double> observed(kTheta * kPhi + 1, 0.0), expected(kTheta * kPhi + 1, 0.0);
    SphereChiSquare r;
    Rng rng(seed, 7);
    for (int k = 0; k < n; ++k) {
        const std::optional<vec3> w = draw(rng);
        if (!w) {
            ++r.failures;
            continue;
        }
        const double theta = std::acos(std::clamp(double(w->z), -1.0, 1.0));
        double phi = std::atan2(double(w->y), double(w->x));
        if (phi < 0) phi += 2 * kPiD;
        const int i = std::min(int(theta / kPiD * kTheta), kTheta - 1);
        const int j = std::min(int(phi / (2 * kPiD) * kPhi), kPhi - 1);
        observed[i * kPhi + j] += 1;
    }
    for (int i = 0; i < kTheta; ++i)
        for (int j = 0; j < kPhi; ++j) {
            const double mass = patch_integral(pdf, kPiD * i / kTheta, kPiD * (i + 1) / kTheta, 2 * kPiD * j / kPhi,
                                               2 * kPiD * (j + 1) / kPhi);
            r.pdf_integral += mass;
            expected[i * kPhi + j] = n * mass;
        }
    observed.back() = r.failures;
    expected.back() = n * std::max(0.0, 1 - r.pdf_integral);
    r.chi = test::chi_square_test(observed, expected);
    return r;
}

// Per configuration: a 1% level over the 96 configurations of this file (Sidak).
constexpr double kMinP = 1e-4;
constexpr int kChiSamples = 100000;

PrincipledParams conductor(float roughness, vec3 base = vec3(0.9f, 0.6f, 0.3f)) {
    PrincipledParams p;
    p.base_colour = base;
    p.metallic = 1;
    p.roughness = roughness;
    return p;
}

PrincipledParams glass(float roughness, vec3 tint = vec3(0.8f, 0.9f, 1.0f)) {
    PrincipledParams p;
    p.base_colour = tint;
    p.roughness = roughness;
    p.transmission = 1;
    return p;
}

PrincipledParams mixture(float roughness) {
    PrincipledParams p;
    p.base_colour = vec3(0.7f, 0.4f, 0.2f);
    p.metallic = 0.3f;
    p.roughness = roughness;
    p.ior = 1.45f;
    p.specular = 0.8f;
    p.specular_colour = vec3(1.0f, 0.8f, 0.6f);
    p.transmission = 0.4f;
    return p;
}

// The chi-square of one material over the roughnesses and angles; returns the smallest p.
double check_sampling(const char* name, const std::function<PrincipledParams(float)>& make, bool inside,
                      uint64_t seed) {
    double min_p = 1;
    for (float r : kRoughnesses)
        for (float a : kAngles) {
            const PrincipledBsdf bsdf(make(r));
            const vec3 wo = inside ? -incident(a) : incident(a);
            const SphereChiSquare c = sphere_chi_square(
                [&](Rng& rng) -> std::optional<vec3> {
                    const BsdfSample s = bsdf.sample(wo, vec3(rng.uniform(), rng.uniform(), rng.uniform()));
                    if (!s) return std::nullopt;
                    return s.wi;
                },
                [&](const vec3& wi) { return double(bsdf.pdf(wo, wi)); }, kChiSamples, seed++);
            EXPECT_GT(c.chi.p_value, kMinP) << name << " roughness " << r << " angle " << a << " chi2 "
                                            << c.chi.statistic << " dof " << c.chi.dof << " failures " << c.failures;
            EXPECT_LE(c.pdf_integral, 1 + 1e-3) << name << " roughness " << r << " angle " << a;
            min_p = std::min(min_p, c.chi.p_value);
        }
    std::printf("  %-32s min p = %.3g\n", name, min_p);
    return min_p;
}

enum class Side { Both, Reflected, Transmitted };

// Mean sample weight: the directional albedo of wo (of one side's directions only, on request).
vec3 albedo(const PrincipledBsdf& bsdf, const vec3& wo, int n, uint64_t seed, Transport mode = Transport::Radiance,
            Side side = Side::Both) {
    Rng rng(seed, 11);
    dvec3 sum(0.0);
    for (int k = 0; k < n; ++k) {
        // Stratified in u.z: the lobe choice, whose variance would dominate.
        const BsdfSample s = bsdf.sample(wo, vec3(rng.uniform(), rng.uniform(), (k + rng.uniform()) / n), mode);
        if (!s) continue;
        if ((side == Side::Reflected && s.transmitted) || (side == Side::Transmitted && !s.transmitted)) continue;
        sum += dvec3(s.weight);
    }
    return vec3(sum / double(n));
}

// Below this f (per steradian) the pair is in a lobe's far tail, where f is a difference of
// nearly equal floats (1 - F near total internal reflection) and only its smallness matters.
constexpr float kNegligibleF = 1e-3f;

float relative_error(const vec3& a, const vec3& b) {
    return glm::length(a - b) / std::max(glm::length(b), 1e-12f);
}

}  // namespace

TEST(GgxMicrofacet, NormalsAreNormalisedInProjectedArea) {
    for (float r : {0.1f, 0.3f, 0.6f, 1.0f}) {
        const Ggx ggx(ggx_alpha(r));
        const double projected = integrate(
            [&](double t) {
                return 2 * kPiD * std::sin(t) * std::cos(t) * ggx.D(direction(t, 0));
            },
            0, kPiD / 2, 1e-9, 64);
        EXPECT_NEAR(projected, 1.0, 1e-4) << "roughness " << r;
    }
}

TEST(GgxMicrofacet, SmithMaskingMatchesTheMicrofacetsProjectedArea) {
    // G1(w) w.z is the visible microfacet area projected on w (Heitz 2014, eq. 17), and the
    // visible normals' density integrates to 1.
    for (float r : {0.1f, 0.3f, 0.6f, 1.0f})
        for (float a : kAngles) {
            const Ggx ggx(ggx_alpha(r));
            const vec3 w = incident(a);
            const double visible = patch_integral(
                [&](const vec3& m) { return double(std::max(0.0f, glm::dot(w, m)) * ggx.D(m)); }, 0, kPiD / 2, 0,
                2 * kPiD);
            EXPECT_NEAR(ggx.G1(w) * visible / w.z, 1.0, 2e-3) << "roughness " << r << " angle " << a;
            const double mass =
                patch_integral([&](const vec3& m) { return double(ggx.visible_pdf(w, m)); }, 0, kPiD / 2, 0, 2 * kPiD);
            EXPECT_NEAR(mass, 1.0, 2e-3) << "roughness " << r << " angle " << a;
        }
}

TEST(GgxMicrofacet, VisibleNormalSamplesFollowTheirPdf) {
    double min_p = 1;
    uint64_t seed = 100;
    for (float r : kRoughnesses)
        for (float a : kAngles) {
            const Ggx ggx(ggx_alpha(r));
            const vec3 w = incident(a);
            const SphereChiSquare c = sphere_chi_square(
                [&](Rng& rng) -> std::optional<vec3> {
                    return ggx.sample_visible(w, vec2(rng.uniform(), rng.uniform()));
                },
                [&](const vec3& m) { return double(ggx.visible_pdf(w, m)); }, kChiSamples, seed++);
            EXPECT_GT(c.chi.p_value, kMinP) << "roughness " << r << " angle " << a << " chi2 " << c.chi.statistic;
            min_p = std::min(min_p, c.chi.p_value);
        }
    std::printf("  %-32s min p = %.3g\n", "GGX visible normals", min_p);
}

TEST(GgxMicrofacet, AlbedoTableMatchesMonteCarlo) {
    // Between the table's nodes, against random visible-normal draws of the F = 1 lobe.
    Rng rng(5, 5);
    for (float r : {0.12f, 0.27f, 0.5f, 0.77f, 0.95f})
        for (float mu : {0.09f, 0.3f, 0.55f, 0.93f}) {
            const Ggx ggx(ggx_alpha(r));
            const vec3 wo(std::sqrt(1 - mu * mu), 0, mu);
            const int n = 100000;
            double sum = 0;
            for (int k = 0; k < n; ++k) {
                const vec3 wi = reflect_about(wo, ggx.sample_visible(wo, vec2(rng.uniform(), rng.uniform())));
                if (wi.z > 0) sum += ggx.G2(wo, wi) / ggx.G1(wo);
            }
            EXPECT_NEAR(ggx_albedo(mu, r), sum / n, 4e-3) << "roughness " << r << " mu " << mu;
        }
}

TEST(PrincipledBsdf, ConductorSamplesFollowThePdf) {
    EXPECT_GT(check_sampling("conductor", [](float r) { return conductor(r); }, false, 200), kMinP);
}

TEST(PrincipledBsdf, OpaqueDielectricSamplesFollowThePdf) {
    // Specular layer alone (black base), then over a diffuse base.
    auto layer = [](float r) {
        PrincipledParams p;
        p.base_colour = vec3(0);
        p.roughness = r;
        return p;
    };
    auto plastic = [](float r) {
        PrincipledParams p;
        p.base_colour = vec3(0.2f, 0.5f, 0.8f);
        p.roughness = r;
        return p;
    };
    EXPECT_GT(check_sampling("dielectric layer", layer, false, 300), kMinP);
    EXPECT_GT(check_sampling("dielectric over diffuse", plastic, false, 320), kMinP);
}

TEST(PrincipledBsdf, RoughGlassSamplesFollowThePdfFromBothSides) {
    EXPECT_GT(check_sampling("glass from outside", [](float r) { return glass(r); }, false, 400), kMinP);
    EXPECT_GT(check_sampling("glass from inside", [](float r) { return glass(r); }, true, 420), kMinP);
}

TEST(PrincipledBsdf, FullMixtureSamplesFollowThePdf) {
    EXPECT_GT(check_sampling("mixture from outside", mixture, false, 500), kMinP);
    EXPECT_GT(check_sampling("mixture from inside", mixture, true, 520), kMinP);
}

TEST(PrincipledBsdf, PdfIntegratesToAtMostOneOverTheSphere) {
    // Stratified uniform directions; the roughest lobes only, where this estimate is sharp (the
    // chi-square tests integrate every configuration's pdf by quadrature).
    const int n_side = 250;
    for (float r : {0.3f, 0.6f, 1.0f})
        for (const PrincipledParams& p : {conductor(r), glass(r), mixture(r)})
            for (float a : kAngles)
                for (bool inside : {false, true}) {
                    const PrincipledBsdf bsdf(p);
                    const vec3 wo = inside ? -incident(a) : incident(a);
                    Rng rng(9, 9);
                    double sum = 0, sum2 = 0;
                    for (int i = 0; i < n_side; ++i)
                        for (int j = 0; j < n_side; ++j) {
                            const vec3 wi = sample_uniform_sphere(
                                vec2((i + rng.uniform()) / n_side, (j + rng.uniform()) / n_side));
                            const double v = 4 * kPiD * bsdf.pdf(wo, wi);
                            sum += v;
                            sum2 += v * v;
                        }
                    const double n = double(n_side) * n_side, mean = sum / n;
                    const double sigma = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
                    EXPECT_LE(mean, 1 + 4 * sigma + 1e-3)
                        << "roughness " << r << " angle " << a << " inside " << inside;
                    EXPECT_GT(mean, 0.3) << "roughness " << r << " angle " << a << " inside " << inside;
                }
}

TEST(PrincipledBsdf, SampleWeightIsEvalOverPdf) {
    Rng rng(12, 12);
    int checked = 0;
    for (float r : {0.05f, 0.3f, 1.0f})
        for (const PrincipledParams& p : {conductor(r), glass(r), mixture(r)})
            for (Transport mode : {Transport::Radiance, Transport::Importance})
                for (int k = 0; k < 2000; ++k) {
                    const PrincipledBsdf bsdf(p);
                    const vec3 wo = sample_uniform_sphere(vec2(rng.uniform(), rng.uniform()));
                    const BsdfSample s = bsdf.sample(wo, vec3(rng.uniform(), rng.uniform(), rng.uniform()), mode);
                    if (!s) continue;
                    const float pdf = bsdf.pdf(wo, s.wi);
                    const vec3 f = bsdf.eval(wo, s.wi, mode);
                    ASSERT_NEAR(s.pdf, pdf, 1e-4f * pdf) << "roughness " << r;
                    ASSERT_LT(relative_error(s.weight, f / pdf), 1e-4f) << "roughness " << r;
                    ASSERT_EQ(s.transmitted, (s.wi.z < 0) != (wo.z < 0));
                    ++checked;
                }
    EXPECT_GT(checked, 30000);
}

TEST(PrincipledBsdf, WhiteConductorKeepsItsEnergyAtEveryRoughness) {
    // F = 1 (white base): single scattering loses up to 70% at roughness 1; the compensation
    // lobe puts it back.
    std::printf("  white conductor, albedo by roughness (angles 2, 30, 60, 75, 85 deg):\n");
    for (float r : {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f, 0.9f, 1.0f}) {
        const PrincipledBsdf bsdf(conductor(r, vec3(1)));
        std::printf("    %.1f:", r);
        for (float a : {2.0f, 30.0f, 60.0f, 75.0f, 85.0f}) {
            const float e = albedo(bsdf, incident(a), 40000, 13).x;
            std::printf(" %.4f (single %.3f)", e, ggx_albedo(std::cos(a * float(kPiD) / 180), r));
            EXPECT_NEAR(e, 1.0f, 0.01f) << "roughness " << r << " angle " << a;
        }
        std::printf("\n");
    }
}

TEST(PrincipledBsdf, DielectricEnergyIsMeasured) {
    // A white base under the layer gets what the layer does not reflect: within 1% of 1. Rough
    // glass is not compensated, so what one bounce off the microfacets loses (mostly total
    // internal reflections sent into the surface, from inside) stays lost: its floors are the
    // measured figures (docs/materials.md) less 0.01.
    struct Floor {
        float roughness, outside[3], inside[3];
    };
    const Floor floors[] = {{0.1f, {0.99f, 0.99f, 0.984f}, {0.99f, 0.99f, 0.982f}},
                            {0.3f, {0.989f, 0.983f, 0.911f}, {0.98f, 0.96f, 0.857f}},
                            {0.6f, {0.973f, 0.923f, 0.884f}, {0.85f, 0.73f, 0.754f}},
                            {1.0f, {0.882f, 0.731f, 0.741f}, {0.409f, 0.502f, 0.504f}}};
    std::printf("  white glass R+T (importance) outside | inside | white plastic, angles 2, 60, 85 deg:\n");
    for (const Floor& floor : floors) {
        const PrincipledBsdf g(glass(floor.roughness, vec3(1)));
        PrincipledParams white;
        white.base_colour = vec3(1);
        white.roughness = floor.roughness;
        const PrincipledBsdf plastic(white);
        float out[3], in[3], diffuse[3];
        for (int k = 0; k < 3; ++k) {
            out[k] = albedo(g, incident(kAngles[k]), 50000, 14, Transport::Importance).x;
            in[k] = albedo(g, -incident(kAngles[k]), 50000, 15, Transport::Importance).x;
            diffuse[k] = albedo(plastic, incident(kAngles[k]), 50000, 16).x;
            EXPECT_LE(out[k], 1.005f) << "roughness " << floor.roughness << " angle " << kAngles[k];
            EXPECT_LE(in[k], 1.005f) << "roughness " << floor.roughness << " angle " << kAngles[k];
            EXPECT_GT(out[k], floor.outside[k]) << "roughness " << floor.roughness << " angle " << kAngles[k];
            EXPECT_GT(in[k], floor.inside[k]) << "roughness " << floor.roughness << " angle " << kAngles[k];
            EXPECT_NEAR(diffuse[k], 1.0f, 0.01f) << "roughness " << floor.roughness << " angle " << kAngles[k];
        }
        std::printf("    %.1f: %.4f %.4f %.4f | %.4f %.4f %.4f | %.4f %.4f %.4f\n", floor.roughness, out[0], out[1],
                    out[2], in[0], in[1], in[2], diffuse[0], diffuse[1], diffuse[2]);
    }
}

TEST(PrincipledBsdf, ReflectionIsReciprocal) {
    Rng rng(17, 17);
    int checked = 0;
    for (float r : {0.1f, 0.4f, 1.0f}) {
        for (PrincipledParams p : {conductor(r), mixture(r), glass(r)}) {
            p.transmission = std::min(p.transmission, 0.5f);  // keep the diffuse base in the mix
            const PrincipledBsdf bsdf(p);
            for (int k = 0; k < 2000; ++k) {
                vec3 wo = sample_uniform_sphere(vec2(rng.uniform(), rng.uniform()));
                vec3 wi = sample_uniform_sphere(vec2(rng.uniform(), rng.uniform()));
                if (wo.z * wi.z < 0) wi.z = -wi.z;  // the same side: reflection (inside too)
                const vec3 f_oi = bsdf.eval(wo, wi) / std::abs(wi.z), f_io = bsdf.eval(wi, wo) / std::abs(wo.z);
                if (glm::length(f_oi) < kNegligibleF) continue;
                ASSERT_LT(relative_error(f_io, f_oi), 1e-3f) << "roughness " << r << " sample " << k;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 10000);
}

TEST(PrincipledBsdf, ImportanceTransportIsTheAdjointOfRadiance) {
    // f*(wo, wi) = f(wi, wo), the roles of the two sides (and so eta) swapped: the eta^2 of
    // radiance transport is checked against its own mirror image.
    Rng rng(18, 18);
    int checked = 0;
    for (float r : {0.1f, 0.4f, 1.0f}) {
        const PrincipledBsdf bsdf(mixture(r));
        for (int k = 0; k < 4000; ++k) {
            const vec3 wo = sample_uniform_sphere(vec2(rng.uniform(), rng.uniform()));
            vec3 wi = sample_uniform_sphere(vec2(rng.uniform(), rng.uniform()));
            if (wo.z * wi.z > 0) wi.z = -wi.z;  // transmission
            const vec3 adjoint = bsdf.eval(wo, wi, Transport::Importance) / std::abs(wi.z);
            const vec3 swapped = bsdf.eval(wi, wo, Transport::Radiance) / std::abs(wo.z);
            if (glm::length(swapped) < kNegligibleF) continue;
            ASSERT_LT(relative_error(adjoint, swapped), 1e-3f) << "roughness " << r << " sample " << k;
            // And radiance itself is not symmetric: eta^2 apart.
            const vec3 radiance = bsdf.eval(wo, wi, Transport::Radiance) / std::abs(wi.z);
            const float eta = wo.z > 0 ? 1.45f : 1 / 1.45f;
            ASSERT_LT(relative_error(radiance * eta * eta, adjoint), 1e-5f);
            ++checked;
        }
    }
    EXPECT_GT(checked, 1000);
}

TEST(PrincipledBsdf, NearSmoothLimitMatchesFresnel) {
    // At the roughness below which callers switch to the specular code, the rough lobes carry
    // what the mirror and glass do: reflectance F, transmitted flux 1 - F, radiance (1 - F)/eta^2.
    const float r = kSpecularRoughness;
    PrincipledParams layer;
    layer.base_colour = vec3(0);
    layer.roughness = r;
    const vec3 f0(0.95f, 0.64f, 0.54f);
    for (float a : kAngles) {
        const vec3 wo = incident(a);
        const float F = fresnel_dielectric(wo.z, 1 / 1.5f);
        EXPECT_NEAR(albedo(PrincipledBsdf(layer), wo, 50000, 19).x, F, 0.01f * F) << "angle " << a;
        const vec3 metal = albedo(PrincipledBsdf(conductor(r, f0)), wo, 50000, 20);
        EXPECT_LT(relative_error(metal, fresnel_schlick(f0, wo.z)), 0.01f) << "angle " << a;
        const PrincipledBsdf g(glass(r, vec3(1)));
        const float t_flux = albedo(g, wo, 50000, 21, Transport::Importance, Side::Transmitted).x;
        const float t_radiance = albedo(g, wo, 50000, 21, Transport::Radiance, Side::Transmitted).x;
        EXPECT_NEAR(t_flux, 1 - F, 0.01f) << "angle " << a;
        EXPECT_NEAR(t_radiance, (1 - F) / (1.5f * 1.5f), 0.01f) << "angle " << a;
        // From inside, radiance leaving into air is expanded by eta^2; beyond the critical angle
        // (41.8 degrees) all of it reflects.
        const float F_in = fresnel_dielectric(wo.z, 1.5f);
        EXPECT_NEAR(albedo(g, -wo, 50000, 22, Transport::Importance, Side::Reflected).x, F_in, 0.01f) << "angle " << a;
        EXPECT_NEAR(albedo(g, -wo, 50000, 22, Transport::Radiance, Side::Transmitted).x, (1 - F_in) * 1.5f * 1.5f, 0.02f)
            << "angle " << a;
    }
}

TEST(PrincipledBsdf, WithoutSpecularMetalOrTransmissionItIsLambert) {
    PrincipledParams p;
    p.base_colour = vec3(0.2f, 0.5f, 0.9f);
    p.specular = 0;
    for (float r : {0.1f, 0.7f}) {
        p.roughness = r;
        const PrincipledBsdf bsdf(p);
        Rng rng(23, 23);
        for (int k = 0; k < 1000; ++k) {
            vec3 wo = sample_uniform_sphere(vec2(rng.uniform(), rng.uniform()));
            vec3 wi = sample_uniform_sphere(vec2(rng.uniform(), rng.uniform()));
            const vec3 f = bsdf.eval(wo, wi);
            if (wo.z * wi.z <= 0) {
                ASSERT_EQ(f, vec3(0.0f));
                continue;
            }
            ASSERT_LT(relative_error(f, p.base_colour * kInvPi * std::abs(wi.z)), 1e-5f);
            ASSERT_NEAR(bsdf.pdf(wo, wi), std::abs(wi.z) * kInvPi, 1e-5f);
            const BsdfSample s = bsdf.sample(wo, vec3(rng.uniform(), rng.uniform(), rng.uniform()));
            ASSERT_TRUE(s);
            ASSERT_LT(relative_error(s.weight, p.base_colour), 1e-5f);
        }
    }
}
