#include "base/memory.h"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "base/cgroup_memory.h"

namespace dp {

namespace {

uint64_t physical_memory_bytes() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : 0;
}

/// /proc/self/cgroup's text (a few lines; bounded all the same), "" where there is none.
std::string self_cgroup() {
    std::ifstream in("/proc/self/cgroup");
    std::string text;
    for (std::string line; text.size() < 65536 && std::getline(in, line);) text += line + "\n";
    return text;
}

}  // namespace

uint64_t usable_memory_bytes() {
    static const uint64_t bytes = [] {
        const uint64_t ram = physical_memory_bytes();
        const uint64_t limit = cgroup_memory_limit(self_cgroup(), "/sys/fs/cgroup");
        if (ram == 0 || limit == 0) return std::max(ram, limit);
        return std::min(ram, limit);
    }();
    return bytes;
}

}  // namespace dp
