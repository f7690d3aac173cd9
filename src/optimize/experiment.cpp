#include "optimize/experiment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/format_text.h"
#include "image/image.h"
#include "image/regular_file.h"
#include "optimize/coarse_grid_gradient.h"
#include "optimize/density_grid_options.h"
#include "optimize/grid_priors.h"
#include "optimize/log_space.h"
#include "optimize/loss_kind_text.h"
#include "optimize/parameter_vector.h"
#include "scene/gltf_diagnostics.h"
#include "scene/orthographic_view.h"
#include "scene/parameters.h"
#include "scene/parse_json_text.h"

namespace vkdr {
namespace {

using Json = nlohmann::ordered_json;  // keeps "start" in file order: the default parameter order

const std::set<std::string> kKeys = {"scene", "views", "cameras", "width", "height", "spp", "target_spp",
                                     "max_depth", "seed", "iterations", "optimizer", "learning_rate",
                                     "learning_rates", "learning_rate_decay", "learning_rate_decay_start", "log_parameters", "adam_epsilon", "loss", "true", "start",
                                     "parameters", "smoothness", "sparsity", "total_variation", "grid_levels", "held_out_views"};
const std::set<std::string> kCameraKeys = {"name", "position", "look_at", "up", "yfov_degrees",
                                           "orthographic_half_height"};

// Reads one experiment file, prefixing every error with the file and the key at fault.
// ", got VALUE" for a message, VALUE as the file writes it (its first 40 characters).
std::string got(const Json& value) {
    std::string text = value.dump();
    if (text.size() > 40) text = text.substr(0, 40) + "...";
    return ", got " + text;
}

class ExperimentReader {
public:
    explicit ExperimentReader(std::filesystem::path file) : file_(std::move(file)) {}

    [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
        throw Error(file_.string() + ": " + (key.empty() ? "" : key + ": ") + problem);
    }

    Json parse() const {
        try {
            ParsedJsonText<Json> parsed = parseJsonText<Json>(readRegularFile(file_));
            if (parsed.repeatedKey) fail(*parsed.repeatedKey, kRepeatedKeyProblem);
            if (!parsed.document.is_object()) fail("", "expected a JSON object");
            return std::move(parsed.document);
        } catch (const Json::exception& e) {
            fail("", "not valid JSON: " + jsonErrorText(e));
        }
    }

    void requireKnownKeys(const Json& object, const std::set<std::string>& known, const std::string& where) const {
        for (const auto& [key, value] : object.items()) {
            if (!known.count(key)) {
                std::string list;
                for (const std::string& name : known) list += (list.empty() ? "" : ", ") + name;
                fail(where + key, "unknown key; valid keys: " + list);
            }
        }
    }

    std::string string(const Json& value, const std::string& key) const {
        if (!value.is_string()) fail(key, "expected a string");
        return value.get<std::string>();
    }

    // The command line's bounds apply here too: they keep sizes and loops within range.
    // The JSON parser keeps an integer beyond 64 bits as a double, and one beyond int64's
    // range as unsigned: each is compared as what it is.
    // A whole number written with a decimal point (16.0, as a script's floats print) counts.
    uint32_t count(const Json& value, const std::string& key, uint32_t minimum,
                   uint32_t maximum = UINT32_MAX) const {
        bool inRange = false;
        if (value.is_number_unsigned()) {
            inRange = value.get<uint64_t>() >= minimum && value.get<uint64_t>() <= maximum;
        } else if (value.is_number_integer()) {
            inRange = value.get<int64_t>() >= int64_t(minimum) && value.get<int64_t>() <= int64_t(maximum);
        } else if (value.is_number_float()) {
            const double number = value.get<double>();
            inRange = number == std::floor(number) && number >= double(minimum) && number <= double(maximum);
            if (inRange) return uint32_t(number);
        }
        if (!inRange) {
            fail(key, "expected an integer in [" + std::to_string(minimum) + ", " + std::to_string(maximum) + "]" +
                          got(value));
        }
        return uint32_t(value.get<uint64_t>());
    }

