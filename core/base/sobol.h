#pragma once
#include <cstdint>

#include "base/math.h"
#include "base/rng.h"

namespace dp {

/// Owen-scrambled Sobol' points, after Burley (2020), "Practical Hash-based Owen Scrambling".
/// A pixel's samples across passes come from these, so that smooth integrands (sub-pixel
/// position, a soft shadow's visibility, the object's shading) converge faster than random
/// samples would; each dimension pair has its own scramble and index shuffle ("padding"), so
/// pairs are independent of each other while each stays a (0,2)-sequence.

inline uint32_t reverse_bits32(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
    x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
    return (x >> 16) | (x << 16);
}

/// A random permutation of bit-reversed integers in which each bit depends only on the bits
/// below it (Laine and Karras 2011, constants from Burley 2020): on reversed numbers, an Owen
/// scramble.
inline uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/// Owen scramble of a 32-bit fixed-point number in [0, 1): every bit is flipped by a hash of
/// the bits above it.
inline uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed) {
    return reverse_bits32(laine_karras_permutation(reverse_bits32(x), seed));
}

/// The first two Sobol' dimensions as 32-bit fixed point: van der Corput, and the dimension
/// whose generator is Pascal's matrix mod 2. Together they form a (0,2)-sequence.
inline uint32_t sobol_dimension0(uint32_t index) { return reverse_bits32(index); }
inline uint32_t sobol_dimension1(uint32_t index) {
    uint32_t v = 1u << 31, result = 0;
    for (; index; index >>= 1, v ^= v >> 1)
        if (index & 1) result ^= v;
    return result;
}

/// 32-bit fixed point to a float in [0, 1) (the top 24 bits: never rounds up to 1).
inline float fixed_to_unit(uint32_t x) { return float(x >> 8) * 0x1p-24f; }

/// Point `index` of the Owen-scrambled, index-shuffled 2D Sobol' sequence keyed by `seed`.
/// Any 2^k consecutive aligned indices form a (0,2)-net: one point in every elementary box of
/// area 2^-k.
inline vec2 sobol_owen_2d(uint32_t index, uint64_t seed) {
    const uint32_t s0 = uint32_t(mix64(seed)), s1 = uint32_t(mix64(seed ^ 0x5851f42d4c957f2dull));
    const uint32_t s2 = uint32_t(mix64(seed + 0x14057b7ef767814full));
    const uint32_t i = nested_uniform_scramble(index, s0);
    return vec2(fixed_to_unit(nested_uniform_scramble(sobol_dimension0(i), s1)),
                fixed_to_unit(nested_uniform_scramble(sobol_dimension1(i), s2)));
}

/// A pixel's sample `index` (its pass) as a stream of dimension pairs: each call to next2d()
/// takes a new pair with its own scramble. Streams for different (seed, pixel) are independent.
/// A sampler made by independent() returns independent uniform numbers instead (a baseline to
/// measure what the low-discrepancy points buy).
class PixelSampler {
public:
    PixelSampler(uint64_t seed, uint64_t pixel, uint32_t index)
        : key_(hash_combine(hash_combine(seed, 0x736f626f6cull), pixel)), index_(index) {}

    /// The stream of a pixel in pass `pass` (1-based). Odd and even passes are two separately
    /// scrambled sequences, each low-discrepancy over its own passes: the two interleaved
    /// halves of a render are then independent estimates, and their difference an honest
    /// measure of the error (halves of one sequence would share its strata).
    static PixelSampler for_pass(uint64_t seed, uint64_t pixel, int pass, bool low_discrepancy = true) {
        PixelSampler s(hash_combine(seed, uint64_t(pass & 1)), pixel, uint32_t((pass - 1) / 2));
        s.independent_ = !low_discrepancy;
        return s;
    }

    vec2 next2d() {
        const uint64_t pair_key = hash_combine(key_, pair_++);
        if (independent_) {
            Rng rng(pair_key, index_);
            return vec2(rng.uniform(), rng.uniform());
        }
        return sobol_owen_2d(index_, pair_key);
    }
    /// One dimension: the first of a fresh pair (a stratified 1D sequence).
    float next1d() { return next2d().x; }
    /// The same stream at another sample index (several samples of one pixel in one pass).
    PixelSampler with_index(uint32_t index) const {
        PixelSampler s = *this;
        s.index_ = index;
        return s;
    }
    uint32_t index() const { return index_; }

private:
    uint64_t key_;
    uint32_t index_;
    uint32_t pair_ = 0;
    bool independent_ = false;
};

}  // namespace dp
