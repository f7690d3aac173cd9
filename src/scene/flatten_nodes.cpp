#include "scene/flatten_nodes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "scene/gltf_accessors.h"
#include "scene/gltf_lights.h"
#include "scene/mesh_placement.h"
#include "scene/orthographic_view.h"
#include "scene/texture_coordinate_set.h"
#include "scene/unique_name.h"

namespace vkdr {
namespace {

// Bounds on what a file can make the loader build. The largest scenes vkdiffrender is
// meant for (10M triangles from tools/make_scene) fit well within them; a hierarchy that
// instances a mesh exponentially often (each node listing the next twice) or nests
// nodes deeper than any exporter does is refused before it exhausts memory, time or
// the stack.
constexpr size_t kMaxSceneTriangles = size_t(1) << 25;
constexpr size_t kMaxSceneVertices = size_t(1) << 26;
constexpr size_t kMaxNodeDepth = 1000;
constexpr size_t kMaxNodeVisits = size_t(1) << 20;


const char* modeName(int mode) {
    switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    default: return "unknown";
    }
}

// Rays are built from the camera's axes, which must be a rigid, right-handed frame. glTF
// cameras look down their node's -Z with its +Y up: the view direction is the node's -Z,
// up is the node's +Y made perpendicular to it, and right follows from the two, so a
// scale (mirroring ones included) or a shear neither mirrors nor skews the image. In
// doubles, so a large scale does not overflow; a collapsed frame comes out not finite.
glm::mat4 rigidCameraToWorld(const glm::mat4& nodeToWorld) {
    const glm::dvec3 back = glm::normalize(glm::dvec3(nodeToWorld[2]));
    const glm::dvec3 nodeUp(nodeToWorld[1]);
    const glm::dvec3 up = glm::normalize(nodeUp - glm::dot(nodeUp, back) * back);
    const glm::dvec3 right = glm::cross(up, back);
    return glm::mat4(glm::vec4(glm::vec3(right), 0.0f), glm::vec4(glm::vec3(up), 0.0f),
                     glm::vec4(glm::vec3(back), 0.0f), nodeToWorld[3]);
}

std::string describe(std::string_view array, size_t index, const std::string& name) {
    return indexed(array, index) + (name.empty() ? "" : " ('" + name + "')");
}

// A primitive as read from the file, shared by every instance of its mesh.
struct DecodedPrimitive {
    std::string field;                  // its JSON path, for messages
    std::vector<glm::vec3> positions;   // in mesh space
    std::vector<glm::vec2> uvs;         // one per position
    std::vector<glm::vec3> colors;      // COLOR_0's RGB, one per position, or none
    std::vector<glm::vec3> normals;     // one per position, or none (flat shading)
    std::vector<glm::uvec3> triangles;  // counter-clockwise, indexing positions
    uint32_t material = 0;
};

// Where a node index is listed: slot `slot` of the root list (parent < 0) or of node
// `parent`'s children. It becomes a JSON path only for a message, since a hierarchy may
// instance millions of nodes.
struct NodeSlot {
    int parent = -1;
    size_t slot = 0;
};

class NodeFlattener {
public:
    NodeFlattener(const tinygltf::Model& model, GltfDiagnostics& diagnostics, Scene& scene, std::string rootsField)
        : model_(model), diagnostics_(diagnostics), scene_(scene), rootsField_(std::move(rootsField)) {}

