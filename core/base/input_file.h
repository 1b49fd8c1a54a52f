#pragma once
#include <sys/stat.h>

#include <cstdint>
#include <optional>
#include <string>

namespace dp {

/// Checks that `path` names a regular file (after symlinks) that can be read without blocking:
/// not missing ("file not found"), not a folder, FIFO, socket or device (each named as such,
/// `what` saying what was expected: "an image", "a project file"), and at most `max_bytes`
/// long (0: no limit; the message gives both sizes). Throws InputError(path, field, ...).
/// Returns the file's size in bytes.
uint64_t check_input_file(const std::string& path, const std::string& field, const std::string& what,
                          uint64_t max_bytes = 0);

/// The file `path` names after symbolic links, or nothing when there is none (or it cannot be
/// looked at).
std::optional<struct stat> file_status(const std::string& path);

/// What `path` is (after symlinks) when it exists but is no regular file, as check_input_file
/// names it ("a folder", "a FIFO (named pipe)", "a character device"); empty for a regular
/// file and for a path that cannot be looked at (missing, no permission).
std::string special_file_kind(const std::string& path);

}  // namespace dp
