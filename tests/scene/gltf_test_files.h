#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace vkdr::test {

using nlohmann::json;

// Triangle geometry for building test meshes.
struct MeshData {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;  // empty: a non-indexed primitive
    std::vector<glm::vec2> uvs;     // empty: no TEXCOORD_0
};

// An axis-aligned box, 12 triangles wound outwards (or inwards when `inward`).
MeshData box(glm::vec3 min, glm::vec3 max, bool inward = false);
// A unit quad in the xz plane at height y, facing +y, with uvs.
MeshData floorQuad(float halfSize, float y = 0.0f);

// Assembles a small glTF document whose binary data lives in one buffer, embedded as
// a base64 data URI (writeGltf) or as the GLB binary chunk (writeGlb).
class GltfBuilder {
public:
    GltfBuilder();

    // A mesh with one primitive; returns its index. `material` < 0 leaves it unset.
    int addMesh(const std::string& name, const MeshData& mesh, int material = -1);
    int addMaterial(json material);
    // Adds a node and lists it in the scene when `root`; returns its index.
    int addNode(json node, bool root = true);
    int addCamera(json camera);
    // A float VEC2 attribute `name` (e.g. "TEXCOORD_1") of mesh `mesh`'s primitive.
    void addVec2Attribute(int mesh, const std::string& name, const std::vector<glm::vec2>& values);
    // Raw bytes appended to the buffer, with a buffer view; returns the view index.
    int addBufferView(const std::vector<unsigned char>& bytes);

    json& document() { return document_; }
    std::string gltfText() const;  // with the buffer as a data URI
    std::filesystem::path writeGltf(const std::filesystem::path& file) const;
    // The builder's buffer is buffers[0] (the data URI, or the BIN chunk); buffers that
    // document() lists come after it.
    std::filesystem::path writeGlb(const std::filesystem::path& file) const;

private:
    int addAccessor(const void* data, size_t bytes, size_t count, int componentType,
                    const char* type, bool indices);

    json document_;
    std::vector<unsigned char> buffer_;
};

// A fresh, empty directory for one test's files, removed when the test ends.
class TemporaryDirectory {
public:
    TemporaryDirectory();
    ~TemporaryDirectory();
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    std::filesystem::path path_;
};

std::filesystem::path writeText(const std::filesystem::path& file, const std::string& text);
// Loads `file` expecting a vkdr::Error that names the file and contains every one of `parts`.
void expectLoadError(const std::filesystem::path& file, const std::vector<std::string>& parts);
std::string base64(const std::vector<unsigned char>& bytes);
// A 24-bit BMP image (rows given top first), which stb_image, and so tinygltf, decodes.
std::vector<unsigned char> bmpImage(int width, int height, const std::vector<glm::u8vec3>& topFirstRgb);

}  // namespace vkdr::test