    void visit(int nodeIndex, const glm::mat4& parentToWorld, NodeSlot where, size_t depth = 0) {
        if (nodeIndex < 0 || size_t(nodeIndex) >= model_.nodes.size()) {
            diagnostics_.fail(fieldOf(where), "node " + std::to_string(nodeIndex) + " out of range (" +
                                                  std::to_string(model_.nodes.size()) + " nodes)");
        }
        if (depth >= kMaxNodeDepth) {
            diagnostics_.fail(fieldOf(where), "the node hierarchy is nested more than " +
                                                  std::to_string(kMaxNodeDepth) + " levels deep");
        }
        if (++visits_ > kMaxNodeVisits) {
            diagnostics_.fail(fieldOf(where), "the node hierarchy instances more than " +
                                                  std::to_string(kMaxNodeVisits) +
                                                  " nodes (nodes listed as children of several parents multiply)");
        }
        const tinygltf::Node& node = model_.nodes[size_t(nodeIndex)];
        glm::mat4 nodeToWorld = parentToWorld * localTransform(node);
        if (node.skin >= 0) {
            diagnostics_.warn(indexed("nodes", size_t(nodeIndex)) + ".skin",
                              "skinning is ignored; the bind pose is used");
        }
        if (node.mesh >= 0) {
            addMeshInstance(size_t(nodeIndex), nodeToWorld);
        }
        if (node.camera >= 0) {
            addCamera(node, indexed("nodes", size_t(nodeIndex)), nodeToWorld);
        }
        if (auto light = placeNodeLight(model_, size_t(nodeIndex), nodeToWorld, diagnostics_)) {
            scene_.lightPlacements.push_back(*light);
        }
        for (size_t c = 0; c < node.children.size(); ++c) {
            visit(node.children[c], nodeToWorld, {nodeIndex, c}, depth + 1);
        }
    }

    std::vector<MeshInstance> takeInstances() { return std::move(instances_); }

private:
    std::string fieldOf(NodeSlot where) const {
        return where.parent < 0 ? indexed(rootsField_, where.slot)
                                : indexed(indexed("nodes", size_t(where.parent)) + ".children", where.slot);
    }

    void addMeshInstance(size_t nodeIndex, const glm::mat4& meshToWorld) {
        const tinygltf::Node& node = model_.nodes[nodeIndex];
        if (size_t(node.mesh) >= model_.meshes.size()) {
            diagnostics_.fail(indexed("nodes", nodeIndex) + ".mesh",
                              "mesh " + std::to_string(node.mesh) + " out of range (" +
                                  std::to_string(model_.meshes.size()) + " meshes)");
        }
        const tinygltf::Mesh& mesh = model_.meshes[size_t(node.mesh)];
        MeshInstance instance;
        const std::string nodeDescription = describe("nodes", nodeIndex, node.name);
        instance.description = describe("meshes", size_t(node.mesh), mesh.name) + " at " + nodeDescription;
        instance.firstTriangle = uint32_t(scene_.triangles.size());
        for (const DecodedPrimitive& primitive : decodedMesh(size_t(node.mesh))) {
            addPrimitive(primitive, meshToWorld, nodeDescription);
        }
        instance.triangleCount = uint32_t(scene_.triangles.size()) - instance.firstTriangle;
        instances_.push_back(std::move(instance));
    }

    // Each mesh is read once, however often the hierarchy instances it.
    const std::vector<DecodedPrimitive>& decodedMesh(size_t meshIndex) {
        auto found = decodedMeshes_.find(meshIndex);
        if (found != decodedMeshes_.end()) {
            return found->second;
        }
        const tinygltf::Mesh& mesh = model_.meshes[meshIndex];
        std::vector<DecodedPrimitive> primitives;
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            primitives.push_back(decodePrimitive(mesh.primitives[p],
                                                 indexed(indexed("meshes", meshIndex) + ".primitives", p)));
        }
        return decodedMeshes_.emplace(meshIndex, std::move(primitives)).first->second;
    }

    // A vertex attribute of `count` elements: one per position.
    void requireOnePerPosition(size_t count, const DecodedPrimitive& decoded, const std::string& field) {
        if (count != decoded.positions.size()) {
            diagnostics_.fail(field, std::to_string(count) + " elements, POSITION has " +
                                         std::to_string(decoded.positions.size()));
        }
    }

