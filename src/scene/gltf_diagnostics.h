#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace vkdr {

// Errors and warnings about one glTF file. Every message starts with the file name and
// the JSON path of the field at fault, e.g. "scene.gltf: materials[2].doubleSided: ...".
class GltfDiagnostics {
public:
    explicit GltfDiagnostics(std::string fileName) : fileName_(std::move(fileName)) {}

    [[noreturn]] void fail(std::string_view field, std::string_view message) const;
    // Repeated warnings are kept once, so a file with a thousand textured primitives
    // does not bury the one warning that matters.
    void warn(std::string_view field, std::string_view message);

    const std::string& fileName() const { return fileName_; }
    std::vector<std::string> takeWarnings() { return std::move(warnings_); }

private:
    std::string message(std::string_view field, std::string_view text) const;

    std::string fileName_;
    std::vector<std::string> warnings_;
};

// "materials[2]" from ("materials", 2).
std::string indexed(std::string_view array, size_t index);
// "materials[2].name" from ("materials[2]", "name").
std::string member(std::string_view object, std::string_view key);
// Shortest text that reads back as the same double ("0.1", "1e+999" becomes "inf").
std::string formatNumber(double value);

}  // namespace vkdr
