// How a material looks a texture up: glTF's sampler wrap modes along u and v, and
// KHR_texture_transform's affine map of the texture coordinates before them.
#include <algorithm>
#include <cmath>
#include <functional>

#include "render_test_support.h"
#include "bvh/bvh.h"
#include "scene/load_scene.h"
#include "test_gltf.h"

namespace vkdr::test {
namespace {

constexpr int kWidth = 128, kHeight = 4;
// The wall's u runs over [-kUSpan / 2, kUSpan / 2] + kUOffset across the image.
constexpr double kUSpan = 7.0, kUOffset = 0.3;
const glm::vec4 kA(0.9f, 0.2f, 0.1f, 1.0f), kB(0.1f, 0.3f, 0.8f, 1.0f);

// Texel index i of n wrapped as the OpenGL specification defines it (section 8.14.2), on
// whole texel indices of the unwrapped coordinate.
int specWrap(int i, int n, TextureWrap wrap) {
    auto mod = [](int a, int m) { return ((a % m) + m) % m; };
    switch (wrap) {
        case TextureWrap::Repeat: return mod(i, n);
        case TextureWrap::ClampToEdge: return std::clamp(i, 0, n - 1);
        case TextureWrap::MirroredRepeat: {
            int a = mod(i, 2 * n) - n;
            return (n - 1) - (a >= 0 ? a : -(1 + a));
        }
    }
    return 0;
}

// 1 or 2 where every texel a bilinear lookup at u weighs is an A or every one a B (of
// the texture A A B B), else 0.
int pureColourAt(double u, TextureWrap wrap) {
    const int n = 4;
    const double st = u * n - 0.5;
    const int i0 = int(std::floor(st));
    const double f = st - i0;
    auto colour = [&](int i) { return specWrap(i, n, wrap) < 2 ? 1 : 2; };
    if (f == 0.0) return colour(i0);
    return colour(i0) == colour(i0 + 1) ? colour(i0) : 0;
}

class TextureMappingTest : public RenderTest {
protected:
    // A glowing wall filling the view, whose emission is the texture `texels` (rows of
    // `textureWidth`), looked up with `mapping` at coordinates `uvOf(position)`.
    Image render(const std::vector<glm::vec4>& texels, int textureWidth, const TextureMapping& mapping,
                 const std::function<glm::vec2(glm::vec3)>& uvOf) {
        TestGltf g;
        g.materials = {emissiveMaterial("wall", glm::vec3(1.0f), false)};
        g.meshes = {quadZ(0.0f, 0.0f, 2.0f, 1.0f, false, 0)};
        g.yfov = 0.05f;
        g.aspectRatio = float(kWidth) / float(kHeight);
        Scene scene = loadScene(g.write(tempDir(), "wall")).scene;
        scene.textures.push_back({"wall", textureWidth, int(texels.size()) / textureWidth, texels});
        scene.materials[0].emissionTexture = 0;
        scene.materials[0].emissionMapping = mapping;
        scene.uvs.clear();
        for (const glm::vec3& p : scene.positions) {
            scene.uvs.push_back(uvOf(p));
        }
        Bvh bvh = buildBvh(scene.positions, scene.triangles);
        return Renderer(testContext(), scene, bvh, {.width = kWidth, .height = kHeight, .spp = 4, .maxDepth = 1})
            .render();
    }

    // Half the width of the view at the wall, which is 1 ahead of the camera.
    static double halfWidth() { return std::tan(0.025) * double(kWidth) / double(kHeight); }

