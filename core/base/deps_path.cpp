#include "base/deps_path.h"

#include <algorithm>
#include <system_error>

namespace dp {

std::vector<std::filesystem::path> deps_candidates(const std::filesystem::path& relative) {
    return tree_candidates(std::filesystem::path(".deps") / relative);
}

std::vector<std::filesystem::path> tree_candidates(const std::filesystem::path& relative) {
    namespace fs = std::filesystem;
    std::vector<fs::path> out;
    auto add = [&](const fs::path& p) {
        if (std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
    };
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec)
        for (fs::path d = exe.parent_path(); !d.empty(); d = d.parent_path()) {
            add(d / relative);
            if (d == d.root_path()) break;
        }
#ifdef DP_SOURCE_DIR
    add(fs::path(DP_SOURCE_DIR) / relative);
#endif
    return out;
}

}  // namespace dp
