#pragma once
#include <cstdint>

namespace dp {

/// Physical memory of this machine in bytes (0 if unknown): the figure memory limits and
/// out-of-memory messages are given against.
uint64_t physical_memory_bytes();

}  // namespace dp
