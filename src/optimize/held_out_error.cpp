#include "optimize/held_out_error.h"

#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/sample_statistics.h"

namespace vkdr {
namespace {

double squaredDifference(const float* a, const float* b) {
    double sum = 0.0;
    for (int c = 0; c < 3; ++c) sum += (double(a[c]) - double(b[c])) * (double(a[c]) - double(b[c]));
    return sum / 3.0;
}

}  // namespace

double targetMean(const Image& target) {
    double sum = 0.0;
    for (float value : target.rgb) sum += value;
    return target.rgb.empty() ? 0.0 : sum / double(target.rgb.size());
}

HeldOutError heldOutError(const Image& render, const Image& trueRender, const Image& target) {
    const bool sameSize = render.rgb.size() == target.rgb.size() && trueRender.rgb.size() == target.rgb.size() &&
                          render.width == target.width && trueRender.width == target.width;
    if (!sameSize || target.rgb.empty()) throw Error("held-out view: the renders and the target differ in size");
    const double brightness = targetMean(target);
    if (!(brightness > 0.0)) throw Error("held-out view: the target is black, so no error is relative to it");

    std::vector<double> excess;
    excess.reserve(target.rgb.size() / 3);
    double renderSum = 0.0, trueSum = 0.0;
    for (size_t i = 0; i < target.rgb.size(); i += 3) {
        const double renderError = squaredDifference(&render.rgb[i], &target.rgb[i]);
        const double trueError = squaredDifference(&trueRender.rgb[i], &target.rgb[i]);
        renderSum += renderError;
        trueSum += trueError;
        excess.push_back(renderError - trueError);
    }
    const double pixels = double(target.rgb.size() / 3);
    HeldOutError error;
    error.relativeRmse = std::sqrt(renderSum / pixels) / brightness;
    error.floorRelativeRmse = std::sqrt(trueSum / pixels) / brightness;
    const MeanAndError mean = meanAndError(excess);
    error.excessInStandardErrors = mean.error > 0.0 ? mean.mean / mean.error : 0.0;
    return error;
}

}  // namespace vkdr
