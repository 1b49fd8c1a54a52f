#pragma once
#include <algorithm>
#include <thread>

namespace dp {

/// Cores this machine has (at least 1).
inline int hardware_threads() { return std::max(1, int(std::thread::hardware_concurrency())); }

/// Worker threads for a requested count: 0 or less means every core; more than the cores is
/// clamped to them (more only slows a CPU-bound render, and TBB fails beyond 65536).
inline int worker_threads(int requested) {
    return requested <= 0 ? hardware_threads() : std::min(requested, hardware_threads());
}

}  // namespace dp
