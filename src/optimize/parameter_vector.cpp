#include "optimize/parameter_vector.h"

#include <algorithm>

#include "core/error.h"
#include "scene/parameters.h"

namespace vkdr {

void requireOptimisableParameters(const Scene& scene, const std::vector<std::string>& names) {
    if (names.empty()) {
        throw Error("no parameters to optimise");
    }
    for (size_t i = 0; i < names.size(); ++i) {
        if (std::find(names.begin(), names.begin() + long(i), names[i]) != names.begin() + long(i)) {
            throw Error("parameter '" + names[i] + "' is given twice");
        }
        getParameter(scene, names[i]);  // throws for an unknown name, listing the valid ones
        boundsForParameter(names[i]);
    }
}

ParameterVector::ParameterVector(const Scene& scene, std::vector<std::string> names) : names_(std::move(names)) {
    requireOptimisableParameters(scene, names_);
    offsets_.push_back(0);
    for (size_t i = 0; i < names_.size(); ++i) {
        std::vector<float> current = getParameter(scene, names_[i]);
        bounds_.push_back(boundsForParameter(names_[i]));
        values_.insert(values_.end(), current.begin(), current.end());
        offsets_.push_back(values_.size());
    }
}

void ParameterVector::project() {
    for (size_t i = 0; i < names_.size(); ++i) {
        projectOntoBounds(std::span(values_).subspan(offset(i), count(i)), bounds_[i]);
    }
}

void ParameterVector::writeTo(Scene& scene) const {
    for (size_t i = 0; i < names_.size(); ++i) {
        std::vector<float> values(values_.begin() + long(offset(i)), values_.begin() + long(offset(i) + count(i)));
        setParameter(scene, names_[i], values);
    }
}

}  // namespace vkdr
