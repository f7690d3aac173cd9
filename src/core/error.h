#pragma once
#include <stdexcept>
#include <string>

namespace vkdr {

// A failure the user can act on: bad input, an unsupported scene feature, a device
// without a needed feature. The command line prints what() and exits with code 2;
// everything else that escapes is a bug.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace vkdr
