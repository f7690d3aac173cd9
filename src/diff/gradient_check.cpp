#include "diff/gradient_check.h"

#include <cmath>

#include "scene/parameters.h"

namespace vkdr {
namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

struct MeanAndError {
    double mean;
    double error;
};

MeanAndError meanAndError(const std::vector<double>& v) {
    double sum = 0.0, sumSquares = 0.0;
    for (double x : v) {
        sum += x;
        sumSquares += x * x;
    }
    double n = double(v.size());
    double mean = sum / n;
    double variance = n > 1 ? std::max(0.0, (sumSquares - n * mean * mean) / (n - 1)) : 0.0;
    return {mean, std::sqrt(variance / n)};
}

double lossWith(RenderedLossGradient& lg, const Scene& scene, const std::string& name, int component, float value,
                uint32_t seed) {
    Scene changed = scene;
    std::vector<float> v = getParameter(changed, name);
    v[component] = value;
    setParameter(changed, name, v);
    return lg.loss(changed, seed);
}

}  // namespace

double finiteDifferenceStep(const std::string& parameter, float value) {
    if (endsWith(parameter, "/g")) {
        return 1e-2;
    }
    if (endsWith(parameter, "/sigma_a") || endsWith(parameter, "/sigma_s")) {
        return 0.15 * std::max(std::abs(double(value)), 0.1);
    }
    return 1e-2 * std::max(std::abs(double(value)), 0.1);
}

std::vector<GradientCheckRow> checkGradients(RenderedLossGradient& lg, const Scene& scene,
                                             const std::vector<std::string>& parameters, int seeds) {
    std::vector<std::vector<std::vector<double>>> adjoint(parameters.size());
    for (int s = 0; s < seeds; ++s) {
        GradientResult r = lg.evaluate(scene, uint32_t(s));
        for (size_t p = 0; p < parameters.size(); ++p) {
            adjoint[p].resize(r.parameters[p].gradient.size());
            for (size_t c = 0; c < r.parameters[p].gradient.size(); ++c) {
                adjoint[p][c].push_back(r.parameters[p].gradient[c]);
            }
        }
    }
    std::vector<GradientCheckRow> rows;
    for (size_t p = 0; p < parameters.size(); ++p) {
        const std::vector<float> value = getParameter(scene, parameters[p]);
        for (size_t c = 0; c < value.size(); ++c) {
            const float x = value[c];
            const double h = finiteDifferenceStep(parameters[p], x);
            const bool oneSided = !endsWith(parameters[p], "/g") && x - h < 0.0;
            std::vector<double> differences;
            for (int s = 0; s < seeds; ++s) {
                auto loss = [&](double at) { return lossWith(lg, scene, parameters[p], int(c), float(at), uint32_t(s)); };
                differences.push_back(oneSided ? (-3.0 * loss(x) + 4.0 * loss(x + h) - loss(x + 2.0 * h)) / (2.0 * h)
                                               : (loss(x + h) - loss(x - h)) / (2.0 * h));
            }
            MeanAndError a = meanAndError(adjoint[p][c]);
            MeanAndError f = meanAndError(differences);
            rows.push_back({parameters[p], int(c), a.mean, a.error, f.mean, f.error, h});
        }
    }
    return rows;
}

}  // namespace vkdr
