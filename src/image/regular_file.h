#pragma once
#include <cstdint>
#include <filesystem>
#include <string>

namespace vkdr {

// Why `file` cannot be read as a regular file: "" when it can, else "no such file",
// "is a directory", "is a FIFO", ... Follows symbolic links; never opens the file, so a
// FIFO cannot make it wait.
std::string notRegularFileReason(const std::filesystem::path& file);

// An open regular file, for reading. Opening never waits for a FIFO's writer, and what
// is checked is the file opened, not what the path named a moment before. Anything but
// a regular file (a directory, FIFO, device or socket) is refused with vkdr::Error
// "<file>: <reason>".
class RegularFile {
public:
    explicit RegularFile(const std::filesystem::path& file);
    ~RegularFile();
    RegularFile(const RegularFile&) = delete;
    RegularFile& operator=(const RegularFile&) = delete;

    uint64_t size() const { return size_; }
    // Reads up to `bytes` bytes; fewer only at the end of the file.
    size_t read(char* into, size_t bytes);
    std::string readAll();

private:
    std::filesystem::path file_;
    int descriptor_ = -1;
    uint64_t size_ = 0;
};

// The whole of a regular file (RegularFile's checks).
std::string readRegularFile(const std::filesystem::path& file);

}  // namespace vkdr
