#include "geometry/gltf_json.h"
#include "base/byte_order.h"

#include <cstdint>
#include <fstream>
#include <iterator>

namespace dp {

namespace {

std::string latin1_to_utf8(const std::string& bytes) {
    std::string out;
    out.reserve(bytes.size());
    for (const char c : bytes) {
        const auto b = static_cast<unsigned char>(c);
        if (b < 0x80) {
            out += c;
        } else {
            out += char(0xC0 | (b >> 6));
            out += char(0x80 | (b & 0x3F));
        }
    }
    return out;
}

/// The inverse of latin1_to_utf8 for what it made (U+0080 to U+00FF); other characters (a
/// "\u20ac" escape) stay UTF-8.
std::string utf8_to_latin1(const std::string& text) {
    std::string out;
    for (size_t i = 0; i < text.size(); ++i) {
        const auto b = static_cast<unsigned char>(text[i]);
        if ((b == 0xC2 || b == 0xC3) && i + 1 < text.size()) {
            out += char(((b & 0x03) << 6) | (static_cast<unsigned char>(text[i + 1]) & 0x3F));
            ++i;
        } else {
            out += text[i];
        }
    }
    return out;
}

}  // namespace

std::string gltf_json_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) return bytes;
    const uint64_t length = le32(reinterpret_cast<const unsigned char*>(bytes.data()) + 12);
    return 20 + length <= bytes.size() ? bytes.substr(20, size_t(length)) : "";
}

std::string GltfJson::file_string(const nlohmann::json& value) const {
    const std::string s = value.get<std::string>();
    return latin1 ? utf8_to_latin1(s) : s;
}

GltfJson parse_gltf_json(const std::string& text) {
    GltfJson g;
    g.doc = nlohmann::json::parse(text, nullptr, false);
    if (g.doc.is_discarded()) {
        g.doc = nlohmann::json::parse(latin1_to_utf8(text), nullptr, false);
        g.latin1 = !g.doc.is_discarded();
    }
    return g;
}

}  // namespace dp
