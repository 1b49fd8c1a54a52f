#include "base/input_file.h"
#include "base/text.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "base/error.h"

namespace dp {

namespace {

/// A FIFO or a device would block a reader forever or feed it without end.
const char* special_kind(const struct stat& st) {
    return S_ISDIR(st.st_mode)    ? "a folder"
           : S_ISFIFO(st.st_mode) ? "a FIFO (named pipe)"
           : S_ISSOCK(st.st_mode) ? "a socket"
           : S_ISCHR(st.st_mode)  ? "a character device"
           : S_ISBLK(st.st_mode)  ? "a block device"
           : S_ISREG(st.st_mode)  ? nullptr
                                  : "not a regular file";
}

}  // namespace

std::optional<struct stat> file_status(const std::string& path) {
    struct stat st {};
    if (path.empty() || ::stat(path.c_str(), &st) != 0) return std::nullopt;
    return st;
}

std::string special_file_kind(const std::string& path) {
    const auto st = file_status(path);
    const char* kind = st ? special_kind(*st) : nullptr;
    return kind ? kind : "";
}

uint64_t check_input_file(const std::string& path, const std::string& field, const std::string& what,
                          uint64_t max_bytes) {
    if (path.empty()) throw InputError(path, field, "no file given (expected " + what + ")");
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        if (errno == ENOENT || errno == ENOTDIR) throw InputError(path, field, "file not found");
        throw InputError(path, field, std::string("cannot read it: ") + std::strerror(errno));
    }
    if (const char* kind = special_kind(st)) throw InputError(path, field, std::string("is ") + kind + ", not " + what);
    const uint64_t size = uint64_t(st.st_size);
    if (max_bytes > 0 && size > max_bytes)
        throw InputError(path, field,
                         "is " + format_bytes(double(size)) + ", more than the " + format_bytes(double(max_bytes)) + " " + what +
                             " may have");
    return size;
}

}  // namespace dp
