#pragma once
#include <vector>

#include "scene/flatten_nodes.h"
#include "scene/gltf_diagnostics.h"
#include "scene/scene.h"

namespace vkdr {

// Makes the medium boundaries usable by the renderer. The triangles of one mesh
// instance that share a boundary material form one boundary, which must be closed
// (every edge shared by exactly two triangles of opposite winding). Each of its shells
// (connected closed surfaces) is wound so that normals point out of the enclosed medium:
// outwards, or inwards for a cavity (a shell inside an odd number of the boundary's
// other shells); a shell wound as the shell directly around it is refused. Fills
// Scene::triangleOutsideMedium: a boundary sits in the medium of the innermost other
// boundary containing it, else in Scene::sceneMedium. Warns when two boundaries
// intersect, since overlapping media are not supported.
void prepareMediumBoundaries(Scene& scene, const std::vector<MeshInstance>& instances,
                             GltfDiagnostics& diagnostics);

}  // namespace vkdr
