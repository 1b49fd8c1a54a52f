#include "base/text.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace dp {

std::string ascii_lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

std::string lower_extension(const std::string& path) { return ascii_lower(std::filesystem::path(path).extension().string()); }

size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
            diag = up;
        }
    }
    return row[b.size()];
}

std::string format_bytes(double bytes) {
    char buf[48];
    if (bytes >= 1e9)
        std::snprintf(buf, sizeof(buf), "%.1f GB", bytes / 1e9);
    else
        std::snprintf(buf, sizeof(buf), "%.1f MB", bytes / 1e6);
    return buf;
}

std::string shorten_middle(std::string_view text, size_t max_bytes) {
    static constexpr std::string_view kEllipsis = "\u2026";
    if (text.size() <= max_bytes) return std::string(text);
    if (max_bytes <= kEllipsis.size()) return std::string(kEllipsis);
    auto continuation = [&](size_t i) { return i < text.size() && (uint8_t(text[i]) & 0xC0) == 0x80; };
    const size_t keep = max_bytes - kEllipsis.size();
    size_t head = keep / 2, tail = text.size() - (keep - head);
    while (head > 0 && continuation(head)) --head;  // end the start before a character
    while (continuation(tail)) ++tail;              // begin the end on one
    std::string out(text.substr(0, head));
    out += kEllipsis;
    out += text.substr(tail);
    return out;
}

}  // namespace dp
