#pragma once
#include <stdexcept>
#include <string>

#include "printable_text.h"

namespace vkdr {

// A failure the user can act on: bad input, an unsupported scene feature, a device
// without a needed feature. The command line prints what() and exits with code 2;
// everything else that escapes is a bug. The message is made printable (printableText),
// since it may quote bytes of a damaged file.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(printableText(message)) {}
};

// The scene's parameter values cannot be rendered faithfully (a density grid medium too
// dense to track): where an optimiser's step led there, it names the step.
class UnrenderableValuesError : public Error {
public:
    using Error::Error;
};

}  // namespace vkdr
