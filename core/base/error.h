#pragma once
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/text.h"

namespace dp {

/// Thrown for bad user input (missing file, corrupt image, invalid field). The CLI maps it to
/// exit code 2. The message always names the file (shortened to kMaxPathInMessage: the full path
/// stays in file()) and, where there is one, the field.
class InputError : public std::runtime_error {
public:
    InputError(const std::string& file, const std::string& field, const std::string& what)
        : std::runtime_error(compose(file, field, what)), file_(file), field_(field) {}

    const std::string& file() const { return file_; }
    const std::string& field() const { return field_; }

private:
    static std::string compose(const std::string& file, const std::string& field,
                               const std::string& what) {
        std::string msg;
        if (!file.empty()) msg += shorten_path(file);
        if (!field.empty()) msg += (msg.empty() ? "" : ": ") + std::string("field '") + field + "'";
        if (!msg.empty()) msg += ": ";
        return msg + what;
    }
    std::string file_, field_;
};

/// A failed allocation that says what was being allocated ("an image of 40000 x 30000 pixels
/// (14.4 GB)"), so the CLI can report more than "out of memory".
class OutOfMemory : public std::bad_alloc {
public:
    explicit OutOfMemory(std::string what) : what_(std::move(what)) {}
    const char* what() const noexcept override { return what_.c_str(); }

private:
    std::string what_;
};

}  // namespace dp
