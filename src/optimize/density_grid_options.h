#pragma once
#include <string>
#include <vector>

namespace vkdr {

// Throws vkdr::Error saying that `option` ("a smoothness weight is", "coarse-to-fine grid
// levels are") given but no density grid (media/<medium>/density) is being optimised,
// when none of `parameters` names one.
void requireADensityGridAmong(const std::vector<std::string>& parameters, const std::string& option);

}  // namespace vkdr