    DecodedPrimitive decodePrimitive(const tinygltf::Primitive& primitive, const std::string& field) {
        int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            diagnostics_.fail(field + ".mode", std::string("only triangles are supported, got mode ") +
                                                   std::to_string(mode) + " (" + modeName(mode) + ")");
        }
        auto position = primitive.attributes.find("POSITION");
        if (position == primitive.attributes.end()) {
            diagnostics_.fail(field + ".attributes", "no POSITION attribute");
        }
        if (!primitive.targets.empty()) {
            diagnostics_.warn(field + ".targets", "morph targets are ignored");
        }
        DecodedPrimitive decoded;
        decoded.field = field;
        decoded.positions = readVec3s(model_, position->second, diagnostics_, field + ".attributes.POSITION");
        decoded.uvs.assign(decoded.positions.size(), glm::vec2(0.0f));
        const std::string texcoordName = "TEXCOORD_" + std::to_string(textureCoordinateSetOf(primitive.material));
        if (auto texcoord = primitive.attributes.find(texcoordName); texcoord != primitive.attributes.end()) {
            decoded.uvs = readTexcoords(model_, texcoord->second, diagnostics_, field + ".attributes." + texcoordName);
            requireOnePerPosition(decoded.uvs.size(), decoded, field + ".attributes." + texcoordName);
        } else if (texcoordName != "TEXCOORD_0") {
            diagnostics_.warn(field + ".attributes", "no " + texcoordName + ", which the textures of material " +
                                                         std::to_string(primitive.material) +
                                                         " look up: its texture coordinates are (0, 0)");
        }
        if (auto color = primitive.attributes.find("COLOR_0"); color != primitive.attributes.end()) {
            decoded.colors = readColors(model_, color->second, diagnostics_, field + ".attributes.COLOR_0");
            requireOnePerPosition(decoded.colors.size(), decoded, field + ".attributes.COLOR_0");
        }
        if (auto normal = primitive.attributes.find("NORMAL"); normal != primitive.attributes.end()) {
            decoded.normals = readVec3s(model_, normal->second, diagnostics_, field + ".attributes.NORMAL");
            requireOnePerPosition(decoded.normals.size(), decoded, field + ".attributes.NORMAL");
        }
        std::vector<uint32_t> indices;
        if (primitive.indices >= 0) {
            indices = readIndices(model_, primitive.indices, diagnostics_, field + ".indices");
        } else {
            indices.resize(decoded.positions.size());
            for (size_t i = 0; i < indices.size(); ++i) {
                indices[i] = uint32_t(i);
            }
        }
        for (uint32_t index : indices) {
            if (index >= decoded.positions.size()) {
                diagnostics_.fail(field + ".indices", "vertex index " + std::to_string(index) +
                                                          " out of range (" +
                                                          std::to_string(decoded.positions.size()) +
                                                          " vertices)");
            }
        }
        decoded.triangles = triangleList(mode, indices, field);
        decoded.material = materialIndex(primitive.material, field + ".material");
        return decoded;
    }

    // `node` describes the node placing this instance, for messages.
    void addPrimitive(const DecodedPrimitive& primitive, const glm::mat4& meshToWorld, const std::string& node) {
        requireRoomFor(primitive.positions.size(), primitive.triangles.size(), primitive.field);
        // A mirroring transform turns counter-clockwise triangles clockwise (glTF spec,
        // "Meshes": the determinant decides the winding), so swap two corners back.
        const MeshPlacement placement(meshToWorld);

        uint32_t base = uint32_t(scene_.positions.size());
        for (size_t v = 0; v < primitive.positions.size(); ++v) {
            glm::vec3 world = glm::vec3(meshToWorld * glm::vec4(primitive.positions[v], 1.0f));
            if (!std::isfinite(world.x) || !std::isfinite(world.y) || !std::isfinite(world.z)) {
                diagnostics_.fail(primitive.field + ".attributes.POSITION",
                                  "vertex " + std::to_string(v) + " is not finite in world space, at " + node);
            }
            scene_.positions.push_back(world);
        }
        scene_.uvs.insert(scene_.uvs.end(), primitive.uvs.begin(), primitive.uvs.end());
        // Vertex colours for every vertex once any primitive has them: white where none.
        if (!primitive.colors.empty() || !scene_.colors.empty()) {
            scene_.colors.resize(base, glm::vec3(1.0f));
            if (primitive.colors.empty()) {
                scene_.colors.resize(scene_.positions.size(), glm::vec3(1.0f));
            } else {
                scene_.colors.insert(scene_.colors.end(), primitive.colors.begin(), primitive.colors.end());
            }
        }
        // Normals transform by the inverse transpose, which keeps them perpendicular to
        // the surface under non-uniform scales and turns them with a mirroring transform.
        for (size_t v = 0; v < primitive.positions.size(); ++v) {
            scene_.normals.push_back(primitive.normals.empty() ? glm::vec3(0.0f)
                                                               : placement.worldNormal(primitive.normals[v]));
        }
        for (size_t t = 0; t < primitive.triangles.size(); ++t) {
            glm::uvec3 triangle = primitive.triangles[t] + glm::uvec3(base);
            if (placement.mirrored) {
                std::swap(triangle.y, triangle.z);
            }
            requireFiniteArea(triangle, primitive.field, "triangle " + std::to_string(t) + " at " + node);
            scene_.triangles.push_back(triangle);
            scene_.triangleMaterial.push_back(primitive.material);
        }
    }

    // The renderer takes a triangle's normal and area from the cross product of its edges
    // in float; where that overflows, the triangle would be missed by every ray.
    void requireFiniteArea(glm::uvec3 triangle, const std::string& field, const std::string& what) const {
        const glm::vec3 p0 = scene_.positions[triangle.x];
        const glm::vec3 normal = glm::cross(scene_.positions[triangle.y] - p0, scene_.positions[triangle.z] - p0);
        if (!std::isfinite(normal.x) || !std::isfinite(normal.y) || !std::isfinite(normal.z)) {
            diagnostics_.fail(field, what + " is too large in world space: its edges' cross product (twice its area) "
                                            "is beyond float range (3.4e+38)");
        }
    }

    // Keeps every vertex index within 32 bits and the scene within memory.
    void requireRoomFor(size_t vertices, size_t triangles, const std::string& field) const {
        if (scene_.positions.size() + vertices > kMaxSceneVertices ||
            scene_.triangles.size() + triangles > kMaxSceneTriangles) {
            diagnostics_.fail(field, "the scene would exceed " + std::to_string(kMaxSceneTriangles) +
                                         " triangles or " + std::to_string(kMaxSceneVertices) +
                                         " vertices with all mesh instances");
        }
    }

    std::vector<glm::uvec3> triangleList(int mode, const std::vector<uint32_t>& indices,
                                         const std::string& field) const {
        std::vector<glm::uvec3> triangles;
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (indices.size() % 3 != 0) {
                diagnostics_.fail(field, std::to_string(indices.size()) +
                                             " vertices do not make whole triangles");
            }
            for (size_t i = 0; i + 2 < indices.size(); i += 3) {
                triangles.emplace_back(indices[i], indices[i + 1], indices[i + 2]);
            }
        } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            // Every other strip triangle is listed clockwise; swap to keep the winding.
            for (size_t i = 0; i + 2 < indices.size(); ++i) {
                if (i % 2 == 0) {
                    triangles.emplace_back(indices[i], indices[i + 1], indices[i + 2]);
                } else {
                    triangles.emplace_back(indices[i + 1], indices[i], indices[i + 2]);
                }
            }
        } else {
            for (size_t i = 1; i + 1 < indices.size(); ++i) {
                triangles.emplace_back(indices[0], indices[i], indices[i + 1]);
            }
        }
        return triangles;
    }

    // The TEXCOORD set whose uvs a primitive of glTF material `material` (-1: the default
    // material) keeps, once per material.
    int textureCoordinateSetOf(int material) {
        if (material < 0 || size_t(material) >= model_.materials.size() ||
            scene_.materials[size_t(material)].interiorMedium >= 0) {
            return 0;  // the default material, one materialIndex refuses, or a medium's boundary (no textures)
        }
        auto [found, added] = textureCoordinateSets_.try_emplace(material, 0);
        if (added) {
            found->second = materialTextureCoordinateSet(model_.materials[size_t(material)],
                                                         indexed("materials", size_t(material)), diagnostics_);
        }
        return found->second;
    }

    uint32_t materialIndex(int material, const std::string& field) {
        if (material >= 0) {
            if (size_t(material) >= model_.materials.size()) {
                diagnostics_.fail(field, "material " + std::to_string(material) +
                                             " out of range (" +
                                             std::to_string(model_.materials.size()) +
                                             " materials)");
            }
            return uint32_t(material);
        }
        if (!defaultMaterial_) {
            Material fallback;  // glTF's default: white, not emissive, single-sided
            fallback.name = firstFreeName("default", [&](const std::string& name) {
                return std::any_of(scene_.materials.begin(), scene_.materials.end(),
                                   [&](const Material& existing) { return existing.name == name; });
            });
            scene_.materials.push_back(fallback);
            defaultMaterial_ = uint32_t(scene_.materials.size() - 1);
        }
        return *defaultMaterial_;
    }

    void addCamera(const tinygltf::Node& node, const std::string& nodeField,
                   const glm::mat4& cameraToWorld) {
        if (size_t(node.camera) >= model_.cameras.size()) {
            diagnostics_.fail(nodeField + ".camera", "camera " + std::to_string(node.camera) +
                                                         " out of range (" +
                                                         std::to_string(model_.cameras.size()) +
                                                         " cameras)");
        }
        const tinygltf::Camera& source = model_.cameras[size_t(node.camera)];
        std::string cameraField = indexed("cameras", size_t(node.camera));
        Camera camera;
        if (source.type == "perspective") {
            // Held to the float the renderer takes: a double just under pi rounds to float's
            // pi, and one too small for a float (1e-50) to 0.
            const float yfov = float(source.perspective.yfov);
            if (!(yfov > 0.0f && yfov < std::numbers::pi_v<float>)) {
                diagnostics_.fail(cameraField + ".perspective.yfov",
                                  "must be in (0, pi) as a float, got " + formatNumber(source.perspective.yfov));
            }
            // Absent is 0 (the image's aspect ratio decides).
            requireUsableAspect(source.perspective.aspectRatio, cameraField + ".perspective.aspectRatio", "");
            camera.yfov = yfov;
            camera.aspectRatio = float(source.perspective.aspectRatio);
        } else if (source.type == "orthographic") {
            const std::string field = cameraField + ".orthographic";
            requireOrthographicMagnification(source.orthographic.xmag, field + ".xmag");
            requireOrthographicMagnification(source.orthographic.ymag, field + ".ymag");
            const double aspect = source.orthographic.xmag / source.orthographic.ymag;
            requireUsableAspect(aspect, field, "xmag / ymag ");
            camera.orthographicHalfHeight = float(source.orthographic.ymag);
            camera.aspectRatio = float(aspect);
        } else {
            diagnostics_.warn(cameraField, "camera type '" + source.type +
                                               "' is neither perspective nor orthographic; skipped");
            return;
        }
        camera.name = !node.name.empty() ? node.name : !source.name.empty() ? source.name : cameraField;
        // --camera and experiments pick cameras by name: a repeat gets a name of its own.
        const std::string given = camera.name;
        camera.name = firstFreeName(given, [&](const std::string& name) {
            return std::any_of(scene_.cameras.begin(), scene_.cameras.end(),
                               [&](const Camera& earlier) { return earlier.name == name; });
        });
        if (camera.name != given) {
            diagnostics_.warn(nodeField, "camera '" + given + "' is an earlier camera's name; this one is named '" +
                                             camera.name + "'");
        }
        camera.cameraToWorld = rigidCameraToWorld(cameraToWorld);
        for (int column = 0; column < 4; ++column) {
            glm::vec4 axis = camera.cameraToWorld[column];
            if (!std::isfinite(axis.x) || !std::isfinite(axis.y) || !std::isfinite(axis.z)) {
                diagnostics_.fail(nodeField, "the camera's transform is degenerate (it collapses the node's -Z "
                                             "axis, or its +Y axis onto -Z) or not finite");
            }
        }
        scene_.cameras.push_back(std::move(camera));
    }

    // A wider camera than 1e4 : 1 makes no image of at most 16384 pixels a side.
    void requireUsableAspect(double aspect, const std::string& field, const std::string& what) {
        if (aspect != 0.0 && !(aspect >= 1e-4 && aspect <= 1e4)) {
            diagnostics_.fail(field, what + "must be in [1e-4, 1e4], got " + formatNumber(aspect));
        }
    }

    // glTF's xmag and ymag: half the view's width and height in world units, held to the
    // floats the renderer takes. glTF allows negative ones (a mirrored view), which no
    // exporter writes.
    void requireOrthographicMagnification(double magnification, const std::string& field) {
        if (!usableOrthographicHalfExtent(magnification)) {
            diagnostics_.fail(field, "must be > 0 and a normal float (1.2e-38 to 3.4e+38), got " +
                                        formatNumber(magnification));
        }
    }

    const tinygltf::Model& model_;
    GltfDiagnostics& diagnostics_;
    Scene& scene_;
    std::string rootsField_;      // the JSON path of the root list
    size_t visits_ = 0;           // nodes visited, counting each instance
    std::map<size_t, std::vector<DecodedPrimitive>> decodedMeshes_;  // by mesh index
    std::optional<uint32_t> defaultMaterial_;
    std::map<int, int> textureCoordinateSets_;  // glTF material -> its TEXCOORD set
    std::vector<MeshInstance> instances_;
};


