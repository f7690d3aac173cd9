// A float as a term of a fixed-point sum (layout in device_types.h, kFixedPoint*).
// Float additions round, so a float sum depends on the order of its terms, and atomics
// add in whatever order threads arrive; integer additions are exact, so the words of a
// fixed-point sum reach the same total in any order. Pure maths, compiled on the host
// by the unit tests too.
#ifndef VKDR_FIXED_POINT_GLSL
#define VKDR_FIXED_POINT_GLSL

// x = mantissa * 2^exponent exactly (mantissa < 2^24), placed at bit
// exponent - kFixedPointLowestBit of the sum: it spans at most two 32-bit words.
struct FixedPointTerm {
    uint word;     // the word `low` adds to, `high` to the next; kFixedPointWords: nothing to add
    int64_t low;   // |low| < 2^32
    int64_t high;  // |high| < 2^24
    uint flags;    // kFixedPointNaN or an overflow for what the words cannot hold
};

FixedPointTerm fixedPointTerm(float x) {
    FixedPointTerm term = FixedPointTerm(kFixedPointWords, int64_t(0), int64_t(0), 0u);
    uint bits = floatBitsToUint(x);
    bool negative = (bits >> 31) != 0u;
    uint exponentBits = (bits >> 23) & 0xffu;
    uint mantissaBits = bits & 0x7fffffu;
    uint overflow = negative ? kFixedPointNegativeOverflow : kFixedPointPositiveOverflow;
    if (exponentBits == 0xffu) {
        term.flags = mantissaBits != 0u ? kFixedPointNaN : overflow;
        return term;
    }
    uint mantissa = exponentBits == 0u ? mantissaBits : (mantissaBits | 0x800000u);
    // Subnormals share the exponent of the smallest normal float.
    int bit = max(int(exponentBits), 1) - 150 - kFixedPointLowestBit;
    if (bit < 0) {
        // Below the lowest bit: truncated toward zero, the same way in every order.
        mantissa = bit > -24 ? mantissa >> uint(-bit) : 0u;
        bit = 0;
    }
    if (mantissa == 0u) {
        return term;
    }
    uint word = uint(bit) >> 5;
    uint64_t placed = uint64_t(mantissa) << (uint(bit) & 31u);
    uint64_t high = placed >> 32;
    if (word >= kFixedPointWords || (word + 1u == kFixedPointWords && high != uint64_t(0))) {
        term.flags = overflow;
        return term;
    }
    int64_t sign = negative ? int64_t(-1) : int64_t(1);
    term.word = word;
    term.low = sign * int64_t(placed & uint64_t(0xffffffffu));
    term.high = sign * int64_t(high);
    return term;
}

// What `term` adds to word k of a sum.
int64_t fixedPointDigit(FixedPointTerm term, uint k) {
    return k == term.word ? term.low : (k == term.word + 1u ? term.high : int64_t(0));
}

// A word of a sum holds at most 2^63. An addition that takes a word's magnitude to
// kFixedPointCarryAt or beyond moves all but its low 32 bits into the next word, which
// keeps the total. An addition is below 2^39 (a subgroup's digits), so between two
// crossings there are thousands of additions, and a word would need 2^11 carries of one
// sign in flight at once to overflow.
const int64_t kFixedPointCarryAt = int64_t(1) << 52;

// The carry that an addition taking a word from `before` to `after` moves up (0: none),
// in units of the next word.
int64_t fixedPointCarry(int64_t before, int64_t after) {
    bool crossed = abs(after) >= kFixedPointCarryAt && abs(before) < kFixedPointCarryAt;
    return crossed ? after >> 32 : int64_t(0);
}

#endif
