#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace dp {

/// Levenshtein distance, for "did you mean" suggestions.
size_t edit_distance(std::string_view a, std::string_view b);

/// A byte count for messages: "3.2 MB", "170000.0 GB" (decimal units, one decimal).
std::string format_bytes(double bytes);

}  // namespace dp