// glTF gives a node one place, as a root of the scene or as a child of one node. A node
// listed in several is rendered at each, as an instance; say so, since it is more often
// a slip than meant.
void warnOfNodesPlacedTwice(const tinygltf::Model& model, const std::vector<int>& roots, const std::string& rootsField,
                            GltfDiagnostics& diagnostics) {
    const std::vector<uint32_t> places = placesOfNodes(model, roots);
    for (size_t n = 0; n < places.size(); ++n) {
        if (places[n] > 1) {
            diagnostics.warn(indexed("nodes", n), "listed " + std::to_string(places[n]) + " times in " + rootsField +
                                                      " and the nodes' children; glTF gives a node one place, and "
                                                      "it is rendered at each");
        }
    }
}

// glTF's nodes form disjoint trees. A cycle is refused among every node, those the scene
// does not reach too (they would not render, but the file is not glTF and other readers
// refuse it or loop), before NodeFlattener walks from the roots. Depth-first, with an
// explicit stack: a chain of a million nodes is valid.
void requireAcyclicNodeHierarchy(const tinygltf::Model& model, const GltfDiagnostics& diagnostics) {
    enum class State : uint8_t { unseen, onPath, done };
    std::vector<State> state(model.nodes.size(), State::unseen);
    struct Frame {
        size_t node;
        size_t nextChild;
    };
    std::vector<Frame> path;
    for (size_t start = 0; start < model.nodes.size(); ++start) {
        if (state[start] != State::unseen) continue;
        state[start] = State::onPath;
        path.push_back({start, 0});
        while (!path.empty()) {
            Frame& frame = path.back();
            const std::vector<int>& children = model.nodes[frame.node].children;
            if (frame.nextChild == children.size()) {
                state[frame.node] = State::done;
                path.pop_back();
                continue;
            }
            const size_t slot = frame.nextChild++;
            const int child = children[slot];
            if (child < 0 || size_t(child) >= model.nodes.size() || state[size_t(child)] == State::done) continue;
            if (state[size_t(child)] == State::onPath) {
                diagnostics.fail(indexed(indexed("nodes", frame.node) + ".children", slot),
                                 "node " + std::to_string(child) +
                                     " is its own ancestor (cycle in the node hierarchy)");
            }
            state[size_t(child)] = State::onPath;
            path.push_back({size_t(child), 0});
        }
    }
}

}  // namespace

