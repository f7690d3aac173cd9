#include "cli/install_layout.h"

#include <filesystem>
#include <system_error>

namespace vkdr {
namespace {

namespace fs = std::filesystem;

// PREFIX/relative for the prefix the running binary is installed in, if it exists there.
fs::path besideInstalledBinary(const fs::path& relative) {
    std::error_code error;
    fs::path binary = fs::read_symlink("/proc/self/exe", error);
    if (error) return {};
    fs::path candidate = binary.parent_path().parent_path() / relative;
    return fs::exists(candidate, error) ? candidate : fs::path();
}

}  // namespace

std::string docReference(const std::string& title, const std::string& file) {
    fs::path guide = besideInstalledBinary(fs::path(VKDR_INSTALL_DOCDIR) / file);
    // A binary in the build tree: the source tree's guide, while that tree is there.
    std::error_code error;
    if (guide.empty() && fs::exists(fs::path(VKDR_SOURCE_DOCS_DIR) / file, error)) {
        guide = fs::path(VKDR_SOURCE_DOCS_DIR) / file;
    }
    return "the " + title + ", " + (guide.empty() ? fs::path(VKDR_FULL_DOCDIR) / file : guide).string();
}

std::string shippedScenesDirectory() {
    fs::path installed = besideInstalledBinary(fs::path(VKDR_INSTALL_DATADIR) / "vkdiffrender" / "scenes");
    return installed.empty() ? std::string(VKDR_SOURCE_SCENES_DIR) : installed.string();
}

}  // namespace vkdr