    double positive(const Json& value, const std::string& key) const {
        if (!value.is_number() || !(value.get<double>() > 0.0) || !std::isfinite(value.get<double>())) {
            fail(key, "expected a finite number > 0" + got(value));
        }
        return value.get<double>();
    }

    // A number in [minimum, maximum], as the command line's finiteNumberIn takes it.
    double numberIn(const Json& value, const std::string& key, double minimum, double maximum) const {
        if (!value.is_number() || !(value.get<double>() >= minimum && value.get<double>() <= maximum)) {
            fail(key, "expected a number in [" + formatNumber(minimum) + ", " + formatNumber(maximum) + "]" +
                          got(value));
        }
        return value.get<double>();
    }

    // Parameter values and camera coordinates are floats.
    float finiteFloat(const Json& value, const std::string& key) const {
        if (!value.is_number() || !(std::abs(value.get<double>()) <= double(std::numeric_limits<float>::max()))) {
            fail(key,
                 "expected finite numbers within float range" + (value.is_number() ? ", got " + value.dump() : ""));
        }
        return float(value.get<double>());
    }

    std::vector<float> numbers(const Json& value, const std::string& key) const {
        if (value.is_number()) return {finiteFloat(value, key)};
        if (!value.is_array() || (value.size() != 1 && value.size() != 3)) {
            fail(key, "expected a number or an array of 1 or 3 numbers");
        }
        std::vector<float> values;
        for (const Json& element : value) values.push_back(finiteFloat(element, key));
        return values;
    }

    glm::vec3 vector3(const Json& value, const std::string& key) const {
        if (!value.is_array() || value.size() != 3) fail(key, "expected an array of 3 numbers" + got(value));
        return {finiteFloat(value[0], key), finiteFloat(value[1], key), finiteFloat(value[2], key)};
    }

    std::vector<std::string> strings(const Json& value, const std::string& key) const {
        if (!value.is_array()) fail(key, "expected an array of strings");
        std::vector<std::string> result;
        for (const Json& element : value) result.push_back(string(element, key));
        return result;
    }

    std::vector<ParameterValue> parameterValues(const Json& value, const std::string& key) const {
        if (!value.is_object()) fail(key, "expected an object of parameter names and values");
        std::vector<ParameterValue> result;
        for (const auto& [name, values] : value.items()) {
            result.push_back({name, numbers(values, key + "." + name)});
        }
        return result;
    }

