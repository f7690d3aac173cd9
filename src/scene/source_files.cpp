#include "scene/source_files.h"

#include <functional>
#include <system_error>

#include "core/error.h"

namespace vkdr {

size_t contentDigest(std::string_view bytes) { return std::hash<std::string_view>{}(bytes); }

void requireUnchangedSource(const std::vector<SourceFile>& sources, const std::filesystem::path& file,
                            std::string_view bytes) {
    std::error_code error;
    const std::filesystem::path resolved = std::filesystem::weakly_canonical(file, error);
    for (const SourceFile& source : sources) {
        if (source.file == resolved && source.digest != contentDigest(bytes)) {
            throw Error(file.string() +
                        ": has changed since the scene was loaded from it, so the scene cannot be written with "
                        "its values (restore the file, or load the scene again)");
        }
    }
}

}  // namespace vkdr
