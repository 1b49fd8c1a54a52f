#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/math.h"

namespace dp {

/// An RGB matrix/TRC ICC profile (v2 or v4), the kind cameras and phones embed (sRGB, Display
/// P3, Adobe RGB): three tone curves and the primaries. LUT-based profiles are not read.
struct IccRgbProfile {
    std::string description;  ///< the profile's 'desc' text ("Display P3", "sRGB IEC61966-2.1")
    /// Per channel, the curve from code value [0, 1] to linear light, sampled at 4096 points.
    std::array<std::vector<float>, 3> curves;
    /// Linear RGB of the profile -> linear Rec.709 / sRGB primaries (D65), through XYZ D50
    /// and Bradford adaptation, as colour-managed viewers show it.
    glm::dmat3 to_rec709{1.0};

    /// Linear light of a code value in [0, 1] for channel c (linear interpolation).
    float decode(int c, float code) const;
    /// True when converting is a no-op within rounding: sRGB primaries and the sRGB curve.
    bool is_srgb() const;
};

/// Parses an embedded ICC profile; nullopt with `why` set when it is not an RGB matrix/TRC
/// profile (a LUT profile, a grey or CMYK one, or corrupt bytes).
std::optional<IccRgbProfile> parse_icc_rgb_profile(const uint8_t* data, size_t size, std::string& why);

/// Just the description of any ICC profile ("" if none is readable), for messages.
std::string icc_description(const uint8_t* data, size_t size);

/// Builds a matrix/TRC profile's bytes (v2, 'para' curves of the sRGB kind with `gamma`, or a
/// pure gamma when `srgb_curve` is false) from primaries and white in xy: what tests and
/// tools need to tag a file (Display P3 is sRGB's curve with P3 primaries).
std::vector<uint8_t> make_icc_rgb_profile(const std::string& description, const std::array<glm::dvec2, 3>& primaries,
                                          glm::dvec2 white, bool srgb_curve, double gamma);

}  // namespace dp