    ExperimentCamera camera(const Json& value, size_t index) const {
        std::string where = "cameras[" + std::to_string(index) + "]";
        if (!value.is_object()) fail(where, "expected an object");
        requireKnownKeys(value, kCameraKeys, where + ".");
        for (const char* required : {"name", "position", "look_at"}) {
            if (!value.contains(required)) fail(where, std::string("missing \"") + required + "\"");
        }
        ExperimentCamera camera;
        camera.name = string(value["name"], where + ".name");
        // In "views", "" stands for the scene's first camera.
        if (camera.name.empty()) fail(where + ".name", "must not be empty");
        // The name labels the view's figures wherever they are printed, one line each.
        auto control = [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; };
        if (std::any_of(camera.name.begin(), camera.name.end(), control)) {
            fail(where + ".name", "must not hold control characters, got '" + camera.name + "'");
        }
        camera.position = vector3(value["position"], where + ".position");
        camera.lookAt = vector3(value["look_at"], where + ".look_at");
        if (value.contains("up")) camera.up = vector3(value["up"], where + ".up");
        if (value.contains("yfov_degrees")) {
            double yfov = positive(value["yfov_degrees"], where + ".yfov_degrees");
            camera.yfovDegrees = float(yfov);
            // In the float radians the camera keeps: 1e-300 rounds to 0, 179.99999999 to 180.
            const float radians = glm::radians(camera.yfovDegrees);
            if (!(radians > 0.0f && radians < std::numbers::pi_v<float>)) {
                fail(where + ".yfov_degrees", "must be above 0 and below 180 once rounded to a float, got " +
                                                  formatText("%.17g", yfov));
            }
        }
        if (value.contains("orthographic_half_height")) {
            if (value.contains("yfov_degrees")) {
                fail(where, "give yfov_degrees (a perspective camera) or orthographic_half_height (an orthographic "
                            "one), not both");
            }
            double halfHeight = positive(value["orthographic_half_height"], where + ".orthographic_half_height");
            if (!usableOrthographicHalfExtent(halfHeight)) {
                fail(where + ".orthographic_half_height", "must be a normal float (1.2e-38 to 3.4e+38)");
            }
            camera.orthographicHalfHeight = float(halfHeight);
        }
        glm::vec3 forward = camera.lookAt - camera.position;
        if (glm::length(forward) == 0.0f || glm::length(glm::cross(forward, camera.up)) == 0.0f) {
            fail(where, "look_at must differ from position, and up must not be parallel to the view direction");
        }
        const glm::mat4 view = glm::lookAt(camera.position, camera.lookAt, camera.up);
        const float* entries = &view[0][0];
        if (!std::all_of(entries, entries + 16, [](float entry) { return std::isfinite(entry); })) {
            fail(where, "position, look_at and up are too large for a float's arithmetic: the view they give "
                        "is not finite");
        }
        return camera;
    }

private:
    std::filesystem::path file_;
};

void readRenderSettings(const ExperimentReader& reader, const Json& document, Experiment& experiment) {
    RenderSettings& render = experiment.render;
    // Given alone, either side sets the other from the camera's aspect ratio, as render's do.
    if (!document.contains("width") && !document.contains("height")) render.width = 128;
    const uint32_t maxSide = kMaxImageSide, maxSpp = kMaxSamplesPerPixel, maxDepth = 100000;
    if (document.contains("width")) render.width = int(reader.count(document["width"], "width", 1, maxSide));
    if (document.contains("height")) render.height = int(reader.count(document["height"], "height", 1, maxSide));
    if (document.contains("spp")) render.spp = reader.count(document["spp"], "spp", 1, maxSpp);
    if (document.contains("max_depth")) {
        render.maxDepth = reader.count(document["max_depth"], "max_depth", 0, maxDepth);
    }
    experiment.targetSpp = document.contains("target_spp")
                               ? reader.count(document["target_spp"], "target_spp", 1, maxSpp)
                               : std::min(4 * render.spp, maxSpp);
}

void readOptimizeOptions(const ExperimentReader& reader, const Json& document, Experiment& experiment) {
    OptimizeOptions& options = experiment.optimize;
    if (document.contains("iterations")) {
        options.iterations = reader.count(document["iterations"], "iterations", 1, 1000000);
    }
    if (document.contains("seed")) options.seed = reader.count(document["seed"], "seed", 0);
    if (document.contains("learning_rate")) {
        options.learningRate = reader.positive(document["learning_rate"], "learning_rate");
    }
    if (document.contains("learning_rate_decay")) {
        options.learningRateDecay = reader.numberIn(document["learning_rate_decay"], "learning_rate_decay",
                                                    OptimizeOptions::kLeastLearningRateDecay, 1.0);
    }
    if (document.contains("learning_rate_decay_start")) {
        options.learningRateDecayStart = reader.numberIn(document["learning_rate_decay_start"],
                                                         "learning_rate_decay_start", 0.0,
                                                         OptimizeOptions::kMostLearningRateDecayStart);
    }
    for (auto [key, weight] : {std::pair{"smoothness", &options.smoothness}, std::pair{"sparsity", &options.sparsity},
                               std::pair{"total_variation", &options.totalVariation}}) {
        if (!document.contains(key)) continue;
        *weight = reader.numberIn(document[key], key, 0.0, kMostGridPriorWeight);
    }
    if (document.contains("grid_levels")) {
        options.gridLevels = reader.count(document["grid_levels"], "grid_levels", 1, kMostGridLevels);
    }
    if (document.contains("adam_epsilon")) {
        options.adamEpsilon = reader.positive(document["adam_epsilon"], "adam_epsilon");
        experiment.adamEpsilonInFile = true;
    }
    if (document.contains("learning_rates")) {
        const Json& rates = document["learning_rates"];
        if (!rates.is_object()) reader.fail("learning_rates", "expected an object of parameter names and rates");
        for (const auto& [name, rate] : rates.items()) {
            options.learningRates[name] = reader.positive(rate, "learning_rates." + name);
        }
    }
    // A name read by `parse`, whose error is given with the file and the key.
    auto parsedName = [&](const char* key, auto parse) {
        const std::string name = reader.string(document[key], key);
        try {
            return parse(name);
        } catch (const Error& e) {
            reader.fail(key, e.what());
        }
    };
    if (document.contains("optimizer")) options.optimizer = parsedName("optimizer", parseOptimizerKind);
    if (document.contains("adam_epsilon") && options.optimizer != OptimizerKind::Adam) {
        reader.fail("adam_epsilon", "only Adam has an epsilon; the experiment's optimizer is sgd");
    }
    if (document.contains("loss")) experiment.loss = parsedName("loss", parseLossKind);
    if (document.contains("parameters")) {
        options.parameters = reader.strings(document["parameters"], "parameters");
    } else {
        for (const ParameterValue& start : experiment.startValues) options.parameters.push_back(start.name);
    }
    if (options.parameters.empty()) {
        reader.fail("parameters", "nothing to optimise: list names in \"parameters\" or give \"start\" values");
    }
    if (document.contains("log_parameters")) {
        options.logParameters = reader.strings(document["log_parameters"], "log_parameters");
    }
}

// Checks `values` against the scene by setting them on a copy: the same messages as --set.
void checkValues(const ExperimentReader& reader, const Scene& scene, const std::vector<ParameterValue>& values,
                 const std::string& key) {
    Scene copy = scene;
    for (const ParameterValue& value : values) {
        try {
            setParameter(copy, value.name, value.values);
        } catch (const Error& e) {
            reader.fail(key + "." + value.name, e.what());
        }
    }
}

Camera sceneCamera(const ExperimentCamera& camera) {
    Camera result;
    result.name = camera.name;
    result.cameraToWorld = glm::inverse(glm::lookAt(camera.position, camera.lookAt, camera.up));
    result.yfov = glm::radians(camera.yfovDegrees);
    result.orthographicHalfHeight = camera.orthographicHalfHeight;
    return result;
}

bool hasCamera(const Scene& scene, const std::string& name) {
    return std::any_of(scene.cameras.begin(), scene.cameras.end(),
                       [&](const Camera& camera) { return camera.name == name; });
}

std::string cameraList(const Scene& scene) {
    std::string list;
    for (const Camera& camera : scene.cameras) list += (list.empty() ? "" : ", ") + camera.name;
    return list.empty() ? "none" : list;
}

}  // namespace

Experiment readExperiment(const std::filesystem::path& file) {
    ExperimentReader reader(file);
    Json document = reader.parse();
    reader.requireKnownKeys(document, kKeys, "");

    Experiment experiment;
    experiment.file = file;
    if (!document.contains("scene")) reader.fail("", "missing \"scene\" (a glTF path relative to this file)");
    const std::string scene = reader.string(document["scene"], "scene");
    if (scene.empty()) reader.fail("scene", "empty: give a glTF path relative to this file");
    experiment.scene = (file.parent_path() / scene).lexically_normal();
    std::string reason = notRegularFileReason(experiment.scene);
    if (!reason.empty()) reader.fail("scene", experiment.scene.string() + ": " + reason);
    if (const std::string type = lowercaseExtension(experiment.scene); type != ".gltf" && type != ".glb") {
        reader.fail("scene", experiment.scene.string() + ": expected a .gltf or .glb file");
    }
    if (document.contains("views")) {
        experiment.views = reader.strings(document["views"], "views");
        if (experiment.views.empty()) {
            reader.fail("views", "empty: list at least one camera name, or leave \"views\" out for the first camera");
        }
    } else {
        experiment.views = {""};
    }
    if (document.contains("held_out_views")) {
        experiment.heldOutViews = reader.strings(document["held_out_views"], "held_out_views");
    }
    if (document.contains("cameras")) {
        if (!document["cameras"].is_array()) reader.fail("cameras", "expected an array");
        for (size_t i = 0; i < document["cameras"].size(); ++i) {
            experiment.cameras.push_back(reader.camera(document["cameras"][i], i));
        }
    }
    if (document.contains("true")) experiment.trueValues = reader.parameterValues(document["true"], "true");
    if (document.contains("start")) experiment.startValues = reader.parameterValues(document["start"], "start");
    readRenderSettings(reader, document, experiment);
    readOptimizeOptions(reader, document, experiment);
    return experiment;
}

void prepareExperimentScene(const Experiment& experiment, Scene& scene) {
    ExperimentReader reader(experiment.file);
    for (const ExperimentCamera& camera : experiment.cameras) {
        if (hasCamera(scene, camera.name)) reader.fail("cameras", "the scene already has a camera '" + camera.name + "'");
        scene.cameras.push_back(sceneCamera(camera));
    }
    // Each camera once, by name: "" in "views" is the first camera.
    std::vector<std::string> fitted;
    for (const std::string& view : experiment.views) {
        if (scene.cameras.empty()) reader.fail("views", "the scene has no camera; add one under \"cameras\"");
        if (!view.empty() && !hasCamera(scene, view)) {
            reader.fail("views", "no camera '" + view + "'; cameras: " + cameraList(scene));
        }
        const std::string& name = view.empty() ? scene.cameras.front().name : view;
        if (std::find(fitted.begin(), fitted.end(), name) != fitted.end()) {
            reader.fail("views", "camera '" + name + "' is listed twice" +
                                     (std::find(experiment.views.begin(), experiment.views.end(), "") !=
                                              experiment.views.end()
                                          ? " (\"\" is the first camera)"
                                          : ""));
        }
        fitted.push_back(name);
    }
    std::vector<std::string> heldOut;
    for (const std::string& view : experiment.heldOutViews) {
        if (view.empty()) {
            reader.fail("held_out_views", "\"\" names no camera here (only in \"views\" is it the first camera): "
                                          "name the camera; cameras: " + cameraList(scene));
        }
        if (!hasCamera(scene, view)) reader.fail("held_out_views", "no camera '" + view + "'; cameras: " + cameraList(scene));
        if (std::find(fitted.begin(), fitted.end(), view) != fitted.end()) {
            reader.fail("held_out_views", "'" + view + "' is also a fitted view (\"views\", whose default is the "
                                          "first camera): a held-out view is one the fit never sees");
        }
        if (std::find(heldOut.begin(), heldOut.end(), view) != heldOut.end()) {
            reader.fail("held_out_views", "camera '" + view + "' is listed twice");
        }
        heldOut.push_back(view);
    }
    try {
        requireOptimisableParameters(scene, experiment.optimize.parameters);
    } catch (const Error& e) {
        reader.fail("parameters", e.what());
    }
    // A value the command line gave is named by its option, not by the file's key.
    auto failAt = [&](const std::string& key, const std::string& problem) {
        auto given = experiment.givenOnCommandLine.find(key);
        if (given != experiment.givenOnCommandLine.end()) throw Error(given->second + ": " + problem);
        reader.fail(key, problem);
    };
    try {
        if (experiment.optimize.gridLevels > 1) {
            requireADensityGridAmong(experiment.optimize.parameters, "grid levels are");
        }
    } catch (const Error& e) {
        failAt("grid_levels", e.what());
    }
    try {
        gridPriorWeights(experiment.optimize.parameters, gridPriorWeightsOf(experiment.optimize));
    } catch (const Error& e) {
        failAt(firstWeightName(gridPriorWeightsOf(experiment.optimize)), e.what());
    }
    for (const auto& [name, rate] : experiment.optimize.learningRates) {
        const std::vector<std::string>& names = experiment.optimize.parameters;
        if (std::find(names.begin(), names.end(), name) == names.end()) {
            reader.fail("learning_rates." + name, "not one of the parameters being optimised");
        }
    }
    checkValues(reader, scene, experiment.trueValues, "true");
    checkValues(reader, scene, experiment.startValues, "start");
    Scene started = scene;
    for (const ParameterValue& start : experiment.startValues) setParameter(started, start.name, start.values);
    try {
        LogSpace(ParameterVector(started, experiment.optimize.parameters), experiment.optimize.logParameters);
    } catch (const Error& e) {
        failAt("log_parameters", e.what());
    }
}

}  // namespace vkdr
