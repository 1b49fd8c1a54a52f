#pragma once
// Shared by the fuzz targets: the loaders under test read files, so each input is written to a
// private temporary file first; and one rule for what counts as a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"

namespace dp::fuzz {

/// A folder of this process's own (removed at exit), so parallel fuzzing jobs never share files.
inline const std::filesystem::path& scratch_dir() {
    // Never destroyed: the handler that removes the folder is registered before the path would
    // be, so it would run after the path's destructor.
    static const std::filesystem::path* const dir = [] {
        auto* d = new std::filesystem::path(std::filesystem::temp_directory_path() /
                                            ("dp-fuzz-" + std::to_string(::getpid())));
        std::filesystem::create_directories(*d);
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(scratch_dir(), ec);
        });
        return d;
    }();
    return *dir;
}

/// Writes the input to `name` in the scratch folder and returns its path.
inline std::string write_input(const uint8_t* data, size_t size, const std::string& name) {
    const std::string path = (scratch_dir() / name).string();
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    return path;
}

/// Runs `body`: an InputError is the loader refusing bad input as documented (the CLI's exit 2),
/// anything else escaping is a finding (the CLI would call it an internal error), so it aborts
/// with the message for libFuzzer to report and minimise.
template <class Body>
void expect_only_input_errors(Body&& body) {
    try {
        body();
    } catch (const InputError&) {
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fuzz finding: %s escaped: %s\n", typeid(e).name(), e.what());
        std::abort();
    }
}

/// A finding for a property the loaders promise (round trips, finite pixels).
inline void require(bool ok, const char* what) {
    if (!ok) {
        std::fprintf(stderr, "fuzz finding: %s\n", what);
        std::abort();
    }
}

/// The input cut at every `separator` (an input of several files): at most `max_parts`, the
/// last one keeping what follows.
inline std::vector<std::string> split_input(const uint8_t* data, size_t size, std::string_view separator,
                                            size_t max_parts) {
    const std::string_view all(reinterpret_cast<const char*>(data), size);
    std::vector<std::string> parts;
    size_t start = 0;
    while (parts.size() + 1 < max_parts) {
        const size_t at = all.find(separator, start);
        if (at == std::string_view::npos) break;
        parts.emplace_back(all.substr(start, at - start));
        start = at + separator.size();
    }
    parts.emplace_back(all.substr(start));
    return parts;
}

/// Writes `bytes` to `name` in the scratch folder and returns its path.
inline std::string write_file(const std::string& bytes, const std::string& name) {
    return write_input(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), name);
}

}  // namespace dp::fuzz
