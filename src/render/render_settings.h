#pragma once
#include <cstdint>
#include <string>

namespace vkdr {

// The largest image side rendered: 16384^2 pixels keep pixel indices and every per-pixel
// buffer size within 32 bits.
inline constexpr int kMaxImageSide = 16384;
// The pass loop counts samples in 32 bits; far more than any render needs.
inline constexpr uint32_t kMaxSamplesPerPixel = 1u << 20;

struct RenderSettings {
    std::string camera;      // empty: the scene's first camera
    int width = 0;           // 0: from the other side and the camera's aspect ratio
    int height = 0;          //    (512 wide when neither is given)
    uint32_t spp = 16;       // samples per pixel
    uint32_t maxDepth = 8;   // scattering vertices per path, as in pbrt: 1 = direct light only
    uint32_t seed = 0;
    // Upper bound on paths in flight per pass; 0 picks one from the device's memory.
    uint32_t pathsPerPass = 0;
    // Device memory a gradient evaluation may spend keeping half of its paths' radiance
    // (32 bytes a path) instead of rendering them again (Renderer::renderWithGradients);
    // at most an eighth of the device's memory is used whatever this says.
    uint64_t keptRadianceBytes = uint64_t(256) << 20;
    // Next-event estimation in scattering homogeneous media also samples distances towards
    // the light (equiangular sampling, combined with the free flight's by MIS). Off: only the
    // free flight's collisions estimate direct light: cheaper, and noisier near lights.
    bool equiangularSampling = true;
};

}  // namespace vkdr
