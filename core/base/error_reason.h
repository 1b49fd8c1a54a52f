#pragma once
#include <string>

#include "base/error.h"

namespace dp {

/// What an InputError says is wrong, without the file and field its message starts with: for
/// saying the same of another file or field (a value the command line gave is reported under
/// the flag, a scene check under the project file).
inline std::string error_reason(const InputError& e) {
    const std::string prefix = InputError(e.file(), e.field(), "").what();
    const std::string what = e.what();
    return what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what;
}

}  // namespace dp
