#version 460
#extension GL_GOOGLE_include_directive : require
// The gradient accumulators' fixed-point sums read as floats on the device: each the
// nearest float to the exact total of its copies (fixedPointFloatBits), written to
// gradientValues, every accumulator's sums one after another. The host then downloads 4
// bytes a sum instead of 72 for each copy, which for a grid's millions of voxels is most
// of a gradient's time on a GPU. Threads stride over the sums, so one dispatch within
// the workgroup limit covers any count.
#include "lib/stage_common.glsl"
#include "lib/fixed_point.glsl"

// Adds the words and flags of the `copies` copies of sum `sum` to `total`.
void addCopies(inout FixedPointTotal total, Int64Buffer sums, uint sum, uint copies, uint copyStride) {
    for (uint c = 0u; c < copies; ++c) {
        uint first = (sum + c * copyStride) * kFixedPointWordsPerSum;
        for (uint k = 0u; k < kFixedPointWords; ++k) {
            addFixedPointWord(total, k, sums.v[first + k]);
        }
        total.flags |= uint(sums.v[first + kFixedPointFlagsWord]);
    }
}

void main() {
    uint threads = gl_NumWorkGroups.x * kWorkgroupSize;
    for (uint i = gl_GlobalInvocationID.x; i < P.gradientValueCount; i += threads) {
        // Which accumulator's sum this is; one call reads it whichever it is, which keeps
        // the stage small for a CPU device to compile.
        Int64Buffer sums = P.mediumGradients;
        uint sum = 0u, copies = 0u, copyStride = 0u;
#define VKDR_FIND_ACCUMULATOR(name, field, floats, copyCount, items) \
        if (i - P.name##FirstValue < P.name##ValueCount) {          \
            sums = P.name;                                           \
            sum = i - P.name##FirstValue;                            \
            copies = copyCount;                                      \
            copyStride = P.name##CopyStride;                         \
        }
        VKDR_GRADIENT_ACCUMULATORS(VKDR_FIND_ACCUMULATOR)
#undef VKDR_FIND_ACCUMULATOR
        FixedPointTotal total = fixedPointTotalOfNothing();
        addCopies(total, sums, sum, copies, copyStride);
        // A medium's sigma_a and sigma_s also hold what their sigma_t sums share
        // (addSigmaTGradient in lib/adjoint.glsl): 64 sums in all, the most a total holds.
        uint channel = sum % kMediumGradientStride - kMediumGradientSigmaA;  // rgb of sigma_a, then of sigma_s
        if (i - P.mediumGradientsFirstValue < P.mediumGradientsValueCount && channel < 6u) {
            uint sigmaT = sum - (sum % kMediumGradientStride) + kMediumGradientSigmaT + channel % 3u;
            addCopies(total, sums, sigmaT, copies, copyStride);
        }
        P.gradientValues.v[i] = fixedPointFloatBits(total);
    }
}
