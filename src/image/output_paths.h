#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace vkdr {

// Every output a command was given is checked before any work starts, so that a bad
// path fails at once instead of after a render, and nothing but a regular file is ever
// replaced. Errors name the option and the path.

// A file output: an existing regular file (replaced once the new one is complete) or a
// new name in an existing directory that can be written to. Anything else is refused:
// a directory, a device node, a FIFO, a socket, and a symbolic link (writing would
// replace the link, not what it points to: give that path instead).
void requireOutputFile(const std::string& option, const std::filesystem::path& file);

// A directory output: an existing directory (or a link to one) that can be written to,
// or a new name whose nearest existing ancestor is such a directory.
void requireOutputDirectory(const std::string& option, const std::filesystem::path& directory);

struct NamedOutput {
    std::string option;
    std::filesystem::path path;
};

// Whether two paths name one file as the file system sees them ("a.exr" and "./a.exr", a
// path through a symbolic link to a directory, a hard link), existing or not.
bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b);

// Refuses two outputs that are one file (sameFile): the second write would replace the first.
void requireDistinctOutputs(const std::vector<NamedOutput>& outputs);

// Refuses an output that is one of the files a command reads (sameFile), which are
// described together as `inputs` ("a file the scene reads").
void requireOutputsAreNotInputs(const std::vector<NamedOutput>& outputs,
                                const std::vector<std::filesystem::path>& inputFiles, const std::string& inputs);

enum class ImageFileType { Exr, Png };

// The type an image file has by its extension: ".exr" or ".png", in any case; nullopt
// for any other.
std::optional<ImageFileType> imageFileTypeOf(const std::filesystem::path& file);

}  // namespace vkdr
