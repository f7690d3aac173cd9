#include "image/regular_file.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/error.h"

namespace vkdr {
namespace {

std::string kindReason(mode_t mode) {
    if (S_ISREG(mode)) return "";
    if (S_ISDIR(mode)) return "is a directory, not a file";
    if (S_ISFIFO(mode)) return "is a FIFO, not a regular file";
    if (S_ISSOCK(mode)) return "is a socket, not a regular file";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "is a device, not a regular file";
    return "is not a regular file";
}

std::string errnoReason(int error) {
    if (error == ENOENT || error == ENOTDIR) return "no such file";
    return std::string("cannot open: ") + std::strerror(error);
}

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& reason) {
    throw Error(file.string() + ": " + reason);
}

}  // namespace

std::string notRegularFileReason(const std::filesystem::path& file) {
    struct stat status {};
    if (::stat(file.c_str(), &status) != 0) return errnoReason(errno);
    return kindReason(status.st_mode);
}

RegularFile::RegularFile(const std::filesystem::path& file) : file_(file) {
    // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer.
    descriptor_ = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (descriptor_ < 0) fail(file_, errnoReason(errno));
    struct stat status {};
    std::string reason = ::fstat(descriptor_, &status) != 0 ? errnoReason(errno) : kindReason(status.st_mode);
    if (!reason.empty()) {
        ::close(descriptor_);
        fail(file_, reason);
    }
    size_ = uint64_t(status.st_size);
}

RegularFile::~RegularFile() { ::close(descriptor_); }

size_t RegularFile::read(char* into, size_t bytes) {
    size_t done = 0;
    while (done < bytes) {
        ssize_t got = ::read(descriptor_, into + done, bytes - done);
        if (got == 0) break;
        if (got < 0) {
            if (errno == EINTR) continue;
            fail(file_, std::string("read error: ") + std::strerror(errno));
        }
        done += size_t(got);
    }
    return done;
}

std::string RegularFile::readAll() {
    std::string bytes;
    // The size is a hint: a file that grows or shrinks while read is read to its end.
    bytes.resize(size_t(size_));
    bytes.resize(read(bytes.data(), bytes.size()));
    char more[1 << 16];
    while (size_t got = read(more, sizeof(more))) bytes.append(more, got);
    return bytes;
}

std::string readRegularFile(const std::filesystem::path& file) { return RegularFile(file).readAll(); }

}  // namespace vkdr
