#include "gltf_test_files.h"

#include <cstring>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "core/error.h"
#include "scene/load_scene.h"

namespace vkdr::test {
namespace {

constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;

template <typename T>
void appendBytes(std::vector<unsigned char>& out, const T& value) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);
    out.insert(out.end(), bytes, bytes + sizeof(T));
}

void pad(std::vector<unsigned char>& bytes, unsigned char with) {
    while (bytes.size() % 4 != 0) {
        bytes.push_back(with);
    }
}

}  // namespace

MeshData box(glm::vec3 min, glm::vec3 max, bool inward) {
    MeshData mesh;
    for (int corner = 0; corner < 8; ++corner) {
        mesh.positions.emplace_back(corner & 1 ? max.x : min.x, corner & 2 ? max.y : min.y,
                                    corner & 4 ? max.z : min.z);
    }
    // Corner bits: x = 1, y = 2, z = 4. Each face counter-clockwise seen from outside.
    mesh.indices = {0, 2, 3, 0, 3, 1,   // -z
                    4, 5, 7, 4, 7, 6,   // +z
                    0, 4, 6, 0, 6, 2,   // -x
                    1, 3, 7, 1, 7, 5,   // +x
                    0, 1, 5, 0, 5, 4,   // -y
                    2, 6, 7, 2, 7, 3};  // +y
    if (inward) {
        for (size_t i = 0; i < mesh.indices.size(); i += 3) {
            std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
        }
    }
    return mesh;
}

MeshData floorQuad(float halfSize, float y) {
    float h = halfSize;
    return {{{-h, y, h}, {h, y, h}, {h, y, -h}, {-h, y, -h}},
            {0, 1, 2, 0, 2, 3},
            {{0, 1}, {1, 1}, {1, 0}, {0, 0}}};
}

GltfBuilder::GltfBuilder() {
    document_ = {{"asset", {{"version", "2.0"}}},
                 {"scenes", json::array({{{"nodes", json::array()}}})},
                 {"scene", 0},
                 {"nodes", json::array()},
                 {"meshes", json::array()},
                 {"accessors", json::array()},
                 {"bufferViews", json::array()}};
}

int GltfBuilder::addBufferView(const std::vector<unsigned char>& bytes) {
    size_t offset = buffer_.size();
    buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
    pad(buffer_, 0);
    document_["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes.size()}});
    return int(document_["bufferViews"].size() - 1);
}

int GltfBuilder::addAccessor(const void* data, size_t bytes, size_t count, int componentType,
                             const char* type, bool indices) {
    std::vector<unsigned char> copy(bytes);
    std::memcpy(copy.data(), data, bytes);
    int view = addBufferView(copy);
    document_["bufferViews"][size_t(view)]["target"] = indices ? 34963 : 34962;
    document_["accessors"].push_back(
        {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
    return int(document_["accessors"].size() - 1);
}

int GltfBuilder::addMesh(const std::string& name, const MeshData& mesh, int material) {
    json primitive;
    primitive["attributes"]["POSITION"] =
        addAccessor(mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3),
                    mesh.positions.size(), kFloat, "VEC3", false);
    if (!mesh.uvs.empty()) {
        primitive["attributes"]["TEXCOORD_0"] = addAccessor(
            mesh.uvs.data(), mesh.uvs.size() * sizeof(glm::vec2), mesh.uvs.size(), kFloat, "VEC2", false);
    }
    if (!mesh.indices.empty()) {
        primitive["indices"] = addAccessor(mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t),
                                           mesh.indices.size(), kUnsignedInt, "SCALAR", true);
    }
    if (material >= 0) {
        primitive["material"] = material;
    }
    document_["meshes"].push_back({{"name", name}, {"primitives", json::array({primitive})}});
    return int(document_["meshes"].size() - 1);
}

void GltfBuilder::addVec2Attribute(int mesh, const std::string& name, const std::vector<glm::vec2>& values) {
    document_["meshes"][size_t(mesh)]["primitives"][0]["attributes"][name] =
        addAccessor(values.data(), values.size() * sizeof(glm::vec2), values.size(), kFloat, "VEC2", false);
}

int GltfBuilder::addMaterial(json material) {
    document_["materials"].push_back(std::move(material));
    return int(document_["materials"].size() - 1);
}

int GltfBuilder::addNode(json node, bool root) {
    document_["nodes"].push_back(std::move(node));
    int index = int(document_["nodes"].size() - 1);
    if (root) {
        document_["scenes"][0]["nodes"].push_back(index);
    }
    return index;
}

int GltfBuilder::addCamera(json camera) {
    document_["cameras"].push_back(std::move(camera));
    return int(document_["cameras"].size() - 1);
}

std::string GltfBuilder::gltfText() const {
    json document = document_;
    if (!buffer_.empty()) {  // glTF has no empty buffers
        json buffers = json::array(
            {{{"byteLength", buffer_.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer_)}}});
        if (document_.contains("buffers")) {
            for (const json& later : document_["buffers"]) buffers.push_back(later);
        }
        document["buffers"] = buffers;
    }
    return document.dump(2);
}

