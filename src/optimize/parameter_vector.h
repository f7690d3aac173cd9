#pragma once
#include <span>
#include <string>
#include <vector>

#include "optimize/constraints.h"
#include "scene/scene.h"

namespace vkdr {

// Throws what ParameterVector's constructor would for these names, without reading
// values: for checking a command line before any rendering starts.
void requireOptimisableParameters(const Scene& scene, const std::vector<std::string>& names);

// The parameters being optimised, as the optimiser sees them: one flat vector of
// doubles (each RGB parameter three values, g one), with each parameter's bounds.
class ParameterVector {
public:
    // Reads the current values of `names` from `scene`. Throws vkdr::Error for an unknown
    // name (listing the valid ones), a name given twice, or none at all.
    ParameterVector(const Scene& scene, std::vector<std::string> names);

    const std::vector<std::string>& names() const { return names_; }
    size_t size() const { return values_.size(); }
    std::span<double> values() { return values_; }
    std::span<const double> values() const { return values_; }
    // The slice of values() (or of any vector in the same layout) that is parameter i.
    size_t offset(size_t parameter) const { return offsets_[parameter]; }
    size_t count(size_t parameter) const { return offsets_[parameter + 1] - offsets_[parameter]; }

    // Clamps every value into its parameter's bounds.
    void project();
    // Sets each parameter in `scene` (as floats).
    void writeTo(Scene& scene) const;

private:
    std::vector<std::string> names_;
    std::vector<size_t> offsets_;  // parameter i is values_[offsets_[i], offsets_[i + 1])
    std::vector<ValueRange> bounds_;
    std::vector<double> values_;
};

}  // namespace vkdr
