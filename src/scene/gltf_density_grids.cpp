#include "scene/gltf_density_grids.h"

#include <cmath>

#include "core/error.h"
#include "core/format_text.h"
#include "scene/flatten_nodes.h"
#include "scene/gltf_media.h"
#include "scene/gltf_values.h"
#include "volume/index_transform.h"
#include "volume/read_density_grid.h"

namespace vkdr {
namespace {

// The world transform of node `index`, which must have at most one parent.
glm::dmat4 nodeToWorld(const tinygltf::Model& model, int index, const std::string& field,
                       const GltfDiagnostics& diagnostics) {
    if (index < 0 || size_t(index) >= model.nodes.size()) {
        diagnostics.fail(field, "node " + std::to_string(index) + " out of range (" +
                                    std::to_string(model.nodes.size()) + " nodes)");
    }
    // A root of the rendered scene is placed there as well as under any parent it has.
    const std::vector<uint32_t> places = placesOfNodes(model, rootNodes(model, diagnostics).first);
    std::vector<int> parent(model.nodes.size(), -1);
    for (size_t n = 0; n < model.nodes.size(); ++n) {
        for (int child : model.nodes[n].children) {
            if (child >= 0 && size_t(child) < model.nodes.size()) {
                parent[size_t(child)] = int(n);
            }
        }
    }
    glm::dmat4 transform(1.0);
    size_t depth = 0;
    for (int n = index; n >= 0; n = parent[size_t(n)]) {
        if (++depth > model.nodes.size()) {
            diagnostics.fail(field, "node " + std::to_string(index) + " is its own ancestor");
        }
        if (places[size_t(n)] > 1) {
            diagnostics.fail(field, "node " + std::to_string(n) +
                                        " has several parents (a scene's root counts as one), so the grid would be "
                                        "placed more than once");
        }
        transform = glm::dmat4(localTransform(model.nodes[size_t(n)])) * transform;
    }
    return transform;
}

// The same rule as for the grid file's own transform, applied to where the node puts it;
// and the renderer takes index to world coordinates and back in float, so the
// transform and its inverse must fit.
void requireInvertible(const glm::dmat4& indexToWorld, const std::string& field, const GltfDiagnostics& diagnostics) {
    const std::string what = "the grid's placement (the node's transform times the grid's own): ";
    if (std::string problem = indexTransformProblem(indexToWorld); !problem.empty()) {
        diagnostics.fail(field, what + problem);
    }
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 3; ++row) {
            if (!std::isfinite(float(indexToWorld[column][row]))) {
                diagnostics.fail(field, what + formatText("it has an entry of %g, beyond float's range: the voxels "
                                                          "are too large, or too far away, for the renderer",
                                                          indexToWorld[column][row]));
            }
        }
    }
    const glm::dmat4 worldToIndex = glm::inverse(indexToWorld);
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 3; ++row) {
            if (!std::isfinite(float(worldToIndex[column][row]))) {
                diagnostics.fail(field, what + formatText("its inverse has an entry of %g, beyond float's range: "
                                                          "the voxels are too small, or too far from the origin for "
                                                          "their size, for the renderer",
                                                          worldToIndex[column][row]));
            }
        }
    }
}

// Reads with `readGrid` the grid a medium's "density", "emissionGrid" or "albedoGrid"
// object references; returns its index in Scene::densityGrids.
using ReadGrid = DensityGrid (*)(const std::filesystem::path&, const std::string&);

