#include "scene/gltf_accessors.h"

#include <cmath>
#include <cstring>
#include <initializer_list>
#include <optional>

namespace vkdr {
namespace {

// Where an accessor's elements lie, once every index and size has been checked.
struct ElementRange {
    const unsigned char* first = nullptr;
    size_t stride = 0;  // bytes from one element to the next
    size_t count = 0;
    int componentType = 0;
    bool normalized = false;  // integer components stand for [0, 1]
};

// Where the last of `count` elements ends: byteOffset + stride * (count - 1) + elementSize
// (byteOffset for none), or nothing when a corrupt file's huge count or offset makes
// that overflow.
std::optional<size_t> bytesNeeded(size_t byteOffset, size_t stride, size_t count, size_t elementSize) {
    if (count == 0) return byteOffset;
    size_t span = 0, end = 0;
    if (__builtin_mul_overflow(stride, count - 1, &span) || __builtin_add_overflow(span, elementSize, &end) ||
        __builtin_add_overflow(end, byteOffset, &end)) {
        return std::nullopt;
    }
    return end;
}

ElementRange checkedElements(const tinygltf::Model& model, int accessorIndex, int type,
                             std::initializer_list<int> componentTypes,
                             const GltfDiagnostics& diagnostics, std::string_view field) {
    if (accessorIndex < 0 || size_t(accessorIndex) >= model.accessors.size()) {
        diagnostics.fail(field, "accessor " + std::to_string(accessorIndex) +
                                    " out of range (" + std::to_string(model.accessors.size()) +
                                    " accessors)");
    }
    const tinygltf::Accessor& accessor = model.accessors[size_t(accessorIndex)];
    std::string accessorField = indexed("accessors", size_t(accessorIndex));
    if (accessor.sparse.isSparse) {
        diagnostics.fail(accessorField, "sparse accessors are not supported");
    }
    bool allowedComponent = false;
    for (int componentType : componentTypes) {
        allowedComponent = allowedComponent || accessor.componentType == componentType;
    }
    if (accessor.type != type || !allowedComponent) {
        diagnostics.fail(accessorField, "element type (type " + std::to_string(accessor.type) +
                                            ", componentType " +
                                            std::to_string(accessor.componentType) +
                                            ") is not allowed for " + std::string(field));
    }
    if (accessor.bufferView < 0) {
        diagnostics.fail(accessorField, "has no bufferView (an accessor of zeros, for sparse accessors); the "
                                        "loader reads an accessor's values from a buffer view only");
    }
    if (size_t(accessor.bufferView) >= model.bufferViews.size()) {
        diagnostics.fail(accessorField + ".bufferView",
                         "buffer view " + std::to_string(accessor.bufferView) +
                             " out of range (" + std::to_string(model.bufferViews.size()) +
                             " buffer views)");
    }
    const tinygltf::BufferView& view = model.bufferViews[size_t(accessor.bufferView)];
    std::string viewField = indexed("bufferViews", size_t(accessor.bufferView));
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) {
        diagnostics.fail(viewField + ".buffer", "buffer " + std::to_string(view.buffer) +
                                                    " out of range (" +
                                                    std::to_string(model.buffers.size()) +
                                                    " buffers)");
    }
    const tinygltf::Buffer& buffer = model.buffers[size_t(view.buffer)];
    // Compared without adding, so that offsets near SIZE_MAX cannot wrap around.
    if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset) {
        diagnostics.fail(viewField, "byteOffset + byteLength = " +
                                        std::to_string(view.byteOffset + view.byteLength) +
                                        " exceeds the " + std::to_string(buffer.data.size()) +
                                        " bytes of " + indexed("buffers", size_t(view.buffer)));
    }

    const size_t componentSize = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType)));
    // glTF requires it: an offset between components reads bytes of two of them.
    if (accessor.byteOffset % componentSize != 0 || view.byteOffset % componentSize != 0) {
        const bool ownOffset = accessor.byteOffset % componentSize != 0;
        diagnostics.fail(ownOffset ? accessorField + ".byteOffset" : viewField + ".byteOffset",
                         std::to_string(ownOffset ? accessor.byteOffset : view.byteOffset) +
                             " is not a multiple of the " + std::to_string(componentSize) +
                             "-byte components of " + accessorField);
    }
    size_t elementSize = componentSize * size_t(tinygltf::GetNumComponentsInType(uint32_t(accessor.type)));
    size_t stride = view.byteStride == 0 ? elementSize : view.byteStride;
    if (stride < elementSize) {
        diagnostics.fail(viewField + ".byteStride",
                         "stride " + std::to_string(stride) + " is smaller than the " +
                             std::to_string(elementSize) + "-byte elements of " + accessorField);
    }
    std::optional<size_t> needed = bytesNeeded(accessor.byteOffset, stride, accessor.count, elementSize);
    if (!needed || *needed > view.byteLength) {
        diagnostics.fail(accessorField, std::to_string(accessor.count) + " elements need " +
                                            (needed ? std::to_string(*needed) : "more than 2^64") + " bytes but " +
                                            viewField + " holds " + std::to_string(view.byteLength));
    }
    return {buffer.data.data() + view.byteOffset + accessor.byteOffset, stride, accessor.count,
            accessor.componentType, accessor.normalized};
}

