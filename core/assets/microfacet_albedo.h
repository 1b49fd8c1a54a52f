#pragma once
// Directional albedos of the single-scattering GGX reflection lobe, tabulated at first use, for
// energy compensation: the conductor's multiple-scattering lobe (Kulla & Conty 2017) puts back
// what one bounce off the microfacets loses, and the diffuse base under the dielectric layer
// receives exactly what the layer does not reflect (albedo scaling).
#include "base/math.h"

namespace dp {

/// E(mu, roughness) = \f$\int f_{ss}(w_o, w_i)\, \cos\theta_i\, dw_i\f$ with F = 1, for
/// mu = cos(theta_o) in [0, 1] and glTF roughness in [0, 1] (alpha = roughness^2).
float ggx_albedo(float mu, float roughness);

/// E_avg(roughness) = 2 \f$\int_0^1\f$ E(mu) mu dmu, exact for the interpolated table, so that
/// a lobe proportional to (1 - E(mu_i)) integrates to exactly 1 - E_avg.
float ggx_average_albedo(float roughness);

/// The same lobe's albedo with the Fresnel weight w = (F(wo.m) - F0) / (1 - F0) in place of 1,
/// F being fresnel_dielectric seen from the outside of index `ior` (clamped to [1, 5]) and F0
/// its value at normal incidence. A dielectric layer whose Fresnel is F0' + (1 - F0') w
/// reflects F0' E + (1 - F0') E_w.
float ggx_dielectric_albedo(float mu, float roughness, float ior);

/// 2 \f$\int_0^1\f$ ggx_dielectric_albedo(mu) mu dmu, exact for the interpolated table.
float ggx_dielectric_average_albedo(float roughness, float ior);

/// The tables' grid: x = k / (kGgxAlbedoSize - 1) gives the nodes mu = x^2 (denser towards
/// grazing, where E changes fastest), roughness = x; kGgxAlbedoIors nodes uniform in
/// (ior - 1) / (ior + 1) over [1, 5]. Values are trilinear between nodes. Built at first use,
/// deterministically (stratified quadrature, 2304 points a node; under 0.1 s, thread-safe).
inline constexpr int kGgxAlbedoSize = 32, kGgxAlbedoIors = 9;

}  // namespace dp
