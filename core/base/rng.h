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

/// The named random streams: one per use of randomness, so that no two uses draw the same
/// numbers and one pass, pixel or photon can be reproduced alone from the seed.
namespace rng_stream {
inline constexpr uint64_t kReferenceSalt = 0x7265665f7074ull;  ///< "ref_pt": the path tracer's seeds

/// Photon `index` of progressive pass `pass` (passes and pixels interleave: even keys).
inline Rng photon(uint64_t seed, uint64_t pass, uint64_t index) { return Rng::keyed(seed, pass * 2, index); }
/// Pixel `pixel`'s numbers in pass `pass` beyond the first bounce's Sobol' points (odd keys).
inline Rng camera(uint64_t seed, uint64_t pass, uint64_t pixel) { return Rng::keyed(seed, pass * 2 + 1, pixel); }
/// Pixel `pixel`'s draws when a probe is aligned to a grey card.
inline Rng probe_alignment(uint64_t seed, uint64_t pixel) { return Rng::keyed(seed, pixel, 0xca7d); }
/// Texel `texel`'s probe samples in an albedo texture estimate.
inline Rng albedo_texel(uint64_t seed, uint64_t texel) { return Rng::keyed(seed, texel, 0xa1bed0); }
/// The reference path tracer's path `sample` from pixel `pixel`.
inline Rng reference_path(uint64_t seed, uint64_t pixel, uint64_t sample) {
    return Rng::keyed(seed ^ kReferenceSalt, pixel, sample * 2);
}
/// A second, independent path per sample (standard differential's second image).
inline Rng reference_second_path(uint64_t seed, uint64_t pixel, uint64_t sample) {
    return Rng::keyed(seed ^ kReferenceSalt, pixel, sample * 2 + 1);
}
/// The pixel's Cranley-Patterson shift of its R2 sample positions in the reference.
inline Rng reference_pixel_shift(uint64_t seed, uint64_t pixel) {
    return Rng::keyed(seed ^ kReferenceSalt, pixel, ~uint64_t(0));
}
}  // namespace rng_stream

}  // namespace dp
