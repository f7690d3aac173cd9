#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "diff/loss_gradient.h"
#include "optimize/optimize_loop.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace vkdr {

// A camera an experiment adds to its scene, for views the scene file has no camera for.
struct ExperimentCamera {
    std::string name;
    glm::vec3 position{0.0f};
    glm::vec3 lookAt{0.0f, 0.0f, -1.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float yfovDegrees = 40.0f;
    // > 0: an orthographic camera, viewing this half height (Camera::orthographicHalfHeight).
    float orthographicHalfHeight = 0.0f;
};

struct ParameterValue {
    std::string name;
    std::vector<float> values;  // 1 (g, or one value for all channels) or 3
};

// A self-contained inverse problem (docs/optimisation.md, "Experiment files"): render
// targets from the true values, start from others, optimise, compare.
struct Experiment {
    std::filesystem::path file;              // the experiment file itself
    std::filesystem::path scene;             // resolved against the experiment file's directory
    std::vector<std::string> views;          // camera names; "" = the scene's first camera
    // Cameras whose targets are rendered but not fitted: their error is measured at every
    // iteration (optimize/held_out_error.h), to see the fit generalise.
    std::vector<std::string> heldOutViews;
    std::vector<ExperimentCamera> cameras;   // added to the scene before anything renders
    RenderSettings render;                   // width, height, spp, max depth of every render
    uint32_t targetSpp = 0;                  // samples per pixel of the target renders
    LossKind loss = LossKind::L2;
    OptimizeOptions optimize;                // parameters, optimiser, learning rates, iterations, seed
    std::vector<ParameterValue> trueValues;  // set before the targets render (kept for the fit)
    std::vector<ParameterValue> startValues; // set before the fit starts
    // The keys whose values a command line gave in place of the file's, with the option
    // that gave each ("smoothness": "--smoothness"): a problem with one names the option.
    std::map<std::string, std::string> givenOnCommandLine;
    // Whether the file gives adam_epsilon (its value may be the default's): only Adam has
    // one, whichever optimizer a command line names.
    bool adamEpsilonInFile = false;
};

// Reads and checks an experiment file's structure: unknown keys, wrong types, a
// missing scene file. Throws vkdr::Error naming the file and the key at fault.
Experiment readExperiment(const std::filesystem::path& file);

// Checks the experiment against its loaded scene (parameter names, values, views) and
// adds its cameras to the scene. Throws vkdr::Error naming the experiment file.
void prepareExperimentScene(const Experiment& experiment, Scene& scene);

}  // namespace vkdr
