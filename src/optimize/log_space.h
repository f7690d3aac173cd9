#pragma once
#include <span>
#include <string>
#include <vector>

#include "optimize/parameter_vector.h"

namespace vkdr {

// Parameters optimised as the logarithm of their value: a step changes the value by a
// factor rather than an amount, so one learning rate serves values that span orders of
// magnitude (a fog from sigma_s = 0.2 down to 1e-3) and the value can never reach 0.
class LogSpace {
public:
    // Which of `parameters`' values are stepped in log space. Throws vkdr::Error naming
    // the parameter for one that is not being optimised, that may be negative (g), or
    // whose current value is not positive.
    LogSpace(const ParameterVector& parameters, const std::vector<std::string>& logParameters);

    // Values to log values, and dLoss/dvalue to dLoss/dlog(value) = value * dLoss/dvalue.
    void enter(std::span<double> values, std::span<double> gradient) const;
    // Log values back to values.
    void leave(std::span<double> values) const;

private:
    std::vector<bool> logValue_;  // per value of the ParameterVector
};

}  // namespace vkdr
