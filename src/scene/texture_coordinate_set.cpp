#include "scene/texture_coordinate_set.h"

#include "scene/gltf_materials.h"
#include "scene/gltf_textures.h"
#include "scene/gltf_values.h"

namespace vkdr {

int textureCoordinateSet(const tinygltf::TextureInfo& info, std::string_view field,
                         const GltfDiagnostics& diagnostics) {
    auto transform = info.extensions.find(kTextureTransformExtension);
    if (transform != info.extensions.end() && transform->second.Has("texCoord")) {
        // The JSON checks have made it an index.
        return int(readNumber(diagnostics, transform->second,
                              std::string(field) + ".extensions." + kTextureTransformExtension, "texCoord", 0.0));
    }
    return info.texCoord;
}

int materialTextureCoordinateSet(const tinygltf::Material& material, const std::string& field,
                                 GltfDiagnostics& diagnostics) {
    const std::string baseColorField = field + ".pbrMetallicRoughness.baseColorTexture";
    const std::string emissionField = field + ".emissiveTexture";
    const tinygltf::TextureInfo& baseColor = material.pbrMetallicRoughness.baseColorTexture;
    const tinygltf::TextureInfo& emission = material.emissiveTexture;
    const int baseColorSet = baseColor.index >= 0 ? textureCoordinateSet(baseColor, baseColorField, diagnostics) : -1;
    // An emission texture multiplies emissiveFactor: with a factor of 0 it does nothing,
    // and its set matters nowhere.
    const int emissionSet = emission.index >= 0 && hasEmissiveFactor(material)
                                ? textureCoordinateSet(emission, emissionField, diagnostics)
                                : -1;
    if (baseColorSet >= 0 && emissionSet >= 0 && baseColorSet != emissionSet) {
        diagnostics.warn(emissionField, "looks up TEXCOORD_" + std::to_string(emissionSet) +
                                            " and the base colour texture TEXCOORD_" + std::to_string(baseColorSet) +
                                            "; a material's textures share one set: both use TEXCOORD_" +
                                            std::to_string(baseColorSet));
    }
    if (baseColorSet >= 0) return baseColorSet;
    return emissionSet >= 0 ? emissionSet : 0;
}

}  // namespace vkdr
