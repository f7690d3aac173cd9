#include "optimize/run_identity.h"

#include <cinttypes>
#include <cstdio>
#include <fstream>

#include "core/error.h"

namespace vkdr {

std::string fileDigest(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw Error("cannot read '" + file.string() + "'");
    uint64_t hash = 0xcbf29ce484222325ull;  // FNV-1a offset basis and prime
    uint64_t size = 0;
    char buffer[1 << 16];
    while (in.read(buffer, sizeof(buffer)) || in.gcount() > 0) {
        for (std::streamsize i = 0; i < in.gcount(); ++i) {
            hash = (hash ^ uint64_t(static_cast<unsigned char>(buffer[i]))) * 0x100000001b3ull;
        }
        size += uint64_t(in.gcount());
    }
    if (in.bad()) throw Error("cannot read '" + file.string() + "': read error");
    char text[64];
    std::snprintf(text, sizeof(text), "%" PRIu64 " bytes, fnv1a64 %016" PRIx64, size, hash);
    return text;
}

void requireSameRun(const std::filesystem::path& checkpoint, const RunIdentity& written, const RunIdentity& current) {
    auto valueIn = [](const RunIdentity& identity, const std::string& name) {
        auto found = identity.find(name);
        return found == identity.end() ? std::string("(none)") : "'" + found->second + "'";
    };
    RunIdentity names = written;
    names.insert(current.begin(), current.end());
    for (const auto& [name, ignored] : names) {
        std::string before = valueIn(written, name), now = valueIn(current, name);
        if (before != now) {
            throw Error(checkpoint.string() + ": written by a run with " + name + " " + before + ", but this run has " +
                        now + "; resume with the same scene, targets, parameters and options, or start afresh in "
                        "another --out directory");
        }
    }
}

}  // namespace vkdr
