#include "volume/smoke_plume.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "volume/index_transform.h"

// The plume, at a local point p in [-0.5, 0.5]^3 with height h = p.y + 0.5:
//   q        = p + (0.02 + 0.09 h) * (fbm2(3p), fbm2(3p), fbm2(3p))  turbulence, growing with height
//   axis(h)  = 0.06 (h - h0) * (n(2.3h), n(2.3h))                    the column leans as it rises
//   radius   = 0.05 + 0.4 (hq - h0)                                   widens with height (hq = q.y + 0.5)
//   core     = 1 - smoothstep(0.3, 1, |q.xz - axis(h)| / radius)
//   body     = core * smoothstep(h0, h0 + 0.08, hq) * (1 - smoothstep(0.6, 0.88, hq)) / (1 + 6 (hq - h0))
//   contrast = 0.6 + 3 (hq - h0)                                      steady at the source, billowy above
//   density  = clamp(body * (1 + contrast * fbm4(5q - (0, 2hq, 0))) - 0.04, 0, 1) * faceFade(p)
// with h0 = 0.14, where the column starts. n is gradient noise of a seeded hash, fbm2 and
// fbm4 sum 2 or 4 octaves of it, each axis and each use with a seed of its own.
// Subtracting 0.04 cuts the thin fringe to exact zeros and lets the billows open holes;
// faceFade is 1 inside |p| < 0.38 on every axis and 0 beyond 0.45.
namespace vkdr {
namespace {

constexpr float kSourceHeight = 0.14f;     // h0: where the column starts, above the bottom's fade
constexpr float kSourceRadius = 0.05f;     // r0
constexpr float kSpread = 0.4f;            // radius gained per unit of height
constexpr float kDrift = 0.06f;            // sideways lean of the axis per unit of height
constexpr float kWarpAtSource = 0.02f;     // turbulent displacement at h = 0 ...
constexpr float kWarpGrowth = 0.09f;       // ... plus this much per unit of height
constexpr float kWarpScale = 3.0f;         // frequency of the turbulence
constexpr float kBillowScale = 5.0f;       // frequency of the billows
// |n| stays below about 1.04 (Perlin's gradients); two octaves of amplitude 1 and 0.5.
constexpr float kFbm2Bound = 1.1f * 1.5f;

uint32_t mix(uint32_t h) {  // MurmurHash3's finaliser
    h ^= h >> 16;
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    h *= 0xC2B2AE35u;
    h ^= h >> 16;
    return h;
}

float smoothstep(float edge0, float edge1, float x) {
    const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// Perlin's improved gradient noise (2002) with the permutation table replaced by a hash
// of the lattice point and a seed: about [-1, 1], 0 on the lattice.
class GradientNoise {
public:
    explicit GradientNoise(uint32_t seed) : seed_(mix(seed + 0x9E3779B9u)) {}

    float operator()(glm::vec3 p) const {
        const glm::vec3 cell = glm::floor(p);
        const glm::ivec3 i(cell);
        const glm::vec3 f = p - cell;
        const glm::vec3 u = f * f * f * (f * (f * 6.0f - 15.0f) + 10.0f);
        float corners[8];
        for (int c = 0; c < 8; ++c) {
            const glm::ivec3 offset(c & 1, (c >> 1) & 1, c >> 2);
            corners[c] = gradientDot(i + offset, f - glm::vec3(offset));
        }
        const float x00 = corners[0] + u.x * (corners[1] - corners[0]);
        const float x10 = corners[2] + u.x * (corners[3] - corners[2]);
        const float x01 = corners[4] + u.x * (corners[5] - corners[4]);
        const float x11 = corners[6] + u.x * (corners[7] - corners[6]);
        const float y0 = x00 + u.y * (x10 - x00);
        const float y1 = x01 + u.y * (x11 - x01);
        return y0 + u.z * (y1 - y0);
    }

private:
    // The dot product of `d` with one of Perlin's 12 edge gradients, picked by the hash.
    float gradientDot(glm::ivec3 lattice, glm::vec3 d) const {
        const uint32_t h = mix(uint32_t(lattice.x) * 0x8DA6B343u ^ uint32_t(lattice.y) * 0xD8163841u ^
                               uint32_t(lattice.z) * 0xCB1AB31Fu ^ seed_) >> 28;
        const float a = h < 8 ? d.x : d.y;
        const float b = h < 4 ? d.y : (h == 12 || h == 14 ? d.x : d.z);
        return ((h & 1) ? -a : a) + ((h & 2) ? -b : b);
    }

    uint32_t seed_;
};

// Fractal sum of `octaves` octaves, each at twice the frequency and half the amplitude
// of the one before and shifted so that their lattices do not line up.
float fbm(const GradientNoise& noise, glm::vec3 p, int octaves) {
    float sum = 0.0f, amplitude = 1.0f;
    for (int octave = 0; octave < octaves; ++octave) {
        sum += amplitude * noise(p + float(octave) * glm::vec3(17.13f, -9.71f, 5.37f));
        p *= 2.0f;
        amplitude *= 0.5f;
    }
    return sum;
}

float radiusAt(float height) { return kSourceRadius + kSpread * std::max(height - kSourceHeight, 0.0f); }

float faceFade(glm::vec3 p) {
    const glm::vec3 distance = glm::abs(p);
    return (1.0f - smoothstep(0.38f, 0.45f, distance.x)) * (1.0f - smoothstep(0.38f, 0.45f, distance.y)) *
           (1.0f - smoothstep(0.38f, 0.45f, distance.z));
}

class SmokePlume {
public:
    explicit SmokePlume(uint32_t seed)
        : warpX_(mix(seed) ^ 1u), warpY_(mix(seed) ^ 2u), warpZ_(mix(seed) ^ 3u), billows_(mix(seed) ^ 4u),
          leanX_(mix(seed) ^ 5u), leanZ_(mix(seed) ^ 6u) {}

    // Where the column's axis is at height h (in x and z).
    glm::vec2 axisAt(float h) const {
        const glm::vec3 along(2.3f * h, 0.5f, 0.5f);
        return kDrift * std::max(h - kSourceHeight, 0.0f) * glm::vec2(leanX_(along), leanZ_(along));
    }

    // The density at p, its column's axis at p's height being `axis`; exactly 0 without
    // evaluating any noise wherever the turbulence cannot bring the column.
    float densityAt(glm::vec3 p, glm::vec2 axis) const {
        const float h = p.y + 0.5f;
        const float warpAmplitude = kWarpAtSource + kWarpGrowth * h;
        const float reach = warpAmplitude * kFbm2Bound;  // the most q moves along any axis
        if (h + reach < kSourceHeight || h - reach > 0.88f || faceFade(p) == 0.0f) return 0.0f;
        if (glm::distance(glm::vec2(p.x, p.z), axis) >= radiusAt(h + reach) + reach * std::sqrt(2.0f)) return 0.0f;
        const glm::vec3 turbulence = kWarpScale * p;
        const glm::vec3 q = p + warpAmplitude * glm::vec3(fbm(warpX_, turbulence, 2), fbm(warpY_, turbulence, 2),
                                                          fbm(warpZ_, turbulence, 2));
        const float hq = q.y + 0.5f;
        const float radial = glm::distance(glm::vec2(q.x, q.z), axis) / radiusAt(hq);
        const float core = 1.0f - smoothstep(0.3f, 1.0f, radial);
        const float body = core * smoothstep(kSourceHeight, kSourceHeight + 0.08f, hq) *
                           (1.0f - smoothstep(0.6f, 0.88f, hq)) / (1.0f + 6.0f * std::max(hq - kSourceHeight, 0.0f));
        if (body == 0.0f) return 0.0f;
        const float billows = fbm(billows_, kBillowScale * q - glm::vec3(0.0f, 2.0f * hq, 0.0f), 4);
        const float contrast = 0.6f + 3.0f * std::max(hq - kSourceHeight, 0.0f);
        const float density = body * (1.0f + contrast * billows) - 0.04f;
        return std::clamp(density, 0.0f, 1.0f) * faceFade(p);
    }

private:
    GradientNoise warpX_, warpY_, warpZ_, billows_, leanX_, leanZ_;
};

}  // namespace

DensityGrid makeSmokePlume(int resolution, uint32_t seed) {
    if (resolution < 2 || uint64_t(resolution) * uint64_t(resolution) * uint64_t(resolution) > kMaxDenseVoxels) {
        throw Error("smoke plume: resolution " + std::to_string(resolution) + " is outside [2, 1290]");
    }
    DensityGrid grid;
    grid.name = "density";
    grid.size = glm::ivec3(resolution);
    const double voxel = 1.0 / double(resolution);
    grid.indexToLocal = glm::dmat4(voxel);
    grid.indexToLocal[3] = glm::dvec4(glm::dvec3(0.5 * voxel - 0.5), 1.0);
    grid.values.assign(grid.voxelCount(), 0.0f);

    const SmokePlume plume(seed);
    const size_t n = size_t(resolution);
    const auto centre = [&](int index) { return float((double(index) + 0.5) * voxel - 0.5); };
    std::vector<glm::vec2> axes(n);
    for (int j = 0; j < resolution; ++j) axes[size_t(j)] = plume.axisAt(centre(j) + 0.5f);
    // The outermost layer of voxels stays 0 whatever the resolution.
    tbb::parallel_for(tbb::blocked_range<int>(1, resolution - 1), [&](const tbb::blocked_range<int>& slices) {
        for (int k = slices.begin(); k < slices.end(); ++k) {
            for (int j = 1; j < resolution - 1; ++j) {
                for (int i = 1; i < resolution - 1; ++i) {
                    grid.values[(size_t(k) * n + size_t(j)) * n + size_t(i)] =
                        plume.densityAt(glm::vec3(centre(i), centre(j), centre(k)), axes[size_t(j)]);
                }
            }
        }
    });
    return grid;
}

DensityGrid flameOfPlume(const DensityGrid& plume) {
    DensityGrid flame = plume;
    flame.name = "flame";
    const size_t rowLength = size_t(plume.size.x);
    for (int k = 0; k < plume.size.z; ++k) {
        for (int j = 0; j < plume.size.y; ++j) {
            // The voxel's height above the cube's bottom (local y + 0.5).
            const float h = float((plume.indexToLocal * glm::dvec4(0.0, double(plume.firstVoxel.y + j), 0.0, 1.0)).y) +
                            0.5f;
            const float heat = 1.0f - smoothstep(kSourceHeight, kSourceHeight + 0.45f, h);
            float* row = flame.values.data() + (size_t(k) * size_t(plume.size.y) + size_t(j)) * rowLength;
            for (size_t i = 0; i < rowLength; ++i) row[i] *= heat;
        }
    }
    return flame;
}

}  // namespace vkdr
