// Counter-based sample points: a pure function of (pixel, sample, stream, segment,
// dimension group, seed), so the adjoint pass can replay a path in any scheduling order.
// Each group of four dimensions is a 4D Owen-scrambled Sobol' point (Burley 2020,
// "Practical Hash-based Owen Scrambling"): the samples of one pixel stratify every
// group, and independent scrambles per (pixel, group, stream, seed) decorrelate the groups.
#ifndef VKDR_RNG_GLSL
#define VKDR_RNG_GLSL

// Dimension groups used within one path segment (four numbers each).
const uint kDimCamera = 0u;      // pixel jitter (segment 0 only)
const uint kDimFreeFlight = 1u;  // hero channel, distance
const uint kDimLight = 2u;       // emitter choice, point on the emitter
const uint kDimScatter = 3u;     // BSDF / phase direction, Russian roulette
const uint kDimEquiangular = 4u; // emitter choice, point on it, distance along the segment towards it
const uint kDimGroupsPerSegment = 5u;

// pcg4d from Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020:
// a 4D-to-4D bijection with good avalanche, so neighbouring keys are independent.
uvec4 pcg4d(uvec4 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    v ^= v >> 16u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    return v;
}

// The first four dimensions of Sobol's sequence (Joe and Kuo's primitive polynomials
// 1, x + 1, x^2 + x + 1, x^3 + x + 1 with initial numbers m = 1; 1, 3; 1, 3, 1) at
// `index`, as 32-bit fractions. Each dimension's direction number for bit k follows from
// the ones before it by its polynomial's recurrence, so no table is needed.
uvec4 sobol4(uint index) {
    uvec4 point = uvec4(bitfieldReverse(index), 0u, 0u, 0u);
    uint d1 = 1u << 31u;                                        // x + 1
    uint d2 = 1u << 31u, d2Next = 3u << 30u;                    // x^2 + x + 1
    uint d3 = 1u << 31u, d3Next = 3u << 30u, d3After = 1u << 29u;  // x^3 + x + 1
    for (uint bits = index; bits != 0u; bits >>= 1u) {
        if ((bits & 1u) != 0u) {
            point.y ^= d1;
            point.z ^= d2;
            point.w ^= d3;
        }
        d1 ^= d1 >> 1u;
        uint d2Following = d2Next ^ d2 ^ (d2 >> 2u);
        d2 = d2Next;
        d2Next = d2Following;
        uint d3Following = d3Next ^ d3 ^ (d3 >> 3u);
        d3 = d3Next;
        d3Next = d3After;
        d3After = d3Following;
    }
    return point;
}

// A hash-based nested uniform (Owen) scramble of the bits of `x` taken from the least
// significant end: each output bit depends on the seed and the bits below it only, the
// property of Laine and Karras' permutation, with the multipliers of Burley 2020.
uint scrambleFromLowBits(uint x, uint seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

// Owen scrambling of a fraction: its leading bits decide the trailing ones.
uint owenScramble(uint fraction, uint seed) {
    return bitfieldReverse(scrambleFromLowBits(bitfieldReverse(fraction), seed));
}

// 24 high bits to a float in [0, 1): exact, and never 1.
vec4 toUnitFloat(uvec4 bits) {
    return vec4(bits >> 8u) * (1.0f / 16777216.0f);
}

// Point `sampleIndex` of the 4D sequence of (pixel, dimension, stream, seed), where
// dimension = segment * kDimGroupsPerSegment + group. The sample index is itself
// Owen-scrambled, which shuffles the order of the points (so groups are not correlated
// through it) while any 2^k consecutive samples from 0 stay a stratified set. Streams
// are independent sequences: the halves of a split gradient estimate draw from two.
vec4 sample4(uint pixel, uint sampleIndex, uint stream, uint dimension, uint seed) {
    uvec4 scrambles = pcg4d(uvec4(pixel, dimension, seed, stream));
    uint shuffled = owenScramble(sampleIndex, scrambles.x);
    uvec4 point = sobol4(shuffled);
    uvec4 seeds = pcg4d(scrambles);
    return toUnitFloat(uvec4(owenScramble(point.x, seeds.x), owenScramble(point.y, seeds.y),
                             owenScramble(point.z, seeds.z), owenScramble(point.w, seeds.w)));
}

#endif