    // The u at a column's left and right edges for the wall's u = kUOffset + kUSpan / 2 *
    // x / halfWidth(). The camera looks along +z, so the image's left is the world's +x.
    static std::pair<double, double> columnUs(int column) {
        auto uAt = [](double edge) { return kUOffset + kUSpan / 2.0 * (1.0 - 2.0 * edge / kWidth); };
        return {uAt(column), uAt(column + 1)};
    }
};

TEST_F(TextureMappingTest, EachWrapModeRepeatsClampsOrMirrorsAsGltfSays) {
    for (TextureWrap wrap : {TextureWrap::Repeat, TextureWrap::ClampToEdge, TextureWrap::MirroredRepeat}) {
        TextureMapping mapping;
        mapping.wrapS = wrap;
        mapping.wrapT = TextureWrap::MirroredRepeat;  // a texture one texel high: no effect
        const Image image = render({kA, kA, kB, kB}, 4, mapping, [&](glm::vec3 p) {
            return glm::vec2(kUOffset + kUSpan / 2.0 * p.x / halfWidth(), 0.3f);
        });
        ASSERT_TRUE(allFinite(image));
        int pure[3] = {0, 0, 0};
        for (int column = 0; column < kWidth; ++column) {
            // Columns wholly inside a stretch of one colour must show exactly it.
            auto [u0, u1] = columnUs(column);
            int colour = pureColourAt(u0, wrap);
            for (int k = 1; k <= 32 && colour != 0; ++k) {
                if (pureColourAt(u0 + (u1 - u0) * k / 32.0, wrap) != colour) colour = 0;
            }
            if (colour == 0) continue;
            ++pure[colour];
            const glm::vec4 expected = colour == 1 ? kA : kB;
            for (int row = 0; row < kHeight; ++row) {
                for (int c = 0; c < 3; ++c) {
                    EXPECT_NEAR(image.rgb[(size_t(row) * kWidth + column) * 3 + c], expected[c], 1e-5f)
                        << "wrap " << int(wrap) << ", column " << column << ", u " << u0 << ".." << u1;
                }
            }
        }
        // Enough columns of each colour that a wrong mode cannot pass unseen.
        EXPECT_GE(pure[1], 12) << "wrap " << int(wrap);
        EXPECT_GE(pure[2], 12) << "wrap " << int(wrap);
    }
}

TEST_F(TextureMappingTest, ATransformLooksUpWhatTheTransformedCoordinatesWould) {
    // Four distinct texels; mirrored along u and clamped along v, so that a transform
    // applied to the wrong axis or after the wrapping would show.
    const std::vector<glm::vec4> texels = {kA, kB, glm::vec4(0.2f, 0.7f, 0.3f, 1.0f), glm::vec4(0.6f, 0.6f, 0.1f, 1.0f)};
    auto uvOf = [](glm::vec3 p) { return glm::vec2(1.3f * p.x / halfWidth(), 4.0f * p.y / halfWidth()); };
    TextureMapping transformed;
    transformed.uRow = glm::vec3(0.8f, -1.1f, 0.35f);
    transformed.vRow = glm::vec3(0.6f, 0.9f, -0.2f);
    transformed.wrapS = TextureWrap::MirroredRepeat;
    transformed.wrapT = TextureWrap::ClampToEdge;
    TextureMapping untransformed = transformed;
    untransformed.uRow = glm::vec3(1.0f, 0.0f, 0.0f);
    untransformed.vRow = glm::vec3(0.0f, 1.0f, 0.0f);
    const Image viaTransform = render(texels, 2, transformed, uvOf);
    // Texture coordinates are interpolated linearly across a triangle, so an affine map
    // of its corners' coordinates is the same map of the coordinates between them.
    const Image viaCoordinates = render(texels, 2, untransformed, [&](glm::vec3 p) {
        const glm::vec3 uv1(uvOf(p), 1.0f);
        return glm::vec2(glm::dot(transformed.uRow, uv1), glm::dot(transformed.vRow, uv1));
    });
    const Image ignoringTransform = render(texels, 2, untransformed, uvOf);
    ASSERT_TRUE(allFinite(viaTransform));
    ASSERT_EQ(viaTransform.rgb.size(), viaCoordinates.rgb.size());
    double changedByTransform = 0.0;
    for (size_t i = 0; i < viaTransform.rgb.size(); ++i) {
        // The two round differently, by a few ulps of the coordinates: a texel weight,
        // and so a pixel, moves by about 1e-6 of the texture's range.
        EXPECT_NEAR(viaTransform.rgb[i], viaCoordinates.rgb[i], 1e-4f) << "value " << i;
        changedByTransform += std::abs(viaTransform.rgb[i] - ignoringTransform.rgb[i]);
    }
    // The transform moves the image by far more than the tolerance: the check above
    // could not pass with the transform ignored.
    EXPECT_GT(changedByTransform / double(viaTransform.rgb.size()), 0.05);
}

}  // namespace
}  // namespace vkdr::test
