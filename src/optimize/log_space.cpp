#include "optimize/log_space.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "optimize/constraints.h"
#include "scene/gltf_diagnostics.h"
#include "scene/parameters.h"

namespace vkdr {

LogSpace::LogSpace(const ParameterVector& parameters, const std::vector<std::string>& logParameters)
    : logValue_(parameters.size(), false) {
    const std::vector<std::string>& names = parameters.names();
    for (auto name = logParameters.begin(); name != logParameters.end(); ++name) {
        if (std::find(logParameters.begin(), name, *name) != name) {
            throw Error("'" + *name + "' is given twice to be optimised in log space");
        }
    }
    for (const std::string& name : logParameters) {
        auto found = std::find(names.begin(), names.end(), name);
        if (found == names.end()) {
            throw Error("'" + name + "' is to be optimised in log space but is not being optimised");
        }
        if (boundsForParameter(name).lower < 0.0) {
            throw Error("'" + name + "' can be negative, so it cannot be optimised in log space");
        }
        const size_t p = size_t(found - names.begin());
        for (size_t i = parameters.offset(p); i < parameters.offset(p) + parameters.count(p); ++i) {
            if (!(parameters.values()[i] > 0.0)) {
                const size_t count = parameters.count(p);
                throw Error("'" + name + "': " + whichValue(i - parameters.offset(p), count) + "starts at " +
                            formatNumber(parameters.values()[i]) +
                            "; optimising it in log space needs every value positive");
            }
            logValue_[i] = true;
        }
    }
}

// Value by value, in parallel: a grid's millions of voxels cross in every iteration.
void LogSpace::enter(std::span<double> values, std::span<double> gradient) const {
    tbb::parallel_for(size_t(0), values.size(), [&](size_t i) {
        if (logValue_[i]) {
            gradient[i] *= values[i];
            values[i] = std::log(values[i]);
        }
    });
}

// A step far enough down makes exp() 0, from whose log no step returns, and which log
// space must not start from again (a checkpoint's values): values stay at or above
// the smallest normal float, which the scene holds and a device does not flush to 0.
void LogSpace::leave(std::span<double> values) const {
    tbb::parallel_for(size_t(0), values.size(), [&](size_t i) {
        if (logValue_[i]) {
            values[i] = std::max(std::exp(values[i]), double(std::numeric_limits<float>::min()));
        }
    });
}

}  // namespace vkdr
