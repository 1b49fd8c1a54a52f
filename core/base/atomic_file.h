#pragma once
#include <cstddef>
#include <functional>
#include <string>

namespace dp {

/// Writes `path` so that it always holds either its old content or the complete new one, also
/// when the process is killed mid-write or another process writes the same path: `write` fills
/// a temporary file in the same folder (same extension, so encoders that choose the format by
/// extension see the right one), which is flushed to disk and renamed over `path`. If `write`
/// throws, or flushing or renaming fails, the temporary file is removed, `path` is left as it
/// was and the error is rethrown (std::runtime_error naming `path` for the file system's).
void write_atomically(const std::string& path, const std::function<void(const std::string& temp_path)>& write);

/// Removes the temporary files of the writes in progress. Async-signal-safe: for a signal
/// handler that ends the process (a second Ctrl-C), so a killed write leaves no hidden file.
/// The targets are untouched: they still hold their old content.
void remove_temporaries_in_flight() noexcept;

/// write_atomically for text or bytes already in memory.
void write_file_atomically(const std::string& path, const std::string& bytes);

/// The name (no folder) of write_atomically's temporary file for a target named `target_name`:
/// hidden, unique to `pid` and `count`, the target's extension kept. A target whose own name
/// leaves no room for the tag within `name_max` bytes (the file system's limit on one name)
/// gets a 64-bit hash of its name instead of its stem, so that every name the file system
/// takes can be written; the extension goes too where even that does not fit.
std::string temporary_file_name(const std::string& target_name, size_t name_max, unsigned long pid,
                                unsigned count);

/// The longest file name, in bytes, the file system of `folder` takes (pathconf's NAME_MAX, else
/// statvfs's f_namemax); 255 when neither says.
size_t file_name_limit(const std::string& folder);

}  // namespace dp
