#pragma once
#include <filesystem>
#include <string>

namespace vkdr {

// Which files a scene may read besides itself (docs/scene-format.md, "Files a scene
// reads"): by default only files in the scene file's own directory and below.
struct SceneFileAccess {
    bool allowOutsideFiles = false;  // --allow-outside-files: absolute paths and ../ anywhere
};

// A file a URI names, or why it may not be read.
struct ResolvedFile {
    std::filesystem::path file;  // symbolic links resolved
    std::string problem;         // "" when `file` may be read; else what is wrong with it
};

// Resolves the URIs of one scene's buffers and images to files, by its SceneFileAccess.
class SceneFiles {
public:
    SceneFiles(const std::filesystem::path& sceneFile, SceneFileAccess access);

    // A URI as the file spells it (not a data: URI): percent-encoded, without a scheme.
    // The problem quotes the URI ("'../a.bin' is outside the scene's directory; ...").
    ResolvedFile resolveUri(const std::string& uri) const;
    // A path already decoded from its URI, relative to directory() unless absolute. The
    // problem is a predicate ("is a directory, not a file") for the caller to complete.
    ResolvedFile resolvePath(const std::string& path) const;

    // The scene file's directory, symbolic links resolved.
    const std::filesystem::path& directory() const { return directory_; }

private:
    std::filesystem::path directory_;
    SceneFileAccess access_;
};

bool isDataUri(const std::string& uri);
// The URI's scheme with its colon ("file:", "data:"), or "" for a relative reference.
std::string uriScheme(const std::string& uri);

// `uri` in quotes for a message; one of more than 200 characters (a data URI the reader
// does not take as one, "DATA:", may be megabytes) by its start and its length.
std::string quotedUri(const std::string& uri);

// The path a relative URI names, decoded as tinygltf decodes it ("%2F" is '/', '+' a
// space); empty `problem` when the encoding is sound.
std::string decodeUriPath(const std::string& uri, std::string& problem);
// A relative path written as a URI that decodeUriPath reads back unchanged.
std::string encodeUriPath(const std::string& path);

}  // namespace vkdr
