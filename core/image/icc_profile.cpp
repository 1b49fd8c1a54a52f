// ICC profiles through Little CMS 2: whatever a camera, phone or scanner embeds is read by the
// library colour-managed applications use, matrix and LUT profiles alike.
#include "image/icc_profile.h"

#include <lcms2.h>

#include <algorithm>
#include <cmath>

#include "image/image_io.h"

namespace dp {

namespace {

/// A Little CMS profile handle closed on every path.
struct Profile {
    cmsHPROFILE h = nullptr;
    explicit Profile(cmsHPROFILE p) : h(p) {}
    ~Profile() {
        if (h) cmsCloseProfile(h);
    }
    Profile(const Profile&) = delete;
    Profile& operator=(const Profile&) = delete;
};

/// Linear Rec.709 primaries with a D65 white: the renderer's working space.
cmsHPROFILE linear_rec709() {
    const cmsCIExyY white = {0.3127, 0.3290, 1.0};
    const cmsCIExyYTRIPLE primaries = {{0.64, 0.33, 1.0}, {0.30, 0.60, 1.0}, {0.15, 0.06, 1.0}};
    cmsToneCurve* linear = cmsBuildGamma(nullptr, 1.0);
    cmsToneCurve* curves[3] = {linear, linear, linear};
    cmsHPROFILE p = cmsCreateRGBProfile(&white, &primaries, curves);
    cmsFreeToneCurve(linear);
    return p;
}

std::string description_of(cmsHPROFILE p) {
    const auto* mlu = static_cast<const cmsMLU*>(cmsReadTag(p, cmsSigProfileDescriptionTag));
    if (!mlu) return "";
    char text[256] = {};
    cmsMLUgetASCII(mlu, cmsNoLanguage, cmsNoCountry, text, sizeof text);
    std::string s(text);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.pop_back();
    return s;
}

}  // namespace

std::unique_ptr<IccProfile> IccProfile::read(const uint8_t* data, size_t size, std::string& why) {
    if (!data || size < 132 || size > (64u << 20)) {
        why = "not a readable ICC profile (" + std::to_string(size) + " bytes)";
        return nullptr;
    }
    Profile in(cmsOpenProfileFromMem(data, cmsUInt32Number(size)));
    if (!in.h) {
        why = "not a readable ICC profile";
        return nullptr;
    }
    if (cmsGetColorSpace(in.h) != cmsSigRgbData) {
        why = "not an RGB profile";
        return nullptr;
    }
    Profile out(linear_rec709());
    // Floats in and out, unoptimised: Little CMS then evaluates a matrix profile unbounded
    // rather than through a 16-bit table that would clip colours outside sRGB.
    cmsHTRANSFORM t = cmsCreateTransform(in.h, TYPE_RGB_FLT, out.h, TYPE_RGB_FLT, INTENT_RELATIVE_COLORIMETRIC,
                                         cmsFLAGS_NOCACHE | cmsFLAGS_NOOPTIMIZE);
    if (!t) {
        why = "an ICC profile Little CMS cannot build a transform from";
        return nullptr;
    }
    std::unique_ptr<IccProfile> profile(new IccProfile());
    profile->transform_ = t;
    profile->description_ = description_of(in.h);
    return profile;
}

IccProfile::~IccProfile() {
    if (transform_) cmsDeleteTransform(static_cast<cmsHTRANSFORM>(transform_));
}

void IccProfile::to_linear_rec709(float* rgb, size_t pixels) const {
    // In chunks: Little CMS counts pixels in 32 bits.
    constexpr size_t kChunk = size_t(1) << 24;
    for (size_t at = 0; at < pixels; at += kChunk) {
        const size_t n = std::min(kChunk, pixels - at);
        cmsDoTransform(static_cast<cmsHTRANSFORM>(transform_), rgb + 3 * at, rgb + 3 * at, cmsUInt32Number(n));
    }
}

bool IccProfile::is_srgb() const {
    // Greys, the primaries and mixtures at 8-bit steps, against sRGB's own decoding.
    std::vector<float> codes;
    for (int v = 0; v <= 255; v += 5)
        for (const glm::vec3 mix : {glm::vec3(1, 1, 1), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1),
                                    glm::vec3(1, 0.5f, 0.2f)})
            for (int c = 0; c < 3; ++c) codes.push_back(mix[c] * float(v) / 255.0f);
    std::vector<float> linear = codes;
    to_linear_rec709(linear.data(), codes.size() / 3);
    for (size_t i = 0; i < codes.size(); ++i)
        if (!(std::abs(linear[i] - srgb_to_linear(codes[i])) <= 2e-3f)) return false;
    return true;
}

std::string icc_description(const uint8_t* data, size_t size) {
    if (!data || size < 132) return "";
    Profile p(cmsOpenProfileFromMem(data, cmsUInt32Number(std::min<size_t>(size, UINT32_MAX))));
    return p.h ? description_of(p.h) : "";
}

std::vector<uint8_t> make_icc_rgb_profile(const std::string& description, const std::array<glm::dvec2, 3>& primaries,
                                          glm::dvec2 white, bool srgb_curve, double gamma, double version) {
    const cmsCIExyY w = {white.x, white.y, 1.0};
    const cmsCIExyYTRIPLE p = {{primaries[0].x, primaries[0].y, 1.0},
                               {primaries[1].x, primaries[1].y, 1.0},
                               {primaries[2].x, primaries[2].y, 1.0}};
    // sRGB's curve as ICC parametric type 4: Y = (aX + b)^g above d, cX below.
    const cmsFloat64Number srgb[5] = {2.4, 1.0 / 1.055, 0.055 / 1.055, 1.0 / 12.92, 0.04045};
    cmsToneCurve* curve = srgb_curve ? cmsBuildParametricToneCurve(nullptr, 4, srgb) : cmsBuildGamma(nullptr, gamma);
    cmsToneCurve* curves[3] = {curve, curve, curve};
    Profile h(cmsCreateRGBProfile(&w, &p, curves));
    cmsFreeToneCurve(curve);
    if (!h.h) return {};
    cmsSetProfileVersion(h.h, version);
    cmsMLU* mlu = cmsMLUalloc(nullptr, 1);
    cmsMLUsetASCII(mlu, "en", "US", description.c_str());
    cmsWriteTag(h.h, cmsSigProfileDescriptionTag, mlu);
    cmsMLUfree(mlu);
    cmsUInt32Number size = 0;
    if (!cmsSaveProfileToMem(h.h, nullptr, &size)) return {};
    std::vector<uint8_t> bytes(size);
    if (!cmsSaveProfileToMem(h.h, bytes.data(), &size)) return {};
    return bytes;
}

}  // namespace dp
