#pragma once
#include <bit>
#include <cmath>
#include <cstdint>

namespace dp {

/// An exact, order-independent running sum of doubles, in 128-bit fixed point with 64
/// fraction bits (resolution 2^-64, about 5.4e-20).
///
/// Why: a render's passes are summed per pixel, and a sum of doubles depends on the order of
/// its terms. Rounding each term once to a multiple of 2^-64 and adding integers makes the sum
/// associative and commutative, so passes summed in one process and passes summed in shards
/// and merged give the same bits. Every float whose magnitude is at least 2^-41 (4.5e-13) is a
/// multiple of 2^-64, so a float sample is held exactly; smaller terms are rounded to the
/// nearest multiple (ties away from zero). A term's magnitude is clamped to kMax (2^39, about
/// 5.5e11): 2^24 passes of such terms still fit the 2^63 range. The integer arithmetic is
/// modular (unsigned), so even a sum that passes through overflow ends exact when its total
/// fits.
class FixedSum {
public:
    /// Largest magnitude of one term; larger ones are clamped to it.
    static constexpr double kMax = 0x1p39;
    static constexpr int kFractionBits = 64;

    constexpr FixedSum() = default;

    /// The term `x` rounded to the fixed-point grid (x finite; NaN counts as zero).
    static unsigned __int128 to_fixed(double x) {
        double a = std::fabs(x);
        if (!(a > 0)) return 0;
        if (a > kMax) a = kMax;
        const uint64_t bits = std::bit_cast<uint64_t>(a);
        const int exponent = int(bits >> 52);
        if (exponent == 0) return 0;  // subnormal: far below the resolution
        const uint64_t mantissa = (bits & ((uint64_t(1) << 52) - 1)) | (uint64_t(1) << 52);
        // a = mantissa * 2^(exponent - 1075), in units of 2^-64: mantissa * 2^(exponent - 1011).
        const int shift = exponent - 1011;
        unsigned __int128 magnitude = 0;
        if (shift >= 0)
            magnitude = static_cast<unsigned __int128>(mantissa) << shift;  // at most 53 + 52 bits
        else if (shift > -64)
            magnitude = (mantissa + (uint64_t(1) << (-shift - 1))) >> -shift;  // round half away
        return x < 0 ? ~magnitude + 1 : magnitude;
    }

    void add(double x) { raw_ += to_fixed(x); }
    void add(const FixedSum& other) { raw_ += other.raw_; }
    /// The sum, rounded once to the nearest double.
    double value() const { return std::ldexp(static_cast<double>(static_cast<__int128>(raw_)), -kFractionBits); }
    bool zero() const { return raw_ == 0; }

    /// The two's-complement bits, for files: low and high 64 bits.
    uint64_t low() const { return uint64_t(raw_); }
    uint64_t high() const { return uint64_t(raw_ >> 64); }
    static FixedSum from_bits(uint64_t low, uint64_t high) {
        FixedSum s;
        s.raw_ = (static_cast<unsigned __int128>(high) << 64) | low;
        return s;
    }
    friend bool operator==(const FixedSum&, const FixedSum&) = default;

private:
    unsigned __int128 raw_ = 0;
};

}  // namespace dp
