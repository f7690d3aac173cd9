#include "render/light_distribution.h"

namespace vkdr {
namespace {

glm::vec3 averageTexel(const Texture& texture) {
    glm::dvec3 sum(0.0);
    for (const glm::vec4& t : texture.texels) {
        sum += glm::dvec3(t);
    }
    return texture.texels.empty() ? glm::vec3(0.0f) : glm::vec3(sum / double(texture.texels.size()));
}

}  // namespace

std::vector<glm::vec3> meanEmittedRadiance(const Scene& scene) {
    std::vector<glm::vec3> radiance;
    for (const Material& material : scene.materials) {
        radiance.push_back(material.emissionTexture >= 0
                               ? material.emission * averageTexel(scene.textures[material.emissionTexture])
                               : material.emission);
    }
    return radiance;
}

LightDistribution buildLightDistribution(const Scene& scene, std::span<const glm::vec3> radiance) {
    std::vector<double> materialPower(scene.materials.size(), 0.0);
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const glm::vec3& r = radiance[m];
        materialPower[m] = (r.r + r.g + r.b) / 3.0 * (scene.materials[m].doubleSided ? 2.0 : 1.0);
    }

    LightDistribution lights;
    lights.trianglePmf.assign(scene.triangles.size(), 0.0f);
    std::vector<double> power;
    for (size_t t = 0; t < scene.triangles.size(); ++t) {
        double p = materialPower[scene.triangleMaterial[t]];
        if (p <= 0.0) {
            continue;
        }
        const glm::uvec3& tri = scene.triangles[t];
        glm::dvec3 e1 = glm::dvec3(scene.positions[tri[1]] - scene.positions[tri[0]]);
        glm::dvec3 e2 = glm::dvec3(scene.positions[tri[2]] - scene.positions[tri[0]]);
        double area = 0.5 * glm::length(glm::cross(e1, e2));
        if (area > 0.0) {
            lights.triangles.push_back(static_cast<uint32_t>(t));
            power.push_back(p * area);
        }
    }
    double total = 0.0;
    for (double p : power) {
        total += p;
    }
    lights.cdf.push_back(0.0f);
    double running = 0.0;
    for (size_t i = 0; i < power.size(); ++i) {
        running += power[i];
        lights.cdf.push_back(i + 1 == power.size() ? 1.0f : static_cast<float>(running / total));
        lights.trianglePmf[lights.triangles[i]] = static_cast<float>(power[i] / total);
    }
    return lights;
}

}  // namespace vkdr