std::vector<uint32_t> placesOfNodes(const tinygltf::Model& model, const std::vector<int>& roots) {
    std::vector<uint32_t> places(model.nodes.size(), 0);
    auto count = [&](int node) {
        if (node >= 0 && size_t(node) < places.size()) ++places[size_t(node)];
    };
    for (int root : roots) count(root);
    for (const tinygltf::Node& node : model.nodes) {
        for (int child : node.children) count(child);
    }
    return places;
}

std::pair<std::vector<int>, std::string> rootNodes(const tinygltf::Model& model, const GltfDiagnostics& diagnostics) {
    if (model.defaultScene >= 0 && size_t(model.defaultScene) >= model.scenes.size()) {
        diagnostics.fail("scene", "scene " + std::to_string(model.defaultScene) +
                                      " out of range (" + std::to_string(model.scenes.size()) +
                                      " scenes)");
    }
    if (!model.scenes.empty()) {
        size_t scene = model.defaultScene >= 0 ? size_t(model.defaultScene) : 0;
        return {model.scenes[scene].nodes, indexed("scenes", scene) + ".nodes"};
    }
    std::vector<bool> isChild(model.nodes.size(), false);
    for (const tinygltf::Node& node : model.nodes) {
        for (int child : node.children) {
            if (child >= 0 && size_t(child) < isChild.size()) {
                isChild[size_t(child)] = true;
            }
        }
    }
    std::vector<int> roots;
    for (size_t n = 0; n < model.nodes.size(); ++n) {
        if (!isChild[n]) {
            roots.push_back(int(n));
        }
    }
    return {roots, "nodes"};
}

