#pragma once
// The message of the InputError a call throws, for tests of bad input.
#include <functional>
#include <string>

#include "base/error.h"

namespace dp::test {

/// What `f` throws as InputError, or "(no InputError)" when it returns normally.
inline std::string input_error_message(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no InputError)";
}

}  // namespace dp::test
