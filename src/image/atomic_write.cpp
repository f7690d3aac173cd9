#include "image/atomic_write.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>

#include <unistd.h>

#include "core/error.h"

namespace vkdr {
namespace {

// Beside the destination, so that the rename stays within one file system; hidden,
// and unique per process and call, so that concurrent writers never share one.
std::filesystem::path temporaryPathFor(const std::filesystem::path& file) {
    static std::atomic<unsigned> counter{0};
    std::string name = "." + file.filename().string() + ".tmp-" + std::to_string(getpid()) + "-" +
                       std::to_string(counter++);
    return file.parent_path() / name;
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

void writeAtomically(const std::filesystem::path& file, const std::function<void(std::ofstream&)>& writeContents) {
    if (file.filename().empty()) fail(file, "not a file name");
    std::filesystem::path temporary = temporaryPathFor(file);
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) fail(file, std::strerror(errno));
    try {
        writeContents(out);
        out.close();
        if (!out) fail(file, std::string("write failed: ") + std::strerror(errno));
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