glm::mat4 localTransform(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        return glm::mat4(glm::make_mat4(node.matrix.data()));  // column-major, as glm
    }
    glm::mat4 transform(1.0f);
    if (node.translation.size() == 3) {
        transform = glm::translate(transform, glm::vec3(glm::make_vec3(node.translation.data())));
    }
    if (node.rotation.size() == 4) {
        // glTF stores (x, y, z, w); glm's constructor takes w first.
        glm::quat rotation(float(node.rotation[3]), float(node.rotation[0]),
                           float(node.rotation[1]), float(node.rotation[2]));
        transform *= glm::mat4_cast(rotation);
    }
    if (node.scale.size() == 3) {
        transform = glm::scale(transform, glm::vec3(glm::make_vec3(node.scale.data())));
    }
    return transform;
}

std::vector<MeshInstance> flattenNodes(const tinygltf::Model& model, GltfDiagnostics& diagnostics,
                                       Scene& scene) {
    auto [roots, field] = rootNodes(model, diagnostics);
    requireAcyclicNodeHierarchy(model, diagnostics);
    warnOfNodesPlacedTwice(model, roots, field, diagnostics);
    NodeFlattener flattener(model, diagnostics, scene, field);
    for (size_t r = 0; r < roots.size(); ++r) {
        flattener.visit(roots[r], glm::mat4(1.0f), {-1, r});
    }
    return flattener.takeInstances();
}

}  // namespace vkdr