int32_t readMediumGrid(const tinygltf::Model& model, const tinygltf::Value& density, const std::string& field,
                       const std::string& defaultGrid, ReadGrid readGrid, const SceneFiles& files,
                       GltfDiagnostics& diagnostics, Scene& scene, std::vector<std::filesystem::path>& read) {
    if (!density.IsObject()) {
        diagnostics.fail(field, "expected an object {\"uri\", \"grid\", \"node\"}");
    }
    if (!density.Has("uri")) {
        diagnostics.fail(field + ".uri", "missing: the grid file (.vdb or .nvdb) is required");
    }
    const std::string uri = readString(diagnostics, density, field, "uri", "");
    if (uri.empty()) diagnostics.fail(field + ".uri", "empty: give the grid file's path relative to the scene file");
    if (isDataUri(uri)) {
        diagnostics.fail(field + ".uri", "a grid must be a .vdb or .nvdb file, not a data: URI");
    }
    if (const std::string scheme = uriScheme(uri); !scheme.empty()) {
        diagnostics.fail(field + ".uri", quotedUri(uri) + ": URIs with a scheme (" + scheme +
                                             ") are not read; give the grid file's path relative to the scene file");
    }
    const ResolvedFile resolved = files.resolveUri(uri);
    if (!resolved.problem.empty()) {
        diagnostics.fail(field + ".uri", resolved.problem);
    }
    const std::string gridName = readString(diagnostics, density, field, "grid", defaultGrid);
    glm::dmat4 placement(1.0);
    if (density.Has("node")) {
        // An index, as the JSON checks require (gltf_json_checks.cpp).
        placement = nodeToWorld(model, density.Get("node").GetNumberAsInt(), field + ".node", diagnostics);
    }
    SceneDensityGrid placed;
    placed.file = resolved.file;
    try {
        placed.grid = readGrid(resolved.file, gridName);
    } catch (const Error& e) {
        diagnostics.fail(field, e.what());
    }
    placed.indexToWorld = placement * placed.grid.indexToLocal;
    requireInvertible(placed.indexToWorld, field, diagnostics);
    read.push_back(resolved.file);
    scene.densityGrids.push_back(std::move(placed));
    return int32_t(scene.densityGrids.size() - 1);
}

// Reads the grids of the medium that `extensions` (a material's, or the root's) defines.
void readGridsOf(const tinygltf::Model& model, const tinygltf::ExtensionMap& extensions, const std::string& prefix,
                 const SceneFiles& files, GltfDiagnostics& diagnostics, Scene& scene, Medium& medium,
                 std::vector<std::filesystem::path>& read) {
    auto found = extensions.find(kMediumExtension);
    if (found == extensions.end() || !found->second.IsObject()) {
        return;
    }
    const tinygltf::Value& extension = found->second;
    const std::string field = prefix + kMediumExtension;
    struct Reference {
        const char* key;
        const char* defaultGrid;
        ReadGrid readGrid;
        int32_t& grid;
    };
    for (const Reference& reference : {Reference{"density", "density", readDensityGrid, medium.densityGrid},
                                       Reference{"emissionGrid", "flame", readEmissionGrid, medium.emissionGrid},
                                       Reference{"albedoGrid", "color", readAlbedoGrid, medium.albedoGrid}}) {
        if (extension.Has(reference.key)) {
            reference.grid = readMediumGrid(model, extension.Get(reference.key), field + "." + reference.key,
                                            reference.defaultGrid, reference.readGrid, files, diagnostics, scene,
                                            read);
        }
    }
}

}  // namespace

void readDensityGrids(const tinygltf::Model& model, const SceneFiles& files, GltfDiagnostics& diagnostics,
                      Scene& scene, std::vector<std::filesystem::path>& read) {
    for (size_t m = 0; m < model.materials.size(); ++m) {
        if (scene.materials[m].isMediumBoundary()) {
            readGridsOf(model, model.materials[m].extensions, indexed("materials", m) + ".extensions.", files,
                        diagnostics, scene, scene.media[size_t(scene.materials[m].interiorMedium)], read);
        }
    }
    if (scene.sceneMedium >= 0) {
        readGridsOf(model, model.extensions, "extensions.", files, diagnostics, scene,
                    scene.media[size_t(scene.sceneMedium)], read);
    }
}

}  // namespace vkdr
