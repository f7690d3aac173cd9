#pragma once
#include <sys/stat.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"

namespace vkdr::test {

// Expects `action` to throw vkdr::Error with every one of `parts` in its message.
inline void expectErrorMentioning(const std::function<void()>& action, const std::vector<std::string>& parts) {
    try {
        action();
        ADD_FAILURE() << "no error";
    } catch (const Error& error) {
        for (const std::string& part : parts) {
            EXPECT_NE(std::string(error.what()).find(part), std::string::npos)
                << "'" << part << "' not in: " << error.what();
        }
    }
}

// Expects `read` to refuse a directory and a FIFO (made in `directory`) with an error
// naming each and what it is, without waiting for a writer on the FIFO.
inline void expectNonRegularFilesRefused(const std::filesystem::path& directory,
                                         const std::function<void(const std::filesystem::path&)>& read) {
    std::filesystem::create_directory(directory / "folder.json");
    expectErrorMentioning([&] { read(directory / "folder.json"); }, {"folder.json", "is a directory"});
    ASSERT_EQ(::mkfifo((directory / "pipe.json").c_str(), 0600), 0);
    expectErrorMentioning([&] { read(directory / "pipe.json"); }, {"pipe.json", "FIFO"});
}

}  // namespace vkdr::test
