#pragma once
#include <cmath>
#include <limits>
#include <utility>
#include <string>
#include <vector>

#include "core/error.h"
#include "diff/loss_gradient.h"
#include "scene/parameters.h"

namespace vkdr::test {

// An analytic stand-in for the renderer: loss = sum over parameters and channels of
// (value - minimum)^2, with a known minimum per parameter. Its "render" is an image
// (4x3 unless told) of the first parameter's value, so output files have something to show.
class QuadraticLossGradient : public LossGradient {
public:
    using Minima = std::vector<std::pair<std::string, std::vector<double>>>;
    explicit QuadraticLossGradient(Minima minima) : minima_(std::move(minima)) {}

    // From this evaluation on (counted from 0), the gradient of `name` is NaN.
    void failFrom(size_t evaluation, std::string name) {
        failFrom_ = evaluation;
        failing_ = std::move(name);
    }
    void setImageSize(int width, int height) {
        width_ = width;
        height_ = height;
    }
    // From now on its "render" fails (UnrenderableValuesError) where the first parameter's first value
    // is above `most`, as a renderer's does on a density grid too dense to track.
    void renderOnlyUpTo(double most) { mostRenderable_ = most; }
    const std::vector<uint32_t>& seeds() const { return seeds_; }
    const std::vector<uint32_t>& renderabilitySeeds() const { return renderabilitySeeds_; }

    void requireRenderable(const Scene& scene, uint32_t seed) override {
        renderabilitySeeds_.push_back(seed);
        requireRenders(scene);
    }

    GradientResult evaluate(const Scene& scene, uint32_t seed) override {
        requireRenders(scene);
        GradientResult result;
        for (const auto& [name, minimum] : minima_) {
            std::vector<float> value = getParameter(scene, name);
            std::vector<double> gradient;
            for (size_t c = 0; c < value.size(); ++c) {
                double offset = value[c] - minimum[c];
                result.loss += offset * offset;
                gradient.push_back(2.0 * offset);
            }
            if (name == failing_ && seeds_.size() >= failFrom_) {
                gradient[0] = std::numeric_limits<double>::quiet_NaN();
            }
            result.parameters.push_back({name, value, gradient});
        }
        Image image{width_, height_, std::vector<float>(size_t(width_ * height_ * 3), result.parameters.front().value[0])};
        result.images.push_back(image);
        result.forwardMs = 1.5;
        result.adjointMs = 2.5;
        seeds_.push_back(seed);
        return result;
    }

private:
    void requireRenders(const Scene& scene) const {
        if (getParameter(scene, minima_.front().first).front() > mostRenderable_) {
            throw UnrenderableValuesError("the value is too large to render");
        }
    }

    Minima minima_;  // the parameters, in the order the optimiser asks for them
    std::vector<uint32_t> seeds_;
    std::vector<uint32_t> renderabilitySeeds_;
    double mostRenderable_ = std::numeric_limits<double>::infinity();
    size_t failFrom_ = std::numeric_limits<size_t>::max();
    std::string failing_;
    int width_ = 4;
    int height_ = 3;
};

// A scene with every kind of parameter: the scene medium "fog", a surface "white", a light "lamp".
inline Scene sceneWithParameters() {
    Scene scene;
    scene.media.push_back({"fog", glm::vec3(0.3f), glm::vec3(0.1f), 0.2f});
    scene.sceneMedium = 0;
    Material white;
    white.name = "white";
    white.baseColor = glm::vec3(0.5f);
    Material lamp;
    lamp.name = "lamp";
    lamp.emission = glm::vec3(2.0f);
    lamp.emitter = true;
    scene.materials = {white, lamp};
    return scene;
}

}  // namespace vkdr::test