std::filesystem::path GltfBuilder::writeGltf(const std::filesystem::path& file) const {
    return writeText(file, gltfText());
}

std::filesystem::path GltfBuilder::writeGlb(const std::filesystem::path& file) const {
    json document = document_;
    json buffers = json::array({{{"byteLength", buffer_.size()}}});
    if (document_.contains("buffers")) {
        for (const json& later : document_["buffers"]) buffers.push_back(later);
    }
    document["buffers"] = buffers;
    std::string text = document.dump();
    std::vector<unsigned char> jsonChunk(text.begin(), text.end());
    pad(jsonChunk, ' ');
    std::vector<unsigned char> binaryChunk = buffer_;
    pad(binaryChunk, 0);
    std::vector<unsigned char> glb;
    appendBytes(glb, uint32_t(0x46546C67));
    appendBytes(glb, uint32_t(2));
    appendBytes(glb, uint32_t(12 + 8 + jsonChunk.size() + 8 + binaryChunk.size()));
    appendBytes(glb, uint32_t(jsonChunk.size()));
    appendBytes(glb, uint32_t(0x4E4F534A));
    glb.insert(glb.end(), jsonChunk.begin(), jsonChunk.end());
    appendBytes(glb, uint32_t(binaryChunk.size()));
    appendBytes(glb, uint32_t(0x004E4942));
    glb.insert(glb.end(), binaryChunk.begin(), binaryChunk.end());
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(glb.data()),
                                                std::streamsize(glb.size()));
    return file;
}

TemporaryDirectory::TemporaryDirectory() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string("vkdr_scene_") + (info ? info->name() : "test") + "_" +
                       std::to_string(std::random_device{}());
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::create_directories(path_);
}

TemporaryDirectory::~TemporaryDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

std::filesystem::path writeText(const std::filesystem::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
    return file;
}

std::string base64(const std::vector<unsigned char>& bytes) {
    static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string text;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t group = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) group |= uint32_t(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) group |= bytes[i + 2];
        for (size_t c = 0; c < 4; ++c) {
            text += i + c <= bytes.size() ? alphabet[(group >> (18 - 6 * c)) & 63] : '=';
        }
    }
    return text;
}

std::vector<unsigned char> bmpImage(int width, int height, const std::vector<glm::u8vec3>& topFirstRgb) {
    size_t rowBytes = (size_t(width) * 3 + 3) & ~size_t(3);
    uint32_t pixelBytes = uint32_t(rowBytes * size_t(height));
    std::vector<unsigned char> bmp = {'B', 'M'};
    appendBytes(bmp, uint32_t(54 + pixelBytes));
    appendBytes(bmp, uint32_t(0));
    appendBytes(bmp, uint32_t(54));  // offset of the pixels
    appendBytes(bmp, uint32_t(40));  // BITMAPINFOHEADER
    appendBytes(bmp, int32_t(width));
    appendBytes(bmp, int32_t(height));  // positive: rows stored bottom first
    appendBytes(bmp, uint16_t(1));
    appendBytes(bmp, uint16_t(24));
    for (int i = 0; i < 6; ++i) {
        appendBytes(bmp, uint32_t(0));
    }
    for (int row = height - 1; row >= 0; --row) {
        size_t start = bmp.size();
        for (int x = 0; x < width; ++x) {
            glm::u8vec3 rgb = topFirstRgb[size_t(row * width + x)];
            bmp.insert(bmp.end(), {rgb.b, rgb.g, rgb.r});
        }
        bmp.resize(start + rowBytes, 0);
    }
    return bmp;
}

void expectLoadError(const std::filesystem::path& file, const std::vector<std::string>& parts) {
    try {
        loadScene(file);
        ADD_FAILURE() << "loading " << file << " did not fail";
    } catch (const Error& error) {
        std::string message = error.what();
        EXPECT_NE(message.find(file.string() + ": "), std::string::npos) << message;
        for (const std::string& part : parts) {
            EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
        }
    }
}

}  // namespace vkdr::test
