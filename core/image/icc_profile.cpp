// Matrix/TRC ICC profiles (ICC.1:2010 sections 7 and 10): enough to bring a phone's Display P3
// or a camera's Adobe RGB photo into the renderer's linear Rec.709 without a colour engine.
#include "image/icc_profile.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "image/image_io.h"

namespace dp {

namespace {

constexpr int kCurveSamples = 4096;

uint32_t be32(const uint8_t* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }
uint16_t be16(const uint8_t* p) { return uint16_t(p[0] << 8 | p[1]); }
double s15f16(const uint8_t* p) { return double(int32_t(be32(p))) / 65536.0; }

struct Tag {
    const uint8_t* data = nullptr;
    size_t size = 0;
};

/// The tag `sig` of the profile, bounds-checked; empty when missing or outside the bytes.
Tag find_tag(const uint8_t* data, size_t size, const char* sig) {
    if (size < 132) return {};
    const uint32_t count = be32(data + 128);
    if (count > (size - 132) / 12) return {};
    for (uint32_t i = 0; i < count; ++i) {
        const uint8_t* entry = data + 132 + 12 * size_t(i);
        if (std::memcmp(entry, sig, 4) != 0) continue;
        const uint32_t offset = be32(entry + 4), length = be32(entry + 8);
        if (offset > size || length > size - offset || length < 8) return {};
        return {data + offset, length};
    }
    return {};
}

bool read_xyz(const Tag& tag, glm::dvec3& out) {
    if (tag.size < 20 || std::memcmp(tag.data, "XYZ ", 4) != 0) return false;
    out = {s15f16(tag.data + 8), s15f16(tag.data + 12), s15f16(tag.data + 16)};
    return true;
}

/// ICC parametric curve of function type 0 to 4 at x in [0, 1].
double parametric(int type, const double* p, double x) {
    const double g = p[0];
    switch (type) {
        case 0: return std::pow(x, g);
        case 1: return x >= -p[2] / p[1] ? std::pow(p[1] * x + p[2], g) : 0.0;
        case 2: return x >= -p[2] / p[1] ? std::pow(p[1] * x + p[2], g) + p[3] : p[3];
        case 3: return x >= p[4] ? std::pow(p[1] * x + p[2], g) : p[3] * x;
        default: return x >= p[4] ? std::pow(p[1] * x + p[2], g) + p[5] : p[3] * x + p[6];
    }
}

bool read_curve(const Tag& tag, std::vector<float>& samples, std::string& why) {
    samples.assign(kCurveSamples, 0.0f);
    if (tag.size >= 12 && std::memcmp(tag.data, "curv", 4) == 0) {
        const uint32_t n = be32(tag.data + 8);
        if (n > (tag.size - 12) / 2) return why = "a tone curve is truncated", false;
        for (int i = 0; i < kCurveSamples; ++i) {
            const double x = double(i) / (kCurveSamples - 1);
            double y = x;
            if (n == 1) {
                y = std::pow(x, double(be16(tag.data + 12)) / 256.0);
            } else if (n > 1) {
                const double at = x * double(n - 1);
                const uint32_t k = std::min(uint32_t(at), n - 2);
                const double a = be16(tag.data + 12 + 2 * k) / 65535.0, b = be16(tag.data + 14 + 2 * k) / 65535.0;
                y = a + (b - a) * (at - k);
            }
            samples[size_t(i)] = float(y);
        }
        return true;
    }
    if (tag.size >= 12 && std::memcmp(tag.data, "para", 4) == 0) {
        static constexpr int kParams[] = {1, 3, 4, 5, 7};
        const int type = be16(tag.data + 8);
        if (type > 4) return why = "an unknown parametric curve type", false;
        if (tag.size < 12 + 4 * size_t(kParams[type])) return why = "a tone curve is truncated", false;
        double p[7] = {};
        for (int k = 0; k < kParams[type]; ++k) p[k] = s15f16(tag.data + 12 + 4 * k);
        if (type >= 1 && p[1] == 0) return why = "a degenerate parametric curve", false;
        for (int i = 0; i < kCurveSamples; ++i) {
            const double y = parametric(type, p, double(i) / (kCurveSamples - 1));
            samples[size_t(i)] = float(std::isfinite(y) ? y : 0.0);
        }
        return true;
    }
    return why = "a tone curve is neither 'curv' nor 'para'", false;
}

/// Bradford adaptation between two whites given as XYZ.
glm::dmat3 bradford(const glm::dvec3& from, const glm::dvec3& to) {
    // glm is column-major: the constructor takes columns.
    const glm::dmat3 m(0.8951, -0.7502, 0.0389, 0.2664, 1.7135, -0.0685, -0.1614, 0.0367, 1.0296);
    const glm::dvec3 a = m * from, b = m * to;
    glm::dmat3 scale(1.0);
    for (int i = 0; i < 3; ++i) scale[i][i] = b[i] / a[i];
    return glm::inverse(m) * scale * m;
}

const glm::dvec3 kD50(0.9642, 1.0, 0.8249);
const glm::dvec3 kD65(0.95047, 1.0, 1.08883);

glm::dvec3 xy_to_xyz(glm::dvec2 xy) { return {xy.x / xy.y, 1.0, (1.0 - xy.x - xy.y) / xy.y}; }

/// Linear RGB -> XYZ for primaries and white given in xy (white at Y = 1).
glm::dmat3 rgb_to_xyz(const std::array<glm::dvec2, 3>& primaries, glm::dvec2 white) {
    glm::dmat3 m;
    for (int c = 0; c < 3; ++c) m[c] = xy_to_xyz(primaries[size_t(c)]);
    const glm::dvec3 s = glm::inverse(m) * xy_to_xyz(white);
    for (int c = 0; c < 3; ++c) m[c] *= s[c];
    return m;
}

glm::dmat3 xyz_d65_to_rec709() {
    return glm::inverse(rgb_to_xyz({glm::dvec2(0.64, 0.33), glm::dvec2(0.30, 0.60), glm::dvec2(0.15, 0.06)},
                                   glm::dvec2(0.3127, 0.3290)));
}

}  // namespace

float IccRgbProfile::decode(int c, float code) const {
    const std::vector<float>& t = curves[size_t(c)];
    const float at = std::clamp(code, 0.0f, 1.0f) * float(t.size() - 1);
    const size_t k = std::min(size_t(at), t.size() - 2);
    return t[k] + (t[k + 1] - t[k]) * (at - float(k));
}

bool IccRgbProfile::is_srgb() const {
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (std::abs(to_rec709[c][r] - (r == c ? 1.0 : 0.0)) > 2e-3) return false;
    // Half an 8-bit step of the sRGB curve, read at every 64th sample.
    for (int ch = 0; ch < 3; ++ch)
        for (size_t i = 0; i < curves[size_t(ch)].size(); i += 64) {
            const float x = float(i) / float(curves[size_t(ch)].size() - 1);
            if (std::abs(linear_to_srgb(curves[size_t(ch)][i]) - x) > 0.5f / 255.0f) return false;
        }
    return true;
}

std::string icc_description(const uint8_t* data, size_t size) {
    const Tag tag = find_tag(data, size, "desc");
    if (tag.size >= 12 && std::memcmp(tag.data, "desc", 4) == 0) {
        const uint32_t n = be32(tag.data + 8);
        if (n > tag.size - 12) return "";
        std::string s(reinterpret_cast<const char*>(tag.data + 12), n);
        return s.substr(0, s.find('\0'));
    }
    if (tag.size >= 28 && std::memcmp(tag.data, "mluc", 4) == 0) {
        const uint32_t length = be32(tag.data + 20), offset = be32(tag.data + 24);
        if (offset > tag.size || length > tag.size - offset) return "";
        std::string s;  // UTF-16BE, kept to ASCII for messages
        for (uint32_t i = 0; i + 1 < length; i += 2) {
            const uint16_t ch = be16(tag.data + offset + i);
            s += ch < 128 ? char(ch) : '?';
        }
        return s;
    }
    return "";
}

std::optional<IccRgbProfile> parse_icc_rgb_profile(const uint8_t* data, size_t size, std::string& why) {
    if (!data || size < 132 || std::memcmp(data + 36, "acsp", 4) != 0) return why = "not an ICC profile", std::nullopt;
    if (std::memcmp(data + 16, "RGB ", 4) != 0) return why = "not an RGB profile", std::nullopt;
    if (std::memcmp(data + 20, "XYZ ", 4) != 0) return why = "its connection space is not XYZ", std::nullopt;
    IccRgbProfile profile;
    profile.description = icc_description(data, size);
    glm::dmat3 to_xyz_d50;
    const char* colorants[3] = {"rXYZ", "gXYZ", "bXYZ"};
    const char* trcs[3] = {"rTRC", "gTRC", "bTRC"};
    for (int c = 0; c < 3; ++c) {
        if (!read_xyz(find_tag(data, size, colorants[c]), to_xyz_d50[c]))
            return why = "no matrix colorants (a LUT-based profile)", std::nullopt;
        if (!read_curve(find_tag(data, size, trcs[c]), profile.curves[size_t(c)], why)) return std::nullopt;
    }
    profile.to_rec709 = xyz_d65_to_rec709() * bradford(kD50, kD65) * to_xyz_d50;
    return profile;
}

std::vector<uint8_t> make_icc_rgb_profile(const std::string& description, const std::array<glm::dvec2, 3>& primaries,
                                          glm::dvec2 white, bool srgb_curve, double gamma) {
    std::vector<uint8_t> out(128, 0);
    auto put32 = [](std::vector<uint8_t>& v, uint32_t x) {
        for (int s = 24; s >= 0; s -= 8) v.push_back(uint8_t(x >> s));
    };
    auto fixed = [&](std::vector<uint8_t>& v, double x) { put32(v, uint32_t(int32_t(std::lround(x * 65536.0)))); };
    auto text = [](std::vector<uint8_t>& v, const char* s) {
        for (int k = 0; k < 4; ++k) v.push_back(uint8_t(s[k]));
    };

    std::vector<std::pair<std::string, std::vector<uint8_t>>> tags;
    {
        std::vector<uint8_t> t;
        text(t, "desc");
        put32(t, 0);
        put32(t, uint32_t(description.size() + 1));
        t.insert(t.end(), description.begin(), description.end());
        t.resize(t.size() + 1 + 4 + 4 + 2 + 1 + 67, 0);  // NUL, Unicode and ScriptCode parts left empty
        tags.emplace_back("desc", t);
    }
    const glm::dmat3 m = bradford(xy_to_xyz(white), kD50) * rgb_to_xyz(primaries, white);
    auto xyz_tag = [&](const glm::dvec3& v) {
        std::vector<uint8_t> t;
        text(t, "XYZ ");
        put32(t, 0);
        for (int k = 0; k < 3; ++k) fixed(t, v[k]);
        return t;
    };
    tags.emplace_back("wtpt", xyz_tag(kD50));
    tags.emplace_back("rXYZ", xyz_tag(m[0]));
    tags.emplace_back("gXYZ", xyz_tag(m[1]));
    tags.emplace_back("bXYZ", xyz_tag(m[2]));
    std::vector<uint8_t> curve;
    text(curve, "para");
    put32(curve, 0);
    if (srgb_curve) {
        put32(curve, 3u << 16);
        for (double p : {2.4, 1 / 1.055, 0.055 / 1.055, 1 / 12.92, 0.04045}) fixed(curve, p);
    } else {
        put32(curve, 0);
        fixed(curve, gamma);
    }
    for (const char* sig : {"rTRC", "gTRC", "bTRC"}) tags.emplace_back(sig, curve);

    put32(out, uint32_t(tags.size()));
    size_t offset = 132 + 12 * tags.size();
    std::vector<uint8_t> body;
    for (const auto& [sig, bytes] : tags) {
        text(out, sig.c_str());
        put32(out, uint32_t(offset + body.size()));
        put32(out, uint32_t(bytes.size()));
        body.insert(body.end(), bytes.begin(), bytes.end());
        body.resize((body.size() + 3) & ~size_t(3), 0);  // tags start on 4-byte boundaries
    }
    out.insert(out.end(), body.begin(), body.end());
    std::vector<uint8_t> header;
    put32(header, uint32_t(out.size()));
    std::memcpy(out.data(), header.data(), 4);
    std::memcpy(out.data() + 8, "\x02\x10\x00\x00", 4);  // version 2.1
    std::memcpy(out.data() + 12, "mntr", 4);
    std::memcpy(out.data() + 16, "RGB ", 4);
    std::memcpy(out.data() + 20, "XYZ ", 4);
    std::memcpy(out.data() + 36, "acsp", 4);
    std::vector<uint8_t> illuminant;
    for (int k = 0; k < 3; ++k) fixed(illuminant, kD50[k]);
    std::memcpy(out.data() + 68, illuminant.data(), 12);
    return out;
}

}  // namespace dp
