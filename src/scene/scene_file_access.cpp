#include "scene/scene_file_access.h"

#include <cctype>

#include "core/setting_names.h"
#include "image/regular_file.h"

namespace vkdr {
namespace {

std::string optOut() {
    return "; a scene reads only files in its own directory and below unless " +
           settingName(Setting::AllowOutsideFiles) + " is given";
}

bool isInside(const std::filesystem::path& file, const std::filesystem::path& directory) {
    std::filesystem::path relative = file.lexically_relative(directory);
    return !relative.empty() && *relative.begin() != "..";
}

int hexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

}  // namespace

// RFC 3986: a scheme is a letter, then letters, digits, '+', '-' or '.', then ':'.
std::string uriScheme(const std::string& uri) {
    if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return "";
    for (size_t i = 1; i < uri.size(); ++i) {
        unsigned char c = static_cast<unsigned char>(uri[i]);
        if (c == ':') return uri.substr(0, i + 1);
        if (!std::isalnum(c) && c != '+' && c != '-' && c != '.') return "";
    }
    return "";
}

std::string quotedUri(const std::string& uri) {
    constexpr size_t kShown = 200;
    if (uri.size() <= kShown) return "'" + uri + "'";
    return "'" + uri.substr(0, kShown) + "...' (" + std::to_string(uri.size()) + " characters)";
}

SceneFiles::SceneFiles(const std::filesystem::path& sceneFile, SceneFileAccess access) : access_(access) {
    std::error_code ec;
    std::filesystem::path directory = std::filesystem::absolute(sceneFile, ec).parent_path();
    directory_ = std::filesystem::weakly_canonical(directory, ec);
    if (ec) directory_ = directory.lexically_normal();
}

ResolvedFile SceneFiles::resolveUri(const std::string& uri) const {
    // The file system would read the name only up to it; and the URI is not quoted, so
    // that the message carries no NUL either.
    if (uri.find('\0') != std::string::npos) return {{}, "contains a NUL character (\\u0000)"};
    std::string scheme = uriScheme(uri);
    if (!scheme.empty()) {
        return {{}, quotedUri(uri) + ": URIs with a scheme (" + scheme + ") are not read; give a path relative to "
                                     "the scene file, or a data: URI (in lower case)"};
    }
    std::string problem;
    std::string path = decodeUriPath(uri, problem);
    if (!problem.empty()) return {{}, "'" + uri + "': " + problem};
    ResolvedFile resolved = resolvePath(path);
    if (!resolved.problem.empty()) {
        resolved.problem = "'" + uri + "'" + (path == uri ? "" : " (decoded '" + path + "')") + " " + resolved.problem;
    }
    return resolved;
}

ResolvedFile SceneFiles::resolvePath(const std::string& path) const {
    std::filesystem::path named(path);
    if (named.is_absolute() && !access_.allowOutsideFiles) return {{}, "is an absolute path" + optOut()};
    std::error_code ec;
    std::filesystem::path file = std::filesystem::weakly_canonical(directory_ / named, ec);
    if (ec) return {{}, "cannot be resolved: " + ec.message()};
    // Checked before the file itself, so nothing is said about a file outside.
    if (!access_.allowOutsideFiles && !isInside(file, directory_)) {
        bool throughLink = isInside((directory_ / named).lexically_normal(), directory_);
        return {{}, std::string("is outside the scene's directory") +
                        (throughLink ? " (through a symbolic link)" : "") + optOut()};
    }
    std::string reason = notRegularFileReason(file);
    if (!reason.empty()) return {{}, reason == "no such file" ? "names no file" : reason};
    return {file, ""};
}

bool isDataUri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

std::string decodeUriPath(const std::string& uri, std::string& problem) {
    std::string path;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            path += ' ';
        } else if (uri[i] == '%') {
            int high = i + 2 < uri.size() ? hexValue(uri[i + 1]) : -1;
            int low = i + 2 < uri.size() ? hexValue(uri[i + 2]) : -1;
            if (high < 0 || low < 0) {
                problem = "'%' must be followed by two hex digits, got '" + uri.substr(i + 1, 2) + "'";
                return "";
            }
            if (high == 0 && low == 0) {
                problem = "'%00' would put a NUL byte in the file name";
                return "";
            }
            path += char(high * 16 + low);
            i += 2;
        } else {
            path += uri[i];
        }
    }
    return path;
}

std::string encodeUriPath(const std::string& path) {
    static const char* kHex = "0123456789ABCDEF";
    std::string uri;
    for (char c : path) {
        unsigned char u = static_cast<unsigned char>(c);
        if (std::isalnum(u) || c == '/' || c == '.' || c == '-' || c == '_' || c == '~') {
            uri += c;
        } else {
            uri += '%';
            uri += kHex[u >> 4];
            uri += kHex[u & 15];
        }
    }
    return uri;
}

}  // namespace vkdr
