#include "image/atomic_write.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <optional>
#include <string>

#include <unistd.h>

#include "core/error.h"
#include "core/interrupt.h"

namespace vkdr {
namespace {

constexpr const char* kTemporaryMarker = ".tmp-";

// Beside the destination, so that the rename stays within one file system; hidden,
// and unique per process and call, so that concurrent writers never share one:
// ".NAME.tmp-PID-COUNTER".
std::filesystem::path temporaryPathFor(const std::filesystem::path& file) {
    static std::atomic<unsigned> counter{0};
    std::string name = "." + file.filename().string() + kTemporaryMarker + std::to_string(getpid()) + "-" +
                       std::to_string(counter++);
    return file.parent_path() / name;
}

// The writing process of a temporary named by temporaryPathFor, if the name is one.
std::optional<pid_t> writerOf(const std::string& name) {
    size_t marker = name.rfind(kTemporaryMarker);
    if (name.empty() || name[0] != '.' || marker == std::string::npos) return std::nullopt;
    const char* digits = name.c_str() + marker + std::strlen(kTemporaryMarker);
    char* end = nullptr;
    long pid = std::strtol(digits, &end, 10);
    if (end == digits || *end != '-' || pid <= 0) return std::nullopt;
    return pid_t(pid);
}

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& reason) {
    throw Error("cannot write '" + file.string() + "': " + reason);
}

void discard(std::ofstream& out, const std::filesystem::path& temporary) {
    out.close();
    std::error_code ignored;  // already failing: report the first error, not this one
    std::filesystem::remove(temporary, ignored);
}

}  // namespace

size_t removeStaleTemporaries(const std::filesystem::path& directory) {
    size_t removed = 0;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
        std::optional<pid_t> writer = writerOf(entry.path().filename().string());
        bool writerGone = writer && kill(*writer, 0) != 0 && errno == ESRCH;
        if (writerGone && entry.is_regular_file() && std::filesystem::remove(entry.path(), error)) ++removed;
    }
    return removed;
}

PendingRenames::~PendingRenames() {
    std::error_code ignored;
    for (const auto& [temporary, file] : renames_) std::filesystem::remove(temporary, ignored);
}

void PendingRenames::commit() {
    while (!renames_.empty()) {
        const auto [temporary, file] = renames_.front();
        std::error_code error;
        std::filesystem::rename(temporary, file, error);
        if (error) fail(file, error.message());
        renames_.erase(renames_.begin());
    }
}

void writeAtomically(const std::filesystem::path& file, const std::function<void(std::ofstream&)>& writeContents,
                     PendingRenames* pending) {
    if (file.filename().empty()) fail(file, "not a file name");
    // The rename would replace whatever has the name: a device node, a FIFO, a socket or
    // a symbolic link (itself, not what it points to) would be lost.
    std::error_code ignored;
    std::filesystem::file_status existing = std::filesystem::symlink_status(file, ignored);
    if (std::filesystem::exists(existing) && !std::filesystem::is_regular_file(existing)) {
        fail(file, "it exists and is not a regular file");
    }
    FileWriteGuard writing;
    std::filesystem::path temporary = temporaryPathFor(file);
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) fail(file, std::strerror(errno));
    try {
        writeContents(out);
        out.close();
        if (!out) fail(file, std::string("write failed: ") + std::strerror(errno));
        if (pending) {
            pending->renames_.emplace_back(temporary, file);
            return;
        }
        std::error_code error;
        std::filesystem::rename(temporary, file, error);
        if (error) fail(file, error.message());
    } catch (const Error&) {
        discard(out, temporary);
        throw;
    } catch (const std::exception& e) {
        discard(out, temporary);
        fail(file, e.what());
    }
}

}  // namespace vkdr
