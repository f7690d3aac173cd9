// The procedural plume: repeatable, seed-dependent, in range, zero at the faces, and
// shaped like smoke (a column that widens and thins as it rises, broken into billows).
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "expect_error.h"
#include "volume/smoke_plume.h"

namespace vkdr::test {
namespace {

bool sameBits(const DensityGrid& a, const DensityGrid& b) {
    return a.values.size() == b.values.size() &&
           std::memcmp(a.values.data(), b.values.data(), a.values.size() * sizeof(float)) == 0;
}

glm::dvec3 localCentre(const DensityGrid& grid, glm::ivec3 voxel) {
    return glm::dvec3(grid.indexToLocal * glm::dvec4(glm::dvec3(voxel), 1.0));
}

TEST(SmokePlume, SameSeedSameBitsOtherSeedOtherPlume) {
    const DensityGrid plume = makeSmokePlume(40, 7);
    EXPECT_TRUE(sameBits(plume, makeSmokePlume(40, 7)));
    const DensityGrid other = makeSmokePlume(40, 8);
    size_t differing = 0, nonZero = 0;
    for (size_t i = 0; i < plume.values.size(); ++i) {
        nonZero += plume.values[i] > 0.0f || other.values[i] > 0.0f;
        differing += plume.values[i] != other.values[i];
    }
    EXPECT_GT(double(differing), 0.8 * double(nonZero));
}

TEST(SmokePlume, MapsTheIndexBoxOntoTheUnitCube) {
    for (int resolution : {2, 3, 17, 64}) {
        const DensityGrid plume = makeSmokePlume(resolution, 1);
        EXPECT_EQ(plume.name, "density");
        EXPECT_EQ(plume.firstVoxel, glm::ivec3(0));
        EXPECT_EQ(plume.size, glm::ivec3(resolution));
        EXPECT_EQ(plume.values.size(), size_t(resolution) * resolution * resolution);
        const double half = 0.5 / resolution;
        const glm::dvec3 first = localCentre(plume, glm::ivec3(0));
        const glm::dvec3 last = localCentre(plume, glm::ivec3(resolution - 1));
        for (int axis = 0; axis < 3; ++axis) {
            EXPECT_NEAR(first[axis], -0.5 + half, 1e-15) << resolution;
            EXPECT_NEAR(last[axis], 0.5 - half, 1e-15) << resolution;
        }
    }
}

TEST(SmokePlume, RefusesResolutionsOutOfRange) {
    for (int resolution : {-3, 0, 1, 1291}) {
        expectErrorMentioning([&] { makeSmokePlume(resolution, 1); },
                              {"resolution " + std::to_string(resolution), "[2, 1290]"});
    }
}

// Densities in [0, 1], many exact zeros around the plume, and nothing within 0.05 of a
// face (nor in the outermost layer of voxels, at any resolution).
TEST(SmokePlume, RangeZerosAndZeroBorder) {
    for (int resolution : {2, 3, 5, 24, 96}) {
        const DensityGrid plume = makeSmokePlume(resolution, 3);
        size_t zeros = 0;
        float largest = 0.0f;
        for (int k = 0; k < resolution; ++k) {
            for (int j = 0; j < resolution; ++j) {
                for (int i = 0; i < resolution; ++i) {
                    const float density = plume.at({i, j, k});
                    ASSERT_TRUE(density >= 0.0f && density <= 1.0f) << density;
                    zeros += density == 0.0f;
                    largest = std::max(largest, density);
                    const bool outermost = glm::any(glm::equal(glm::ivec3(i, j, k), glm::ivec3(0))) ||
                                           glm::any(glm::equal(glm::ivec3(i, j, k), glm::ivec3(resolution - 1)));
                    const glm::dvec3 p = localCentre(plume, {i, j, k});
                    const bool nearFace = glm::any(glm::greaterThanEqual(glm::abs(p), glm::dvec3(0.45)));
                    if (outermost || nearFace) {
                        ASSERT_EQ(density, 0.0f) << i << " " << j << " " << k;
                    }
                }
            }
        }
        if (resolution >= 24) {
            const double zeroFraction = double(zeros) / double(plume.voxelCount());
            EXPECT_GT(zeroFraction, 0.6) << resolution;
            EXPECT_LT(zeroFraction, 0.97) << resolution;
            EXPECT_GT(largest, 0.5f) << resolution;
        }
    }
}

// The density is one continuous field sampled at the voxel centres: its integral over
// the cube hardly depends on the resolution.
TEST(SmokePlume, MassHardlyDependsOnResolution) {
    auto mass = [](int resolution) {
        const DensityGrid plume = makeSmokePlume(resolution, 11);
        double sum = 0.0;
        for (float value : plume.values) sum += value;
        return sum / double(plume.voxelCount());
    };
    const double fine = mass(128);
    EXPECT_GT(fine, 0.002);
    EXPECT_NEAR(mass(64), fine, 0.05 * fine);
}

struct Slab {
    double mass = 0.0;      // sum of densities
    double spread = 0.0;    // density-weighted mean squared distance from the slab's centroid in x and z
    size_t occupied = 0;    // voxels with density > 0
};

// Statistics of the horizontal slabs of voxels in [lowHeight, highHeight) of the cube
// (height 0 at the bottom face, 1 at the top).
Slab slabOf(const DensityGrid& plume, double lowHeight, double highHeight) {
    Slab slab;
    glm::dvec2 weighted(0.0);
    double squared = 0.0;
    for (int k = 0; k < plume.size.z; ++k) {
        for (int j = 0; j < plume.size.y; ++j) {
            for (int i = 0; i < plume.size.x; ++i) {
                const glm::dvec3 p = localCentre(plume, {i, j, k});
                const double density = plume.at({i, j, k});
                if (p.y + 0.5 < lowHeight || p.y + 0.5 >= highHeight || density == 0.0) continue;
                slab.mass += density;
                weighted += density * glm::dvec2(p.x, p.z);
                squared += density * (p.x * p.x + p.z * p.z);
                ++slab.occupied;
            }
        }
    }
    const glm::dvec2 centroid = weighted / slab.mass;
    slab.spread = squared / slab.mass - glm::dot(centroid, centroid);
    return slab;
}

// It rises from near the bottom, widening with height, and stops short of the top face.
// The flame is the plume's density near the column's source, fading out within 0.45 above
// it (the source at height 0.14 of the unit cube): never more than the density, all of
// it at the bottom, none high up.
TEST(SmokePlume, FlameIsTheDensityNearTheSource) {
    const DensityGrid plume = makeSmokePlume(64, 1);
    const DensityGrid flame = flameOfPlume(plume);
    EXPECT_EQ(flame.name, "flame");
    EXPECT_EQ(flame.size, plume.size);
    EXPECT_EQ(flame.indexToLocal, plume.indexToLocal);
    double lowPlume = 0.0, lowFlame = 0.0;
    for (int k = 0; k < 64; ++k) {
        for (int j = 0; j < 64; ++j) {
            const double height = (j + 0.5) / 64.0;
            for (int i = 0; i < 64; ++i) {
                const float d = plume.at({i, j, k}), f = flame.at({i, j, k});
                ASSERT_GE(f, 0.0f);
                ASSERT_LE(f, d);
                if (height >= 0.14 + 0.45) {
                    ASSERT_EQ(f, 0.0f) << "voxel " << i << " " << j << " " << k;
                }
                if (height <= 0.14) {
                    ASSERT_EQ(f, d);
                }
                if (height < 0.25) {
                    lowPlume += d;
                    lowFlame += f;
                }
            }
        }
    }
    EXPECT_GT(lowFlame, 0.8 * lowPlume) << "the flame burns where the smoke rises from";
}

TEST(SmokePlume, RisesAndWidens) {
    for (uint32_t seed : {1u, 2u, 3u}) {
        const DensityGrid plume = makeSmokePlume(64, seed);
        EXPECT_EQ(slabOf(plume, 0.0, 0.1).occupied, 0u) << seed;
        EXPECT_EQ(slabOf(plume, 0.93, 1.0).occupied, 0u) << seed;
        const Slab low = slabOf(plume, 0.2, 0.4), high = slabOf(plume, 0.5, 0.7);
        ASSERT_GT(low.occupied, 0u) << seed;
        EXPECT_GT(high.spread, 1.5 * low.spread) << seed;
        EXPECT_GT(high.occupied, 2 * low.occupied) << seed;
    }
}

// Higher up the smoke is thinner: the mean density of occupied voxels falls. Turbulence
// makes single plumes vary (the stem can be sheared thin), so this holds over seeds.
TEST(SmokePlume, ThinsWithHeight) {
    double low = 0.0, high = 0.0;
    for (uint32_t seed = 1; seed <= 8; ++seed) {
        const DensityGrid plume = makeSmokePlume(64, seed);
        const Slab lowSlab = slabOf(plume, 0.2, 0.4), highSlab = slabOf(plume, 0.5, 0.7);
        low += lowSlab.mass / double(lowSlab.occupied);
        high += highSlab.mass / double(highSlab.occupied);
    }
    EXPECT_LT(high, 0.85 * low);
}

// Not a smooth solid column: inside the plume the density varies strongly from voxel
// to voxel's neighbourhood, with holes (zeros) among occupied voxels.
TEST(SmokePlume, IsBillowyNotSolid) {
    const DensityGrid plume = makeSmokePlume(64, 5);
    double sum = 0.0, squares = 0.0;
    size_t occupied = 0, holes = 0;
    for (int k = 1; k < 63; ++k) {
        for (int j = 1; j < 63; ++j) {
            for (int i = 1; i < 63; ++i) {
                const double density = plume.at({i, j, k});
                if (density > 0.0) {
                    sum += density;
                    squares += density * density;
                    ++occupied;
                } else if (plume.at({i - 1, j, k}) > 0.0 && plume.at({i + 1, j, k}) > 0.0) {
                    ++holes;  // empty between two occupied neighbours
                }
            }
        }
    }
    const double mean = sum / double(occupied);
    const double deviation = std::sqrt(squares / double(occupied) - mean * mean);
    EXPECT_GT(deviation / mean, 0.5);
    EXPECT_GT(holes, occupied / 1000);
}

}  // namespace
}  // namespace vkdr::test