// glTF 2.0 allows integer texture coordinates and colours as normalized values only;
// plain integers are KHR_mesh_quantization's, which is not supported.
void requireNormalizedIntegers(const ElementRange& range, int accessorIndex, const GltfDiagnostics& diagnostics,
                               std::string_view field) {
    if (range.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !range.normalized) {
        diagnostics.fail(indexed("accessors", size_t(accessorIndex)) + ".normalized",
                         "integer components of " + std::string(field) +
                             " must be normalized (\"normalized\": true); plain integers need "
                             "KHR_mesh_quantization, which is not supported");
    }
}

template <typename T>
T load(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T));  // buffers need not be aligned for T
    return value;
}

float normalizedComponent(const unsigned char* bytes, int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return float(load<uint8_t>(bytes)) / 255.0f;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return float(load<uint16_t>(bytes)) / 65535.0f;
    default: return load<float>(bytes);
    }
}

}  // namespace

std::vector<glm::vec3> readVec3s(const tinygltf::Model& model, int accessor,
                                     const GltfDiagnostics& diagnostics, std::string_view field) {
    ElementRange range = checkedElements(model, accessor, TINYGLTF_TYPE_VEC3,
                                         {TINYGLTF_COMPONENT_TYPE_FLOAT}, diagnostics, field);
    std::vector<glm::vec3> positions(range.count);
    for (size_t i = 0; i < range.count; ++i) {
        positions[i] = load<glm::vec3>(range.first + i * range.stride);
    }
    return positions;
}

std::vector<glm::vec2> readTexcoords(const tinygltf::Model& model, int accessor,
                                     const GltfDiagnostics& diagnostics, std::string_view field) {
    ElementRange range = checkedElements(
        model, accessor, TINYGLTF_TYPE_VEC2,
        {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
         TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
        diagnostics, field);
    requireNormalizedIntegers(range, accessor, diagnostics, field);
    size_t componentSize = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(range.componentType)));
    std::vector<glm::vec2> uvs(range.count);
    for (size_t i = 0; i < range.count; ++i) {
        const unsigned char* element = range.first + i * range.stride;
        uvs[i] = {normalizedComponent(element, range.componentType),
                  normalizedComponent(element + componentSize, range.componentType)};
        if (!std::isfinite(uvs[i].x) || !std::isfinite(uvs[i].y)) {
            diagnostics.fail(field, "texture coordinate " + std::to_string(i) + " is not finite");
        }
    }
    return uvs;
}

std::vector<glm::vec3> readColors(const tinygltf::Model& model, int accessor, const GltfDiagnostics& diagnostics,
                                  std::string_view field) {
    const bool rgba = accessor >= 0 && size_t(accessor) < model.accessors.size() &&
                      model.accessors[size_t(accessor)].type == TINYGLTF_TYPE_VEC4;
    ElementRange range = checkedElements(
        model, accessor, rgba ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
        {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
        diagnostics, field);
    requireNormalizedIntegers(range, accessor, diagnostics, field);
    size_t componentSize = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(range.componentType)));
    std::vector<glm::vec3> colors(range.count);
    for (size_t i = 0; i < range.count; ++i) {
        const unsigned char* element = range.first + i * range.stride;
        for (int c = 0; c < 3; ++c) {
            colors[i][c] = normalizedComponent(element + size_t(c) * componentSize, range.componentType);
            if (!(colors[i][c] >= 0.0f && colors[i][c] <= 1.0f)) {
                diagnostics.fail(field, "colour " + std::to_string(i) + " has " + "RGB"[c] + " = " +
                                            formatNumber(colors[i][c]) + "; must be in [0, 1]");
            }
        }
    }
    return colors;
}

std::vector<uint32_t> readIndices(const tinygltf::Model& model, int accessor,
                                  const GltfDiagnostics& diagnostics, std::string_view field) {
    ElementRange range = checkedElements(
        model, accessor, TINYGLTF_TYPE_SCALAR,
        {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
         TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
        diagnostics, field);
    std::vector<uint32_t> indices(range.count);
    for (size_t i = 0; i < range.count; ++i) {
        const unsigned char* element = range.first + i * range.stride;
        switch (range.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: indices[i] = load<uint8_t>(element); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: indices[i] = load<uint16_t>(element); break;
        default: indices[i] = load<uint32_t>(element); break;
        }
    }
    return indices;
}

}  // namespace vkdr
