#pragma once
#include <string>

namespace vkdr {

// `name`, followed by '_' as often as it takes for `taken` to say it is free: how a
// material or camera whose name another has gets one of its own.
template <typename Taken>
std::string firstFreeName(std::string name, Taken taken) {
    while (taken(name)) {
        name += "_";
    }
    return name;
}

}  // namespace vkdr
