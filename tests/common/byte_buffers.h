#pragma once
// Bytes for files tests write by hand (glTF buffers as data URIs).
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace dp::test {

/// Standard base64 with padding.
inline std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t chunk = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) chunk |= uint32_t(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) chunk |= uint32_t(bytes[i + 2]);
        out += kAlphabet[(chunk >> 18) & 63];
        out += kAlphabet[(chunk >> 12) & 63];
        out += i + 1 < bytes.size() ? kAlphabet[(chunk >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? kAlphabet[chunk & 63] : '=';
    }
    return out;
}

/// Appends the raw bytes of `values` to `buf`.
template <typename T>
void append_bytes(std::vector<uint8_t>& buf, const std::vector<T>& values) {
    const size_t at = buf.size();
    buf.resize(at + values.size() * sizeof(T));
    std::memcpy(buf.data() + at, values.data(), values.size() * sizeof(T));
}

}  // namespace dp::test
