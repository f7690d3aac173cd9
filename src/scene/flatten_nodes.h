#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <tiny_gltf.h>

#include "scene/gltf_diagnostics.h"
#include "scene/scene.h"

namespace vkdr {

// The triangles one node's mesh contributed, contiguous in Scene::triangles.
struct MeshInstance {
    std::string description;  // for messages, e.g. "meshes[2] ('Box') at nodes[5] ('Smoke')"
    uint32_t firstTriangle = 0;
    uint32_t triangleCount = 0;
};

// A node's transform relative to its parent: its matrix, or translation * rotation * scale.
glm::mat4 localTransform(const tinygltf::Node& node);

// The nodes the rendered scene starts from (the default scene's, else the first scene's,
// else every node that is no node's child), and the JSON path that lists them.
std::pair<std::vector<int>, std::string> rootNodes(const tinygltf::Model& model, const GltfDiagnostics& diagnostics);

// How many places each node has: one for each time `roots` or a node's children list it.
// glTF gives a node one; a root that is also a child has two.
std::vector<uint32_t> placesOfNodes(const tinygltf::Model& model, const std::vector<int>& roots);

// Walks the glTF scene's node hierarchy (the default scene, else the first, else every
// root node) and bakes each mesh instance into world space: appends to
// Scene::positions, normals, uvs, triangles and triangleMaterial, and to Scene::cameras and
// Scene::lightPlacements in the order the nodes are visited. Triangles are wound counter-clockwise seen from the
// front in world space, even under mirroring transforms. Primitives without a material
// get a glTF-default material named "default", appended to Scene::materials.
std::vector<MeshInstance> flattenNodes(const tinygltf::Model& model, GltfDiagnostics& diagnostics,
                                       Scene& scene);

}  // namespace vkdr
