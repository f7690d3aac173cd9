#pragma once
#include <filesystem>
#include <map>
#include <string>

namespace vkdr {

// The inputs that decide every iteration of an optimisation, by name ("scene",
// "parameters", "optimizer", ...), each as text. A checkpoint records the identity of
// the run that wrote it, and a run resumes from it only with the same identity.
using RunIdentity = std::map<std::string, std::string>;

// The file's size and a 64-bit FNV-1a hash of its bytes, as text: equal files give
// equal digests, and an edited file almost surely a different one. Throws vkdr::Error
// naming the file when it cannot be read.
std::string fileDigest(const std::filesystem::path& file);

// Throws vkdr::Error naming `checkpoint` and the first entry in which `current` differs
// from `written`, with both values.
void requireSameRun(const std::filesystem::path& checkpoint, const RunIdentity& written, const RunIdentity& current);

}  // namespace vkdr
