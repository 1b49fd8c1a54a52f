#pragma once
#include <stdexcept>
#include <string>

namespace dp {

/// Thrown for bad user input (missing file, corrupt image, invalid field). The CLI maps it to
/// exit code 2. The message always names the file and, where there is one, the field.
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
        if (!file.empty()) msg += file;
        if (!field.empty()) msg += (msg.empty() ? "" : ": ") + std::string("field '") + field + "'";
        if (!msg.empty()) msg += ": ";
        return msg + what;
    }
    std::string file_, field_;
};

}  // namespace dp
