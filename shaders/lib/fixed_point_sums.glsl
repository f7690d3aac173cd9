// Adding floats into fixed-point sums in device memory (fixed_point.glsl): the gradient
// accumulators and the loss. The host reads a sum back as the float its words total
// (src/core/fixed_point_value.h), the same bits in every run on every device.
#ifndef VKDR_FIXED_POINT_SUMS_GLSL
#define VKDR_FIXED_POINT_SUMS_GLSL
#include "fixed_point.glsl"

// Adds `value` to word k of the sum at `sum`, moving a carry up when the word grows
// large (fixedPointCarry); a carry out of the top word means the sum is out of range.
void addToWord(Int64Buffer sums, uint sum, uint k, int64_t value) {
    for (;;) {
        int64_t before = atomicAdd(sums.v[sum + k], value);
        int64_t carry = fixedPointCarry(before, before + value);
        if (carry == int64_t(0)) {
            return;
        }
        if (k + 1u == kFixedPointWords) {
            uint overflow = carry > int64_t(0) ? kFixedPointPositiveOverflow : kFixedPointNegativeOverflow;
            atomicOr(sums.v[sum + kFixedPointFlagsWord], int64_t(overflow));
            return;
        }
        atomicAdd(sums.v[sum + k], -(carry << 32));
        value = carry;
        ++k;
    }
}

// Adds x to the sum at `sum` (the index of its first word). Every active lane of the
// subgroup must call it with the same `sum`: the lanes' digits are added up first with
// integer subgroup sums, exact in any grouping, so one lane adds each word's total.
void addFixedPoint(Int64Buffer sums, uint sum, float x) {
    FixedPointTerm term = fixedPointTerm(x);
    uint flags = subgroupOr(term.flags);
    bool adds = term.word < kFixedPointWords;
    uint lowest = subgroupMin(adds ? term.word : kFixedPointWords);
    uint highest = subgroupMax(adds ? term.word + 1u : 0u);
    for (uint k = lowest; k <= highest && k < kFixedPointWords; ++k) {
        int64_t digits = subgroupAdd(fixedPointDigit(term, k));
        if (subgroupElect() && digits != int64_t(0)) {
            addToWord(sums, sum, k, digits);
        }
    }
    if (flags != 0u && subgroupElect()) {
        atomicOr(sums.v[sum + kFixedPointFlagsWord], int64_t(flags));
    }
}

#endif
