#pragma once
#include <string>
#include <vector>

namespace vkdr {

// Where one optimised parameter started and ended (one value, or three for RGB).
struct ParameterFit {
    std::string name;
    std::vector<float> start;
    std::vector<float> fitted;
    std::vector<float> truth;  // the true value, known for experiments; empty otherwise
};

// Values as printed: each one as `pattern` (printf) formats it, space-separated, or for
// more than kMostValuesListed (optimize/value_summary.h) their summary.
std::string fitValues(const std::vector<float>& values, const char* pattern);

// The error of each fitted value relative to the true one, e.g. "+0.42%", or absolute
// ("+0.003 abs") where the true value is 0; for a summarised parameter the relative L2
// error of all its values; "" without a true value.
std::string fitErrors(const ParameterFit& fit);

// What `optimize` prints at the end of a run: an aligned table, one line per parameter,
// of its start and fitted values, and, when any parameter's true value is known (an
// experiment), that value and the error of the fitted one.
std::string parameterTable(const std::vector<ParameterFit>& fits);

}  // namespace vkdr
