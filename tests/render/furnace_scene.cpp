#include "furnace_scene.h"

#include <gtest/gtest.h>

#include "render_test_support.h"
#include "volume/write_density_grid.h"

namespace vkdr::test {

TestGltf furnace(glm::vec3 albedo) {
    nlohmann::json walls = emissiveMaterial("walls", kFurnaceLe, true);
    walls["pbrMetallicRoughness"]["baseColorFactor"] = {albedo.x, albedo.y, albedo.z, 1.0};
    TestGltf g;
    g.materials = {walls};
    g.meshes = {box(glm::vec3(-1.0f), glm::vec3(1.0f), 0)};
    g.cameraPosition = glm::vec3(0.1f, -0.2f, -0.3f);
    g.yfov = 1.2f;
    return g;
}

std::filesystem::path furnaceWithOneDenseVoxelPerCell(glm::vec3 albedo, const MediumCoefficients& sparse, int denseAt,
                                                      float elsewhere, const std::filesystem::path& dir) {
    TestGltf g = furnace(albedo);
    nlohmann::json medium = vkdrMediumMaterial("sparse", sparse.sigmaA, sparse.sigmaS, 0.0f);
    medium["extensions"]["VKDR_participating_media"]["density"] = {{"uri", "sparse.vdb"}};
    medium["extensions"]["VKDR_participating_media"]["emission"] = {sparse.emission.x, sparse.emission.y,
                                                                    sparse.emission.z};
    g.materials.push_back(medium);
    g.meshes.push_back(box(glm::vec3(-0.5f), glm::vec3(0.5f), 1));
    DensityGrid grid;
    grid.name = "density";
    grid.size = glm::ivec3(16);
    grid.indexToLocal = glm::dmat4(glm::dvec4(1.0 / 16, 0, 0, 0), glm::dvec4(0, 1.0 / 16, 0, 0),
                                   glm::dvec4(0, 0, 1.0 / 16, 0), glm::dvec4(glm::dvec3(-0.5 + 0.5 / 16), 1.0));
    for (int i = 0; i < 16 * 16 * 16; ++i) {
        glm::ivec3 v(i % 16, (i / 16) % 16, i / 256);
        grid.values.push_back(v % 8 == glm::ivec3(denseAt) ? 1.0f : elsewhere);
    }
    writeDensityGridVdb(dir / "sparse.vdb", grid);
    return g.write(dir, "furnace");
}

void expectUniformRadiance(const Image& image, glm::dvec3 expected) {
    ASSERT_TRUE(allFinite(image));
    PixelStatistics s = pixelStatistics(image);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(s.mean[c], expected[c], 5.0 * s.standardError[c] + 1e-6) << "channel " << c;
    }
}

}  // namespace vkdr::test
