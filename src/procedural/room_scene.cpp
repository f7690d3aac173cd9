#include "procedural/room_scene.h"

#include <array>
#include <limits>
#include <vector>

#include <nlohmann/json.hpp>

#include "procedural/glb_stream_writer.h"
#include "procedural/sphere_grid.h"

namespace vkdr {
namespace {

using nlohmann::json;

constexpr float kHalfWidth = 5.0f;  // the room spans [-5, 5] in x and z
constexpr float kHeight = 5.0f;
constexpr float kLightHalfWidth = 1.0f;

// A quad as two triangles; corners listed counter-clockwise seen from the lit side.
void addQuad(std::vector<Vertex>& vertices, std::vector<uint32_t>& indices,
             std::array<glm::vec3, 4> corners) {
    uint32_t first = uint32_t(vertices.size());
    const glm::vec2 uvs[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    for (int c = 0; c < 4; ++c) {
        vertices.push_back({corners[size_t(c)], uvs[c]});
    }
    indices.insert(indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
}

struct RoomGeometry {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  // the walls' triangles, then the light's
    size_t wallIndexCount = 0;
};

RoomGeometry roomGeometry() {
    const float w = kHalfWidth, h = kHeight, l = kLightHalfWidth;
    RoomGeometry room;
    auto quad = [&](std::array<glm::vec3, 4> corners) { addQuad(room.vertices, room.indices, corners); };
    quad({{{-w, 0, w}, {w, 0, w}, {w, 0, -w}, {-w, 0, -w}}});   // floor, facing +y
    quad({{{-w, h, -w}, {w, h, -w}, {w, h, w}, {-w, h, w}}});   // ceiling, facing -y
    quad({{{-w, 0, -w}, {w, 0, -w}, {w, h, -w}, {-w, h, -w}}}); // back wall, facing +z
    quad({{{w, 0, w}, {-w, 0, w}, {-w, h, w}, {w, h, w}}});     // front wall, facing -z
    quad({{{-w, 0, w}, {-w, 0, -w}, {-w, h, -w}, {-w, h, w}}}); // left wall, facing +x
    quad({{{w, 0, -w}, {w, 0, w}, {w, h, w}, {w, h, -w}}});     // right wall, facing -x
    room.wallIndexCount = room.indices.size();
    const float y = h - 0.01f;  // just below the ceiling
    quad({{{-l, y, -l}, {l, y, -l}, {l, y, l}, {-l, y, l}}});   // light, facing -y
    return room;
}

struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{std::numeric_limits<float>::lowest()};
    void add(const std::vector<Vertex>& vertices) {
        for (const Vertex& v : vertices) {
            min = glm::min(min, v.position);
            max = glm::max(max, v.position);
        }
    }
};

json vec3Json(glm::vec3 v) { return json::array({v.x, v.y, v.z}); }

constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;

json vertexView(uint64_t offset, uint64_t bytes) {
    return {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes},
            {"byteStride", sizeof(Vertex)}, {"target", 34962}};
}

json indexView(uint64_t offset, uint64_t bytes) {
    return {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", 34963}};
}

json accessor(int view, uint64_t offset, int componentType, uint64_t count, const char* type) {
    return {{"bufferView", view}, {"byteOffset", offset}, {"componentType", componentType},
            {"count", count}, {"type", type}};
}

json positionAccessor(int view, uint64_t count, const Bounds& bounds) {
    json positions = accessor(view, 0, kFloat, count, "VEC3");
    positions["min"] = vec3Json(bounds.min);
    positions["max"] = vec3Json(bounds.max);
    return positions;
}

json lambertian(const char* name, std::array<double, 3> albedo) {
    return {{"name", name},
            {"pbrMetallicRoughness",
             {{"baseColorFactor", {albedo[0], albedo[1], albedo[2], 1.0}}, {"metallicFactor", 0.0}}}};
}

// Positions at accessor `positions`, uvs in the next one.
json primitive(int positions, int indices, int material) {
    return {{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", positions + 1}}},
            {"indices", indices}, {"material", material}};
}

// The glTF document. Buffer layout: room vertices, room indices, sphere vertices,
// sphere indices; vertices interleave POSITION and TEXCOORD_0.
json document(const RoomSceneOptions& options, const RoomGeometry& room, const SphereGrid& spheres,
              const Bounds& roomBounds, const Bounds& sphereBounds) {
    uint64_t roomVertexBytes = room.vertices.size() * sizeof(Vertex);
    uint64_t roomIndexBytes = room.indices.size() * sizeof(uint32_t);
    uint64_t sphereVertexBytes = spheres.vertexCount() * sizeof(Vertex);
    uint64_t sphereIndexBytes = spheres.triangleCount() * 3 * sizeof(uint32_t);
    uint64_t sphereOffset = roomVertexBytes + roomIndexBytes;

    json doc;
    doc["asset"] = {{"version", "2.0"}, {"generator", "vkdr-make-scene"}};
    doc["extensionsUsed"] = json::array({"KHR_materials_emissive_strength"});
    doc["buffers"] = json::array({{{"byteLength", sphereOffset + sphereVertexBytes + sphereIndexBytes}}});
    doc["bufferViews"] = json::array({
        vertexView(0, roomVertexBytes),
        indexView(roomVertexBytes, roomIndexBytes),
        vertexView(sphereOffset, sphereVertexBytes),
        indexView(sphereOffset + sphereVertexBytes, sphereIndexBytes),
    });
    uint64_t lightIndexCount = room.indices.size() - room.wallIndexCount;
    doc["accessors"] = json::array({
        positionAccessor(0, room.vertices.size(), roomBounds),
        accessor(0, 12, kFloat, room.vertices.size(), "VEC2"),
        accessor(1, 0, kUnsignedInt, room.wallIndexCount, "SCALAR"),
        accessor(1, room.wallIndexCount * sizeof(uint32_t), kUnsignedInt, lightIndexCount, "SCALAR"),
        positionAccessor(2, spheres.vertexCount(), sphereBounds),
        accessor(2, 12, kFloat, spheres.vertexCount(), "VEC2"),
        accessor(3, 0, kUnsignedInt, spheres.triangleCount() * 3, "SCALAR"),
    });
    doc["materials"] = json::array({
        lambertian("walls", {0.725, 0.71, 0.68}),
        lambertian("light", {0.78, 0.78, 0.78}),
        lambertian("spheres", {0.45, 0.55, 0.7}),
    });
    doc["materials"][1]["emissiveFactor"] = {1.0, 0.85, 0.6};
    doc["materials"][1]["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", 20.0}};
    doc["meshes"] = json::array({
        {{"name", "room"}, {"primitives", json::array({primitive(0, 2, 0), primitive(0, 3, 1)})}},
        {{"name", "spheres"}, {"primitives", json::array({primitive(4, 6, 2)})}},
    });
    doc["cameras"] = json::array({{{"name", "camera"},
                                   {"type", "perspective"},
                                   {"perspective", {{"yfov", 1.0}, {"aspectRatio", 1.5}, {"znear", 0.01}}}}});
    // Near the front wall, pitched 12 degrees down (a rotation about x).
    const double k = options.scale;
    doc["nodes"] = json::array({
        {{"name", "room"}, {"mesh", 0}},
        {{"name", "spheres"}, {"mesh", 1}},
        {{"name", "camera"}, {"camera", 0}, {"translation", {0.0, 3.0 * k, 4.8 * k}},
         {"rotation", {-0.10452846, 0.0, 0.0, 0.99452190}}},
    });
    if (options.scale != 1.0f) {
        doc["nodes"][0]["scale"] = {k, k, k};
        doc["nodes"][1]["scale"] = {k, k, k};
    }
    doc["scenes"] = json::array({{{"nodes", {0, 1, 2}}}});
    doc["scene"] = 0;
    if (options.fog) {
        doc["extensionsUsed"].push_back("VKDR_participating_media");
        const float a = options.fog->sigma_a, s = options.fog->sigma_s;
        doc["extensions"]["VKDR_participating_media"] = {
            {"name", "fog"}, {"sigma_a", {a, a, a}}, {"sigma_s", {s, s, s}}, {"g", 0.0}};
    }
    return doc;
}

}  // namespace

uint64_t writeRoomScene(const RoomSceneOptions& options) {
    RoomGeometry room = roomGeometry();
    uint64_t roomTriangles = room.indices.size() / 3;
    // Spheres at most 0.3 of the room's height in radius stay well below the light.
    SphereGrid spheres(options.triangles > roomTriangles ? options.triangles - roomTriangles : 0, 4.0f,
                       0.3f * kHeight);

    // Reserve the JSON chunk for the document with the widest possible bounds.
    Bounds roomBounds, sphereBounds;
    roomBounds.add(room.vertices);
    Bounds widest{glm::vec3(std::numeric_limits<float>::lowest()),  // the longest number text
                  glm::vec3(std::numeric_limits<float>::lowest())};
    size_t jsonCapacity = document(options, room, spheres, widest, widest).dump().size();

    uint64_t binaryBytes = room.vertices.size() * sizeof(Vertex) + room.indices.size() * sizeof(uint32_t) +
                           spheres.vertexCount() * sizeof(Vertex) +
                           spheres.triangleCount() * 3 * sizeof(uint32_t);
    GlbStreamWriter writer(options.output, jsonCapacity, binaryBytes);
    writer.writeBinary(room.vertices.data(), room.vertices.size() * sizeof(Vertex));
    writer.writeBinary(room.indices.data(), room.indices.size() * sizeof(uint32_t));
    std::vector<Vertex> vertices;
    for (uint64_t s = 0; s < spheres.sphereCount(); ++s) {
        spheres.sphereVertices(s, vertices);
        sphereBounds.add(vertices);
        writer.writeBinary(vertices.data(), vertices.size() * sizeof(Vertex));
    }
    std::vector<uint32_t> indices;
    for (uint64_t s = 0; s < spheres.sphereCount(); ++s) {
        spheres.sphereIndices(s, indices);
        writer.writeBinary(indices.data(), indices.size() * sizeof(uint32_t));
    }
    writer.finish(document(options, room, spheres, roomBounds, sphereBounds).dump());
    return roomTriangles + spheres.triangleCount();
}

}  // namespace vkdr
