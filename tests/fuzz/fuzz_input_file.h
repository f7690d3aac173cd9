#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <stdlib.h>

namespace vkdr::fuzz {

// The loaders read files, so each input is written to a file first: in a directory of
// this process's own, named `name` (whose extension picks the format), replacing the
// previous input. The directory holds nothing else, so relative URIs find nothing.
inline std::filesystem::path writeInputFile(const uint8_t* data, size_t size, const std::string& name) {
    static const std::filesystem::path directory = [] {
        std::string pattern = (std::filesystem::temp_directory_path() / "vkdr-fuzz-XXXXXX").string();
        if (!mkdtemp(pattern.data())) abort();
        return std::filesystem::path(pattern);
    }();
    for (const auto& entry : std::filesystem::directory_iterator(directory)) std::filesystem::remove(entry.path());
    std::filesystem::path file = directory / name;
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
    return file;
}

inline bool startsWith(const uint8_t* data, size_t size, const std::string& magic) {
    return size >= magic.size() && std::string(reinterpret_cast<const char*>(data), magic.size()) == magic;
}

}  // namespace vkdr::fuzz
