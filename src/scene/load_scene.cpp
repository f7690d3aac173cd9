#include "scene/load_scene.h"

#include "core/error.h"
#include "scene/flatten_nodes.h"
#include "scene/gltf_density_grids.h"
#include "scene/gltf_diagnostics.h"
#include "scene/gltf_json_checks.h"
#include "scene/gltf_lights.h"
#include "scene/gltf_materials.h"
#include "scene/gltf_media.h"
#include "scene/medium_boundaries.h"
#include "scene/read_gltf_model.h"

namespace vkdr {
namespace {

void requireUnderstoodExtensions(const tinygltf::Model& model, const GltfDiagnostics& diagnostics) {
    for (size_t i = 0; i < model.extensionsRequired.size(); ++i) {
        const std::string& name = model.extensionsRequired[i];
        if (!isUnderstoodExtension(name)) {
            diagnostics.fail(indexed("extensionsRequired", i), name + " is not supported");
        }
    }
}

void addSceneMedium(const tinygltf::Model& model, GltfDiagnostics& diagnostics, Scene& scene) {
    std::optional<Medium> medium = readSceneMedium(model, diagnostics);
    if (!medium) {
        return;
    }
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& material = scene.materials[m];
        if (material.isMediumBoundary() &&
            scene.media[size_t(material.interiorMedium)].name == medium->name) {
            diagnostics.fail(std::string("extensions.") + kMediumExtension + ".name",
                             "'" + medium->name + "' already names the medium inside " +
                                 indexed("materials", m) + "; medium names must be unique");
        }
    }
    scene.media.push_back(std::move(*medium));
    scene.sceneMedium = int32_t(scene.media.size() - 1);
}

}  // namespace

LoadedScene loadScene(const std::filesystem::path& file, const SceneFileAccess& access) {
    if (file.empty()) throw Error("the scene's file name is empty");
    GltfDiagnostics diagnostics(file.string());
    Scene scene;
    tinygltf::Model model = readGltfModel(file, access, diagnostics, scene.sourceFiles);
    requireUnderstoodExtensions(model, diagnostics);
    std::vector<std::filesystem::path> externalFiles;
    for (size_t i = 1; i < scene.sourceFiles.size(); ++i) externalFiles.push_back(scene.sourceFiles[i].file);

    scene.punctualLights = readPunctualLights(model, diagnostics);
    readMaterials(model, diagnostics, scene);
    addSceneMedium(model, diagnostics, scene);
    readDensityGrids(model, SceneFiles(file, access), diagnostics, scene, externalFiles);
    requireAttenuatedSceneEmission(scene, diagnostics);
    scene.background = readBackground(model, diagnostics);
    std::vector<MeshInstance> instances = flattenNodes(model, diagnostics, scene);
    if (scene.triangles.empty()) {
        diagnostics.fail("", "the scene has no triangles");
    }
    prepareMediumBoundaries(scene, instances, diagnostics);
    return {std::move(scene), diagnostics.takeWarnings(), std::move(externalFiles)};
}

}  // namespace vkdr
