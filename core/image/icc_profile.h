#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "base/math.h"

namespace dp {

/// An embedded ICC profile of an RGB image, read by Little CMS 2: any kind cameras, phones and
/// scanners embed (matrix/TRC such as sRGB, Display P3 and Adobe RGB, or LUT-based camera and
/// scanner profiles; ICC v2 or v4), with the transform from its codes to linear Rec.709.
class IccProfile {
public:
    /// The profile in `data`; null with `why` set where it is not an RGB profile (a grey or
    /// CMYK one) or Little CMS cannot read it.
    static std::unique_ptr<IccProfile> read(const uint8_t* data, size_t size, std::string& why);
    ~IccProfile();
    IccProfile(const IccProfile&) = delete;
    IccProfile& operator=(const IccProfile&) = delete;

    /// The profile's description ("Display P3", "sRGB IEC61966-2.1"), "" where it has none.
    const std::string& description() const { return description_; }
    /// `pixels` interleaved RGB codes in [0, 1] to linear Rec.709 / sRGB primaries (D65), in
    /// place: relative colorimetric through the profile's connection space (Bradford-adapted
    /// white), as colour-managed viewers show it, unbounded where the profile is a matrix one
    /// (Display P3's red comes out with negative green and blue).
    void to_linear_rec709(float* rgb, size_t pixels) const;
    /// True when converting is a no-op within rounding: sRGB by another name.
    bool is_srgb() const;

private:
    IccProfile() = default;
    void* transform_ = nullptr;  ///< cmsHTRANSFORM (kept out of this header)
    std::string description_;
};

/// Just the description of any ICC profile ("" if none is readable), for messages.
std::string icc_description(const uint8_t* data, size_t size);

/// A matrix/TRC profile's bytes (ICC v2 unless `version` says otherwise) from primaries and white
/// in xy, with sRGB's curve or, when `srgb_curve` is false, a pure `gamma`: what tests and tools
/// need to tag a file (Display P3 is sRGB's curve with P3 primaries). Written by Little CMS.
std::vector<uint8_t> make_icc_rgb_profile(const std::string& description, const std::array<glm::dvec2, 3>& primaries,
                                          glm::dvec2 white, bool srgb_curve, double gamma, double version = 2.1);

}  // namespace dp
