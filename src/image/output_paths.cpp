#include "image/output_paths.h"

#include <fcntl.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstring>

#include "core/error.h"

namespace vkdr {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void fail(const std::string& option, const fs::path& path, const std::string& problem) {
    throw Error(option + " " + path.string() + ": " + problem);
}

// What is at `path`, following a final symbolic link or not; not_found when nothing is.
fs::file_status statusOf(const std::string& option, const fs::path& path, bool followLink) {
    std::error_code error;
    fs::file_status status = followLink ? fs::status(path, error) : fs::symlink_status(path, error);
    if (error && status.type() != fs::file_type::not_found) fail(option, path, error.message());
    return status;
}

// The directory's attributes that chattr sets (STATX_ATTR_*), as far as the file system
// reports them; statx needs no permission on the directory itself.
uint64_t fileAttributes(const fs::path& directory) {
    struct statx attributes {};
    if (statx(AT_FDCWD, directory.c_str(), 0, STATX_BASIC_STATS, &attributes) != 0) return 0;
    return attributes.stx_attributes & attributes.stx_attributes_mask;
}

// What an output needs of a directory: to write its files there (made under a temporary
// name and renamed over their path), or only to make a new directory in it.
enum class DirectoryUse { HoldsOutputs, TakesNewDirectory };

void requireWritableDirectory(const std::string& option, const fs::path& path, const fs::path& directory,
                              DirectoryUse use) {
    fs::file_status parent = statusOf(option, directory, true);
    if (!fs::exists(parent)) fail(option, path, "directory " + directory.string() + " does not exist");
    if (!fs::is_directory(parent)) fail(option, path, directory.string() + " is not a directory");
    const uint64_t attributes = fileAttributes(directory);
    if ((attributes & STATX_ATTR_IMMUTABLE) != 0) {
        fail(option, path, "directory " + directory.string() + " is immutable (chattr +i): it takes no new files");
    }
    if (access(directory.c_str(), W_OK | X_OK) != 0) {
        fail(option, path, "cannot write in directory " + directory.string() + ": " + std::strerror(errno));
    }
    if ((attributes & STATX_ATTR_APPEND) != 0) {
        // Append-only (chattr +a): new names, and so a new directory, but no rename and no
        // removal of a name, which writing an output (made under a temporary name) needs.
        if (use == DirectoryUse::TakesNewDirectory) return;
        fail(option, path,
             "directory " + directory.string() +
                 " is append-only (chattr +a): it does not let a file be renamed or removed, which writing an "
                 "output (made under a temporary name) needs");
    }
    // Permission bits do not tell everything (root passes them; /proc and /sys take no
    // new files): a file made and removed at once does.
    std::string probe = (directory / ".vkdiffrender-write-check-XXXXXX").string();
    int descriptor = mkstemp(probe.data());
    if (descriptor < 0) {
        fail(option, path, "cannot create a file in directory " + directory.string() + ": " + std::strerror(errno));
    }
    close(descriptor);
    // A directory that keeps every name without saying so by its flags keeps the probe
    // too; refused, as the temporary file an output is written to could not be renamed
    // over it either.
    if (unlink(probe.c_str()) != 0) {
        fail(option, path, "directory " + directory.string() + " takes new files but does not let them be removed (" +
                               std::strerror(errno) + "); the test file " + probe + " is left there");
    }
}

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return text;
}

// The path as the file system resolves it: absolute, without "." and "..", through
// every symbolic link of the part that exists.
fs::path resolved(const fs::path& path) {
    std::error_code error;
    fs::path absolute = fs::absolute(path, error);
    if (error) return path.lexically_normal();
    fs::path canonical = fs::weakly_canonical(absolute, error);
    return error ? absolute.lexically_normal() : canonical;
}

}  // namespace

void requireOutputFile(const std::string& option, const fs::path& file) {
    if (file.empty()) throw Error(option + ": give a file name");
    fs::file_status status = statusOf(option, file, false);
    if (fs::is_symlink(status)) {
        fail(option, file,
             "is a symbolic link; writing would replace the link itself, so give the path it points to");
    }
    if (fs::is_directory(status)) fail(option, file, "is a directory; give a file name");
    if (fs::exists(status) && !fs::is_regular_file(status)) {
        fail(option, file, "exists and is not a regular file (a device, FIFO or socket); it is not replaced");
    }
    fs::path name = file.filename();
    if (name.empty() || name == "." || name == "..") fail(option, file, "not a file name");
    fs::path parent = file.parent_path();
    requireWritableDirectory(option, file, parent.empty() ? fs::path(".") : parent, DirectoryUse::HoldsOutputs);
}

void requireOutputDirectory(const std::string& option, const fs::path& directory) {
    if (directory.empty()) throw Error(option + ": give a directory");
    fs::file_status status = statusOf(option, directory, true);
    if (fs::exists(status)) {
        if (!fs::is_directory(status)) fail(option, directory, "exists and is not a directory");
        requireWritableDirectory(option, directory, directory, DirectoryUse::HoldsOutputs);
        return;
    }
    // The missing parts of the path are made as directories: none may be a link to
    // nothing, which making them would fail on only after the work.
    std::error_code error;
    fs::path part = fs::absolute(directory, error).lexically_normal();
    if (error) part = directory.lexically_normal();
    for (; part.has_relative_path(); part = part.parent_path()) {
        if (part.filename().empty()) continue;  // a trailing separator: the same directory
        if (fs::exists(statusOf(option, part, true))) break;
        if (fs::is_symlink(statusOf(option, part, false))) {
            fail(option, directory, part.string() + " is a symbolic link to nothing; create the directory it "
                                    "points to, or give another");
        }
    }
    // Created with its missing parents: the nearest ancestor that exists must take them.
    fs::path ancestor = resolved(directory).parent_path();
    while (!fs::exists(statusOf(option, ancestor, true)) && ancestor.has_relative_path()) {
        ancestor = ancestor.parent_path();
    }
    requireWritableDirectory(option, directory, ancestor, DirectoryUse::TakesNewDirectory);
}

bool sameFile(const fs::path& a, const fs::path& b) {
    if (resolved(a) == resolved(b)) return true;
    std::error_code error;
    return fs::equivalent(a, b, error) && !error;
}

void requireDistinctOutputs(const std::vector<NamedOutput>& outputs) {
    for (size_t i = 0; i < outputs.size(); ++i) {
        for (size_t j = i + 1; j < outputs.size(); ++j) {
            if (sameFile(outputs[i].path, outputs[j].path)) {
                throw Error(outputs[i].option + " " + outputs[i].path.string() + " and " + outputs[j].option + " " +
                            outputs[j].path.string() + " are the same file; give each its own");
            }
        }
    }
}

void requireOutputsAreNotInputs(const std::vector<NamedOutput>& outputs,
                                const std::vector<fs::path>& inputFiles, const std::string& inputs) {
    for (const NamedOutput& output : outputs) {
        for (const fs::path& input : inputFiles) {
            if (sameFile(output.path, input)) fail(output.option, output.path, "is " + inputs + "; give another");
        }
    }
}

std::optional<ImageFileType> imageFileTypeOf(const fs::path& file) {
    std::string extension = lowercase(file.extension().string());
    if (extension == ".exr") return ImageFileType::Exr;
    if (extension == ".png") return ImageFileType::Png;
    return std::nullopt;
}

}  // namespace vkdr
