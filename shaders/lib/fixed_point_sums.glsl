// Adding floats into fixed-point sums in device memory (fixed_point.glsl): the gradient
// accumulators and the loss. The host reads a sum back as the float its words total
// (src/core/fixed_point_value.h), the same bits in every run on every device.
#ifndef VKDR_FIXED_POINT_SUMS_GLSL
#define VKDR_FIXED_POINT_SUMS_GLSL
#include "fixed_point.glsl"

// Makes the additions of `step` and of the steps it leads to (fixedPointAdditionAfter),
// then sets its flags. One atomic addition in a loop rather than one for each case: a
// CPU device runs every atomic instruction it meets once for each lane of the subgroup,
// whether any lane takes it or not.
void addFixedPointSteps(Int64Buffer sums, uint sum, FixedPointAddition step) {
    while (step.word < kFixedPointWords) {
        int64_t before = atomicAdd(sums.v[sum + step.word], step.value);
        step = fixedPointAdditionAfter(step, before);
    }
    if (step.flags != 0u) {
        atomicOr(sums.v[sum + kFixedPointFlagsWord], int64_t(step.flags));
    }
}

// Adds the first `channels` components of x to the sums at `sum`, `sum` +
// kFixedPointWordsPerSum, ... (the index of each one's first word). Every active lane of
// the subgroup must call it with the same `sum`: the lanes' digits are added up first with
// integer subgroup sums, exact in any grouping, so one lane adds each word's total.
void addFixedPoint(Int64Buffer sums, uint sum, vec4 x, uint channels) {
    FixedPointTerm terms[4] = FixedPointTerm[4](fixedPointTerm(x.x), fixedPointTerm(x.y), fixedPointTerm(x.z),
                                                fixedPointTerm(x.w));
    uvec4 flags = subgroupOr(uvec4(terms[0].flags, terms[1].flags, terms[2].flags, terms[3].flags));
    uint lowest = kFixedPointWords;
    uint highest = 0u;
    for (uint c = 0u; c < channels; ++c) {
        if (terms[c].word < kFixedPointWords) {
            lowest = min(lowest, terms[c].word);
            highest = max(highest, terms[c].word + 1u);
        }
    }
    lowest = subgroupMin(lowest);
    highest = min(subgroupMax(highest), kFixedPointWords - 1u);
    for (uint k = lowest; k <= highest; ++k) {
        i64vec4 digits = subgroupAdd(i64vec4(fixedPointDigit(terms[0], k), fixedPointDigit(terms[1], k),
                                             fixedPointDigit(terms[2], k), fixedPointDigit(terms[3], k)));
        if (subgroupElect()) {
            for (uint c = 0u; c < channels; ++c) {
                if (digits[c] != int64_t(0)) {
                    addFixedPointSteps(sums, sum + c * kFixedPointWordsPerSum,
                                       fixedPointAdditionToWord(k, digits[c], int64_t(0)));
                }
            }
        }
    }
    if (subgroupElect()) {
        for (uint c = 0u; c < channels; ++c) {
            if (flags[c] != 0u) {
                atomicOr(sums.v[sum + c * kFixedPointWordsPerSum + kFixedPointFlagsWord], int64_t(flags[c]));
            }
        }
    }
}

// Adds x to the one sum at `sum` from this lane alone, with no subgroup operation: the
// gradients' additions, made in divergent code (addGradient). Integer additions are
// exact, so the total is the same in any order.
void addFixedPointFromOneLane(Int64Buffer sums, uint sum, float x) {
    addFixedPointSteps(sums, sum, fixedPointAdditionOf(fixedPointTerm(x)));
}

#endif
