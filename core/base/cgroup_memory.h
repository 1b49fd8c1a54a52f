#pragma once
// The memory limit of the control groups a process runs in (a container, a systemd slice, a
// batch job's allocation), which a process meets long before the machine's physical memory.
#include <cstdint>
#include <filesystem>
#include <string>

namespace dp {

/// The bytes one cgroup limit file states (memory.max, memory.limit_in_bytes): 0 for no limit,
/// that is "max", text that is no whole number, 0 itself, and values of 2^60 and over (v1
/// writes "no limit" as 2^63 less a page).
uint64_t parse_memory_limit(const std::string& text);

/// The lowest memory limit of the cgroups a process is in, 0 for none. `self_cgroup` is the
/// text of /proc/self/cgroup; `mount` is where the cgroup file systems are mounted
/// (/sys/fs/cgroup). cgroup v2 ("0::/path"): `mount`/path/memory.max; cgroup v1
/// ("N:memory,...:/path"): `mount`/memory/path/memory.limit_in_bytes. The folders above the
/// process's cgroup count too, since a parent's limit binds its children and a container sees
/// its own cgroup as the root. Missing or unreadable files are no limit.
uint64_t cgroup_memory_limit(const std::string& self_cgroup, const std::filesystem::path& mount);

}  // namespace dp
