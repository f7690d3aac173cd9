// A float as a term of a fixed-point sum (layout in device_types.h, kFixedPoint*).
// Float additions round, so a float sum depends on the order of its terms, and atomics
// add in whatever order threads arrive; integer additions are exact, so the words of a
// fixed-point sum reach the same total in any order. Pure maths, compiled on the host
// by the unit tests too.
#ifndef VKDR_FIXED_POINT_GLSL
#define VKDR_FIXED_POINT_GLSL
#include "constants.glsl"

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

// How a term goes into a sum's words, one atomic addition at a time
// (fixed_point_sums.glsl): a step adds `value` to `word`, and what the word held before
// decides the next step. A step that takes the word across kFixedPointCarryAt is followed
// by one that takes the carry back out of it, and the carry goes up with the term's next
// digit; a carry out of the top word flags the sum as out of range.
struct FixedPointAddition {
    uint word;              // kFixedPointWords: nothing more to add
    int64_t value;          // what this step adds to `word`
    int64_t next;           // what the step after it adds to word + 1
    bool takesCarryBack;    // this step's result needs no carry check
    uint flags;             // kFixedPoint* flags for the sum's flags word
};

FixedPointAddition fixedPointAdditionToWord(uint word, int64_t value, int64_t next) {
    return FixedPointAddition(word, value, next, false, 0u);
}

FixedPointAddition fixedPointAdditionOf(FixedPointTerm term) {
    if (term.flags != 0u || term.word >= kFixedPointWords) {
        return FixedPointAddition(kFixedPointWords, int64_t(0), int64_t(0), false, term.flags);
    }
    if (term.low == int64_t(0)) {
        return fixedPointAdditionToWord(term.word + 1u, term.high, int64_t(0));
    }
    return fixedPointAdditionToWord(term.word, term.low, term.high);
}

FixedPointAddition fixedPointAdditionAfter(FixedPointAddition step, int64_t before) {
    if (!step.takesCarryBack) {
        int64_t carry = fixedPointCarry(before, before + step.value);
        if (carry != int64_t(0)) {
            if (step.word + 1u == kFixedPointWords) {
                step.flags |= carry > int64_t(0) ? kFixedPointPositiveOverflow : kFixedPointNegativeOverflow;
                step.word = kFixedPointWords;
                return step;
            }
            step.value = -(carry << 32);
            step.next += carry;
            step.takesCarryBack = true;
            return step;
        }
    }
    step.takesCarryBack = false;
    step.word = step.next != int64_t(0) ? step.word + 1u : kFixedPointWords;
    step.value = step.next;
    step.next = int64_t(0);
    return step;
}

// The exact total of fixed-point sums (the copies of one accumulator), gathered word by
// word: each word's low 32 bits go to its part and the rest to the next one's, so that a
// part stays below 2^39 for up to 64 sums, and the flags of all of them.
struct FixedPointTotal {
    int64_t parts[kFixedPointWords + 1u];  // parts[kFixedPointWords]: above the top word
    uint flags;
};

FixedPointTotal fixedPointTotalOfNothing() {
    FixedPointTotal total;
    for (uint k = 0u; k <= kFixedPointWords; ++k) {
        total.parts[k] = int64_t(0);
    }
    total.flags = 0u;
    return total;
}

void addFixedPointWord(INOUT(FixedPointTotal) total, uint k, int64_t word) {
    total.parts[k] += word & int64_t(0xffffffffu);
    total.parts[k + 1u] += word >> 32;
}

// 64 bits of the number whose 32-bit digits are `digits`, from bit `lowest` (which may be
// negative: zeros below bit 0), and whether any bit below `lowest` is set.
uint64_t fixedPointWindow(uint digits[kFixedPointWords], int lowest, INOUT(bool) anyBelow) {
    uint64_t window = uint64_t(0);
    anyBelow = false;
    for (uint k = 0u; k < kFixedPointWords; ++k) {
        int shift = int(32u * k) - lowest;
        uint64_t digit = uint64_t(digits[k]);
        if (shift >= 0 && shift < 64) {
            window |= digit << uint(shift);
        } else if (shift < 0 && shift > -32) {
            window |= digit >> uint(-shift);
            anyBelow = anyBelow || (digit & ((uint64_t(1) << uint(-shift)) - uint64_t(1))) != uint64_t(0);
        } else if (shift <= -32) {
            anyBelow = anyBelow || digit != uint64_t(0);
        }
    }
    return window;
}

// The bits of the float nearest to `total` (ties to even): one rounding of the exact
// value, so every device and the host give the same bits. NaN if a term was NaN or both
// signs overflowed, an infinity if one did or the total is beyond float range. The
// lowest bit, 2^-96, is far above float's subnormals, so every non-zero total is normal.
uint fixedPointFloatBits(FixedPointTotal total) {
    bool positiveOverflow = (total.flags & kFixedPointPositiveOverflow) != 0u;
    bool negativeOverflow = (total.flags & kFixedPointNegativeOverflow) != 0u;
    if ((total.flags & kFixedPointNaN) != 0u || (positiveOverflow && negativeOverflow)) {
        return 0x7fc00000u;
    }
    if (positiveOverflow || negativeOverflow) {
        return positiveOverflow ? 0x7f800000u : 0xff800000u;
    }
    // Carry-propagate into 32-bit digits and a signed part above them, then take the
    // magnitude (two's complement of all of it when negative).
    uint digits[kFixedPointWords];
    int64_t carry = int64_t(0);
    for (uint k = 0u; k < kFixedPointWords; ++k) {
        int64_t part = total.parts[k] + carry;
        digits[k] = uint(part & int64_t(0xffffffffu));
        carry = part >> 32;
    }
    int64_t above = total.parts[kFixedPointWords] + carry;
    uint sign = 0u;
    if (above < int64_t(0)) {
        sign = 0x80000000u;
        uint64_t increment = uint64_t(1);
        for (uint k = 0u; k < kFixedPointWords; ++k) {
            uint64_t digit = uint64_t(~digits[k]) + increment;
            digits[k] = uint(digit & uint64_t(0xffffffffu));
            increment = digit >> 32;
        }
        above = ~above + int64_t(increment);
    }
    if (above != int64_t(0)) {
        return sign | 0x7f800000u;  // at least 2^(32 kFixedPointWords + kFixedPointLowestBit)
    }
    int highest = -1;
    for (uint k = 0u; k < kFixedPointWords; ++k) {
        if (digits[k] != 0u) {
            highest = int(32u * k) + findMSB(digits[k]);
        }
    }
    if (highest < 0) {
        return 0u;
    }
    // The window's top 24 bits are the significand, the next one decides the rounding
    // with every bit below it.
    int lowest = highest - 63;
    bool anyBelow;
    uint64_t window = fixedPointWindow(digits, lowest, anyBelow);
    uint significand = uint(window >> 40);
    bool roundBit = ((window >> 39) & uint64_t(1)) != uint64_t(0);
    bool sticky = anyBelow || (window & ((uint64_t(1) << 39) - uint64_t(1))) != uint64_t(0);
    int exponent = highest + kFixedPointLowestBit;  // of the significand's top bit
    if (roundBit && (sticky || (significand & 1u) != 0u)) {
        ++significand;
        if (significand == 0x1000000u) {
            significand >>= 1;
            ++exponent;
        }
    }
    if (exponent > 127) {
        return sign | 0x7f800000u;
    }
    return sign | (uint(exponent + 127) << 23) | (significand & 0x7fffffu);
}

#endif
