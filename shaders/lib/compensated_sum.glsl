// A sum of floats kept as an unevaluated pair high + low (a "double-float"): high is the
// sum rounded to a float, low what that rounding left out, so the pair holds about 48
// bits. The adjoint pass needs it for L_rem: the replay subtracts from the path's
// radiance L every contribution it passes, and after a vertex that keeps a fraction f
// of the throughput (a tiny sigma_s / sigma_t, a nearly black wall) the true L_rem is
// about f L. In one float its rounding error is about 6e-8 L, which the vertex's
// gradient term L_rem / f magnifies beyond use once f nears 1e-7; in the pair it is
// about 4e-15 L (docs/gradients.md, "Small factors").
//
// `precise` keeps the compiler from fusing or reassociating the error terms, which
// would make them zero.
#ifndef VKDR_COMPENSATED_SUM_GLSL
#define VKDR_COMPENSATED_SUM_GLSL

struct CompensatedSum {
    vec3 high;
    vec3 low;
};

// Knuth's TwoSum: the float a + b, and in low its rounding error, exact in any order
// of magnitude of a and b. An infinite sum keeps no error (its terms would be inf - inf,
// NaN), so that it stays infinite as a plain float sum does.
CompensatedSum twoSum(vec3 a, vec3 b) {
    precise vec3 high = a + b;
    precise vec3 bPart = high - a;
    precise vec3 low = (a - (high - bPart)) + (b - bPart);
    return CompensatedSum(high, mix(low, vec3(0.0f), isinf(high)));
}

// sum + c: high + c exactly as a pair, its low part gathering the old one, then
// renormalised so that high is the pair's value rounded to a float (a reader of high
// alone sees the sum's float value).
CompensatedSum addCompensated(CompensatedSum sum, vec3 c) {
    CompensatedSum s = twoSum(sum.high, c);
    precise vec3 error = s.low + sum.low;
    return twoSum(s.high, error);
}

#endif
