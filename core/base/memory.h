#pragma once
#include <cstdint>

namespace dp {

/// The memory this process may use in bytes (0 if unknown): the machine's physical memory, or
/// the memory limit of its cgroup (a container, a batch job) where that is lower. The figure
/// memory limits and out-of-memory messages are given against; read once per process.
uint64_t usable_memory_bytes();

}  // namespace dp
