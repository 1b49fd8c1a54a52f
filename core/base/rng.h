#pragma once
#include <cstdint>

namespace dp {

/// 64-bit mix (splitmix64 finaliser) used to derive independent streams from (seed, pass, index).
constexpr uint64_t mix64(uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    x ^= x >> 31;
    return x;
}

constexpr uint64_t hash_combine(uint64_t a, uint64_t b) { return mix64(a ^ (mix64(b) + 0x9e3779b97f4a7c15ull)); }

/// PCG32 (O'Neill). Each photon and each pixel sample gets its own stream so results do not
/// depend on how work is split between threads.
class Rng {
public:
    Rng() : Rng(0, 0) {}
    Rng(uint64_t seed, uint64_t stream) {
        state_ = 0;
        inc_ = (stream << 1u) | 1u;
        next_u32();
        state_ += seed;
        next_u32();
    }
    /// A stream keyed by several integers (seed, pass, item...).
    static Rng keyed(uint64_t seed, uint64_t a, uint64_t b = 0) {
        return Rng(hash_combine(seed, a), hash_combine(a, b) ^ mix64(b + 1));
    }

    uint32_t next_u32() {
        uint64_t old = state_;
        state_ = old * 6364136223846793005ull + inc_;
        uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        uint32_t rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
    }
    /// Uniform in [0, 1).
    float uniform() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }
    double uniform_double() {
        uint64_t v = (static_cast<uint64_t>(next_u32()) << 21) ^ next_u32();
        return static_cast<double>(v & ((1ull << 53) - 1)) * 0x1p-53;
    }

private:
    uint64_t state_, inc_;
};

}  // namespace dp
