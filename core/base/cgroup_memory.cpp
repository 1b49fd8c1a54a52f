#include "base/cgroup_memory.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace dp {

namespace fs = std::filesystem;

namespace {

/// The first line of a small file, "" if it cannot be read.
std::string first_line(const fs::path& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    return line;
}

/// The lowest limit in file `name` of cgroup `group`'s folder under `mount` and the folders
/// above it up to `mount` itself.
uint64_t lowest_limit(const fs::path& mount, const std::string& group, const char* name) {
    fs::path dir = fs::path(group).relative_path().lexically_normal();
    if (dir == ".") dir.clear();
    if (!dir.empty() && *dir.begin() == "..") return 0;  // not a path inside the mount
    uint64_t lowest = 0;
    for (;;) {
        const uint64_t limit = parse_memory_limit(first_line(mount / dir / name));
        if (limit > 0 && (lowest == 0 || limit < lowest)) lowest = limit;
        if (dir.empty()) return lowest;
        dir = dir.parent_path();
    }
}

bool lists_memory(const std::string& controllers) {
    std::istringstream in(controllers);
    for (std::string c; std::getline(in, c, ',');)
        if (c == "memory") return true;
    return false;
}

}  // namespace

uint64_t parse_memory_limit(const std::string& text) {
    const size_t a = text.find_first_not_of(" \t\r\n");
    if (a == std::string::npos) return 0;
    const std::string word = text.substr(a, text.find_last_not_of(" \t\r\n") - a + 1);
    if (word.find_first_not_of("0123456789") != std::string::npos || word.size() > 19) return 0;
    const uint64_t v = std::strtoull(word.c_str(), nullptr, 10);
    return v < (uint64_t(1) << 60) ? v : 0;
}

uint64_t cgroup_memory_limit(const std::string& self_cgroup, const fs::path& mount) {
    uint64_t lowest = 0;
    std::istringstream lines(self_cgroup);
    for (std::string line; std::getline(lines, line);) {
        // "hierarchy:controllers:path"; the path may hold ':' itself.
        const size_t first = line.find(':'), second = first == std::string::npos ? first : line.find(':', first + 1);
        if (second == std::string::npos) continue;
        const std::string id = line.substr(0, first), controllers = line.substr(first + 1, second - first - 1);
        const std::string group = line.substr(second + 1);
        uint64_t limit = 0;
        if (id == "0" && controllers.empty())
            limit = lowest_limit(mount, group, "memory.max");
        else if (lists_memory(controllers))
            limit = lowest_limit(mount / "memory", group, "memory.limit_in_bytes");
        if (limit > 0 && (lowest == 0 || limit < lowest)) lowest = limit;
    }
    return lowest;
}

}  // namespace dp
