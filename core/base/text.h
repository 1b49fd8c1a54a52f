#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace dp {

/// Levenshtein distance, for "did you mean" suggestions.
size_t edit_distance(std::string_view a, std::string_view b);

/// A byte count for messages: "3.2 MB", "170000.0 GB" (decimal units, one decimal).
std::string format_bytes(double bytes);

/// The longest path a message quotes in full, in bytes.
inline constexpr size_t kMaxPathInMessage = 200;

/// `s` with ASCII letters in lower case (file extensions, keywords).
std::string ascii_lower(std::string s);
/// The extension of `path` with its dot, in lower case: ".exr", "" for none.
std::string lower_extension(const std::string& path);

/// `text` cut to at most `max_bytes` bytes by replacing its middle with "…", keeping its start
/// and its end (a path's top folders and its file name); cuts fall between UTF-8 characters.
std::string shorten_middle(std::string_view text, size_t max_bytes);

/// A path as messages quote it: shorten_middle to kMaxPathInMessage, so a path of megabytes
/// never makes a message of megabytes.
inline std::string shorten_path(std::string_view path) { return shorten_middle(path, kMaxPathInMessage); }

}  // namespace dp
