// The optimiser loop against an analytic loss: convergence, constraints, seeds, and
// stopping on a non-finite gradient.
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include <gtest/gtest.h>

#include "core/error.h"
#include "expect_error.h"
#include "optimize/constraints.h"
#include "optimize/optimize_loop.h"
#include "quadratic_loss_gradient.h"
#include "scene/parameters.h"
#include "scene/scene_medium_emission.h"

namespace vkdr::test {
namespace {

OptimizeOptions optionsFor(std::vector<std::string> parameters, OptimizerKind optimizer, double learningRate,
                           uint32_t iterations) {
    OptimizeOptions options;
    options.parameters = std::move(parameters);
    options.optimizer = optimizer;
    options.learningRate = learningRate;
    options.iterations = iterations;
    return options;
}

void expectValues(const Scene& scene, const std::string& name, const std::vector<float>& expected, float tolerance) {
    std::vector<float> values = getParameter(scene, name);
    ASSERT_EQ(values.size(), expected.size()) << name;
    for (size_t i = 0; i < values.size(); ++i) {
        EXPECT_NEAR(values[i], expected[i], tolerance) << name << "[" << i << "]";
    }
}

TEST(OptimizeLoop, AdamFindsTheMinimumOfAQuadraticInSigmaAndG) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/sigma_a", {0.05, 0.1, 0.2}}, {"media/fog/g", {-0.4}}});
    OptimizeResult result =
        optimize(loss, scene, optionsFor({"media/fog/sigma_a", "media/fog/g"}, OptimizerKind::Adam, 0.01, 400));
    expectValues(scene, "media/fog/sigma_a", {0.05f, 0.1f, 0.2f}, 2e-3f);
    expectValues(scene, "media/fog/g", {-0.4f}, 2e-3f);
    ASSERT_EQ(result.losses.size(), 400u);
    EXPECT_LT(result.losses.back(), 1e-4 * result.losses.front());
    ASSERT_EQ(result.lastImages.size(), 1u);
}

// An iteration's wall clock covers its metrics (and evaluation and step): a metric that
// takes 3 ms makes every iteration at least that long.
TEST(OptimizeLoop, IterationTimesIncludeTheMetrics) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/sigma_s", {0.7, 0.6, 0.5}}});
    OptimizeCallbacks callbacks;
    callbacks.measure = [](const Scene&, uint32_t) {
        std::this_thread::sleep_for(std::chrono::milliseconds(3));
        return std::vector<Metric>{};
    };
    std::vector<double> times;
    callbacks.iterationDone = [&](const IterationRecord& record) { times.push_back(record.iterationMs); };
    OptimizeResult result = optimize(loss, scene, optionsFor({"media/fog/sigma_s"}, OptimizerKind::Sgd, 0.1, 4), callbacks);
    ASSERT_EQ(times.size(), 4u);
    for (double ms : times) EXPECT_GE(ms, 3.0);
    EXPECT_EQ(result.iterationsRun, 4u);
    EXPECT_GE(result.iterationMs, 12.0);
}

TEST(OptimizeLoop, SgdFindsTheMinimumOfAQuadratic) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/sigma_s", {0.7, 0.6, 0.5}}});
    optimize(loss, scene, optionsFor({"media/fog/sigma_s"}, OptimizerKind::Sgd, 0.1, 100));
    expectValues(scene, "media/fog/sigma_s", {0.7f, 0.6f, 0.5f}, 1e-5f);
}

TEST(OptimizeLoop, KeepsEveryParameterInsideItsConstraints) {
    Scene scene = sceneWithParameters();
    // Every minimum lies outside the allowed range: the fit must stop on the boundary.
    QuadraticLossGradient loss({{"media/fog/sigma_a", {-1.0, 0.1, -0.5}},
                                {"media/fog/g", {1.5}},
                                {"materials/white/base_color", {1.3, -0.2, 0.4}},
                                {"lights/lamp/emission", {-3.0, 1.0, 2.0}}});
    OptimizeOptions options = optionsFor({"media/fog/sigma_a", "media/fog/g", "materials/white/base_color",
                                          "lights/lamp/emission"},
                                         OptimizerKind::Adam, 0.05, 300);
    size_t evaluations = 0;
    OptimizeCallbacks callbacks;
    callbacks.iterationDone = [&](const IterationRecord&) {
        ++evaluations;
        EXPECT_GE(getParameter(scene, "media/fog/sigma_a")[0], 0.0f);
        EXPECT_LE(std::abs(getParameter(scene, "media/fog/g")[0]), float(describe(ParameterKind::G).range.upper));
    };
    optimize(loss, scene, options, callbacks);
    EXPECT_EQ(evaluations, 300u);
    expectValues(scene, "media/fog/sigma_a", {0.0f, 0.1f, 0.0f}, 2e-3f);
    expectValues(scene, "media/fog/g", {0.99f}, 1e-6f);
    expectValues(scene, "materials/white/base_color", {1.0f, 0.0f, 0.4f}, 2e-3f);
    expectValues(scene, "lights/lamp/emission", {0.0f, 1.0f, 2.0f}, 2e-3f);
}

// A scene-wide medium that emits may not stop attenuating (every ray leaving the scene
// would gather emission / sigma_t beyond any radiance): a fit towards sigma_a = 0 is held
// at emission / kMaxRadiance in the channels that emit, and one towards a stronger
// emission at kMaxRadiance x sigma_t.
TEST(OptimizeLoop, KeepsASceneWideMediumsEmissionBounded) {
    Scene scene = sceneWithParameters();
    scene.media[0].sigma_s = glm::vec3(0.0f);
    scene.media[0].emission = glm::vec3(1.0f, 2.0f, 0.0f);
    OptimizeCallbacks callbacks;
    callbacks.iterationDone = [&](const IterationRecord& record) {
        std::optional<UnboundedSceneEmission> unbounded = unboundedSceneEmission(scene);
        EXPECT_FALSE(unbounded) << "iteration " << record.iteration << ": " << unbounded->problem;
    };
    QuadraticLossGradient towardsNoAttenuation({{"media/fog/sigma_a", {-1.0, -1.0, -1.0}}});
    optimize(towardsNoAttenuation, scene, optionsFor({"media/fog/sigma_a"}, OptimizerKind::Adam, 0.05, 100),
             callbacks);
    std::vector<float> sigmaA = getParameter(scene, "media/fog/sigma_a");
    EXPECT_NEAR(sigmaA[0], 1e-12f, 1e-16f);
    EXPECT_NEAR(sigmaA[1], 2e-12f, 1e-16f);
    EXPECT_EQ(sigmaA[2], 0.0f);

    scene.media[0].sigma_a = glm::vec3(1e-13f, 0.0f, 0.0f);
    scene.media[0].emission = glm::vec3(0.0f);
    QuadraticLossGradient towardsBrighter({{"media/fog/emission", {5.0, 0.0, 0.0}}});
    optimize(towardsBrighter, scene, optionsFor({"media/fog/emission"}, OptimizerKind::Adam, 0.05, 100), callbacks);
    EXPECT_NEAR(getParameter(scene, "media/fog/emission")[0], 0.1f, 1e-5f);
}

TEST(OptimizeLoop, UsesPerParameterLearningRates) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/sigma_a", {0.0, 0.0, 0.0}}, {"media/fog/sigma_s", {0.0, 0.0, 0.0}}});
    OptimizeOptions options = optionsFor({"media/fog/sigma_a", "media/fog/sigma_s"}, OptimizerKind::Adam, 0.01, 1);
    options.learningRates["media/fog/sigma_s"] = 0.05;
    optimize(loss, scene, options);
    expectValues(scene, "media/fog/sigma_a", {0.29f, 0.29f, 0.29f}, 1e-6f);  // Adam's first step is the rate
    expectValues(scene, "media/fog/sigma_s", {0.05f, 0.05f, 0.05f}, 1e-6f);

    options.learningRates["media/fog/g"] = 0.1;
    expectErrorMentioning([&] { optimize(loss, scene, options); }, {"media/fog/g"});
}

// Runs SGD on media/fog/g towards -100 with a base rate of 1e-4 for rates.size()
// iterations and expects iteration i to use rates[i]: SGD's step is rate * 2 (g + 100),
// so the steps show the rates.
void expectSgdRates(OptimizeOptions options, const std::vector<double>& rates) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/g", {-100.0}}});
    options.parameters = {"media/fog/g"};
    options.optimizer = OptimizerKind::Sgd;
    options.learningRate = 1e-4;
    options.iterations = uint32_t(rates.size());
    std::vector<double> values;
    optimize(loss, scene, options, {{}, [&](const IterationRecord& record) { values.push_back(record.parameters[0].value[0]); }});
    values.push_back(getParameter(scene, "media/fog/g")[0]);
    ASSERT_EQ(values.size(), rates.size() + 1);
    for (size_t i = 0; i < rates.size(); ++i) {
        EXPECT_NEAR(values[i] - values[i + 1], rates[i] * 2.0 * (values[i] + 100.0), 1e-7) << i;
    }
}

TEST(OptimizeLoop, DecaysTheLearningRateExponentiallyToTheGivenFraction) {
    OptimizeOptions options;
    options.learningRateDecay = 0.25;
    expectSgdRates(options, {1e-4, 0.5e-4, 0.25e-4});  // 0.25^(i/2)

    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/g", {-100.0}}});
    options = optionsFor({"media/fog/g"}, OptimizerKind::Sgd, 1e-4, 3);
    options.learningRateDecay = 1.5;
    EXPECT_THROW(optimize(loss, scene, options), Error);
}

TEST(OptimizeLoop, HoldsTheLearningRateUntilTheDecayStarts) {
    OptimizeOptions options;
    options.learningRateDecay = 0.25;
    options.learningRateDecayStart = 0.5;
    // Iterations 0-2 at the full rate, then 0.25^(1/2) and 0.25^1 at iterations 3 and 4.
    expectSgdRates(options, {1e-4, 1e-4, 1e-4, 0.5e-4, 0.25e-4});

    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/g", {-100.0}}});
    options = optionsFor({"media/fog/g"}, OptimizerKind::Sgd, 1e-4, 5);
    options.learningRateDecayStart = 1.0;
    EXPECT_THROW(optimize(loss, scene, options), Error);
}

TEST(OptimizeLoop, RendersIterationIWithBaseSeedPlusIAndReportsProgress) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/g", {0.0}}});
    OptimizeOptions options = optionsFor({"media/fog/g"}, OptimizerKind::Adam, 0.01, 3);
    options.seed = 40;
    std::vector<std::pair<uint32_t, double>> progress;
    OptimizeCallbacks callbacks;
    callbacks.iterationDone = [&](const IterationRecord& record) { progress.push_back({record.iteration, record.loss}); };
    optimize(loss, scene, options, callbacks);
    EXPECT_EQ(loss.seeds(), (std::vector<uint32_t>{40, 41, 42}));
    ASSERT_EQ(progress.size(), 3u);
    EXPECT_EQ(progress[2].first, 2u);
    EXPECT_NEAR(progress[0].second, 0.04, 1e-7);  // g starts at 0.2
}

TEST(OptimizeLoop, StopsOnANonFiniteGradientNamingTheParameterAndIteration) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/sigma_a", {0.1, 0.1, 0.1}}, {"media/fog/sigma_s", {0.0, 0.0, 0.0}}});
    loss.failFrom(3, "media/fog/sigma_s");
    std::vector<float> valuesAfterIteration2;
    OptimizeCallbacks callbacks;
    callbacks.iterationDone = [&](const IterationRecord&) {
        valuesAfterIteration2 = getParameter(scene, "media/fog/sigma_s");
    };
    expectErrorMentioning(
        [&] {
            optimize(loss, scene,
                     optionsFor({"media/fog/sigma_a", "media/fog/sigma_s"}, OptimizerKind::Adam, 0.01, 10), callbacks);
        },
        {"iteration 3", "media/fog/sigma_s", "nan"});
    EXPECT_EQ(getParameter(scene, "media/fog/sigma_s"), valuesAfterIteration2);
}

// An emitting scene-wide medium whose sigmas reached (nearly) 0 gives every ray that
// leaves the scene emission / (sigma_a + sigma_s): the error names that, not the renderer.
TEST(OptimizeLoop, NamesAnExtremeSceneWideEmissionAsTheCauseOfANonFiniteGradient) {
    Scene scene = sceneWithParameters();
    scene.media[0].sigma_a = glm::vec3(1e-18f);
    scene.media[0].sigma_s = glm::vec3(0.0f);
    scene.media[0].emission = glm::vec3(1e-6f);
    QuadraticLossGradient loss({{"media/fog/sigma_a", {0.1, 0.1, 0.1}}});
    loss.failFrom(0, "media/fog/sigma_a");
    expectErrorMentioning(
        [&] { optimize(loss, scene, optionsFor({"media/fog/sigma_a"}, OptimizerKind::Adam, 0.01, 3)); },
        {"iteration 0", "every ray that leaves the scene gathers emission / (sigma_a + sigma_s) = 1e+12 (channel R) "
                        "from the scene-wide medium 'fog'"});
}

// Downwards too, where sigma_s's bound at 0 would otherwise clamp the step to 0.
TEST(OptimizeLoop, StopsOnAStepBeyondFloatRangeBeforeItReachesTheScene) {
    for (double minimum : {1e30, -1e30}) {
        Scene scene = sceneWithParameters();
        // SGD's step is rate * 2 (sigma - minimum): far beyond float range for this rate.
        QuadraticLossGradient loss({{"media/fog/sigma_s", {minimum, minimum, minimum}}});
        std::vector<float> before = getParameter(scene, "media/fog/sigma_s");
        SCOPED_TRACE(minimum);
        expectErrorMentioning(
            [&] { optimize(loss, scene, optionsFor({"media/fog/sigma_s"}, OptimizerKind::Sgd, 1e20, 5)); },
            {"iteration 0", "media/fog/sigma_s", "beyond float range"});
        EXPECT_EQ(getParameter(scene, "media/fog/sigma_s"), before);
    }
}

// The values the last step leaves are what a run writes out, and no iteration renders
// them: the loop renders them once more, with the seed the next iteration would take.
TEST(OptimizeLoop, RendersTheLastStepsValuesOnceMore) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/g", {0.0}}});
    OptimizeOptions options = optionsFor({"media/fog/g"}, OptimizerKind::Adam, 0.01, 3);
    options.seed = 40;
    optimize(loss, scene, options);
    EXPECT_EQ(loss.seeds(), (std::vector<uint32_t>{40, 41, 42}));
    EXPECT_EQ(loss.renderabilitySeeds(), (std::vector<uint32_t>{43}));
}

TEST(OptimizeLoop, StopsWhenTheLastStepsValuesDoNotRender) {
    Scene scene = sceneWithParameters();
    // SGD steps sigma_a from 0.3 towards 10 by 0.1 * 2 * 9.7 = 1.94 at the first step.
    QuadraticLossGradient loss({{"media/fog/sigma_a", {10.0, 10.0, 10.0}}});
    loss.renderOnlyUpTo(1.0);
    expectErrorMentioning([&] { optimize(loss, scene, optionsFor({"media/fog/sigma_a"}, OptimizerKind::Sgd, 0.1, 1)); },
                          {"last step (iteration 0)", "too large to render", "smaller learning rate"});
    EXPECT_EQ(loss.seeds().size(), 1u);
}

TEST(OptimizeLoop, NamesTheIterationWhoseRenderFailed) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/sigma_a", {10.0, 10.0, 10.0}}});
    loss.renderOnlyUpTo(1.0);
    expectErrorMentioning([&] { optimize(loss, scene, optionsFor({"media/fog/sigma_a"}, OptimizerKind::Sgd, 0.1, 5)); },
                          {"iteration 1: ", "too large to render"});
    EXPECT_EQ(loss.seeds().size(), 1u);
}

TEST(OptimizeLoop, RejectsUnknownRepeatedAndMissingParameters) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({});
    auto expectError = [&](std::vector<std::string> names, const std::string& part) {
        OptimizeOptions options = optionsFor(names, OptimizerKind::Adam, 0.01, 1);
        expectErrorMentioning([&] { optimize(loss, scene, options); }, {part});
    };
    expectError({"media/haze/sigma_a"}, "media/fog/sigma_a");  // lists the valid names
    expectError({"media/fog/g", "media/fog/g"}, "twice");
    expectError({}, "no parameters");
}

// In log space Adam's first step, which is the rate, is a factor of exp(-rate), and a fit
// from four times the minimum ends on it.
TEST(OptimizeLoop, StepsLogParametersByFactors) {
    Scene scene = sceneWithParameters();
    setParameter(scene, "media/fog/sigma_s", std::vector<float>{0.2f, 0.2f, 0.2f});
    QuadraticLossGradient loss({{"media/fog/sigma_s", {0.05, 0.05, 0.05}}, {"media/fog/g", {0.5}}});
    OptimizeOptions options = optionsFor({"media/fog/sigma_s", "media/fog/g"}, OptimizerKind::Adam, 0.1, 1);
    options.logParameters = {"media/fog/sigma_s"};
    optimize(loss, scene, options);
    const float once = 0.2f * std::exp(-0.1f);
    expectValues(scene, "media/fog/sigma_s", {once, once, once}, 1e-7f);
    expectValues(scene, "media/fog/g", {0.3f}, 1e-6f);  // g, not in log space, moves by the rate from 0.2

    setParameter(scene, "media/fog/sigma_s", std::vector<float>{0.2f, 0.2f, 0.2f});
    options.learningRate = 0.05;
    options.iterations = 1000;
    options.learningRateDecay = 0.01;
    optimize(loss, scene, options);
    expectValues(scene, "media/fog/sigma_s", {0.05f, 0.05f, 0.05f}, 1e-4f);
}

// A step that takes a value in log space below what a double holds leaves it at the
// smallest normal float, from which later steps (and a resumed run) go on.
TEST(OptimizeLoop, LogSpaceValuesStayPositive) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/sigma_a", {0.0, 0.0, 0.0}}});
    OptimizeOptions options = optionsFor({"media/fog/sigma_a"}, OptimizerKind::Sgd, 1e6, 1);
    options.logParameters = {"media/fog/sigma_a"};
    optimize(loss, scene, options);
    const float smallest = std::numeric_limits<float>::min();
    expectValues(scene, "media/fog/sigma_a", {smallest, smallest, smallest}, 0.0f);
    optimize(loss, scene, options);  // starts from there, as a resumed run would
    expectValues(scene, "media/fog/sigma_a", {smallest, smallest, smallest}, 0.0f);
}

TEST(OptimizeLoop, RejectsLogSpaceForNegativeZeroMissingOrRepeatedParameters) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/sigma_a", {0.1, 0.1, 0.1}}, {"media/fog/g", {0.0}}});
    auto expectError = [&](const std::string& logParameter, const std::string& part, size_t times = 1) {
        OptimizeOptions options = optionsFor({"media/fog/sigma_a", "media/fog/g"}, OptimizerKind::Adam, 0.01, 1);
        options.logParameters.assign(times, logParameter);
        expectErrorMentioning([&] { optimize(loss, scene, options); }, {logParameter, part});
    };
    expectError("media/fog/g", "can be negative");
    expectError("media/fog/sigma_s", "not being optimised");
    expectError("media/fog/sigma_a", "given twice", 2);  // as a repeated --param is refused
    setParameter(scene, "media/fog/sigma_a", std::vector<float>{0.1f, 0.0f, 0.1f});
    expectError("media/fog/sigma_a", "value 1 of 3 (counted from 0): starts at 0; optimising it in log space needs "
                                     "every value positive");
}

TEST(Constraints, FollowTheLastComponentOfTheName) {
    EXPECT_EQ(boundsForParameter("media/a/b/sigma_s").lower, 0.0);
    EXPECT_EQ(boundsForParameter("materials/x/base_color").upper, 1.0);
    EXPECT_EQ(boundsForParameter("media/fog/g").lower, -0.99);
    EXPECT_EQ(boundsForParameter("media/fog/density").lower, 0.0);
    EXPECT_THROW(boundsForParameter("media/fog/temperature"), Error);
}

// The optimiser keeps each value in the range that setting it enforces: a value
// projected onto either end is one the scene accepts.
TEST(Constraints, AreTheRangesThatSettingAValueEnforces) {
    for (const ParameterDescription& description : parameterDescriptions()) {
        const std::string name = parameterName(description.kind, "fog");
        const ValueRange bounds = boundsForParameter(name);
        EXPECT_EQ(bounds.lower, description.range.lower) << name;
        EXPECT_EQ(bounds.upper, description.range.upper) << name;
        std::vector<double> values = {-1e6, 1e6};
        projectOntoBounds(values, bounds);
        for (double value : values) {
            EXPECT_TRUE(bounds.contains(float(value))) << name << " " << value;
            EXPECT_EQ(valueProblem(description, float(value)), "") << name;
        }
    }
    Scene scene = sceneWithParameters();
    std::vector<double> g = {1.5};
    projectOntoBounds(g, boundsForParameter("media/fog/g"));
    setParameter(scene, "media/fog/g", std::vector<float>{float(g[0])});
    EXPECT_EQ(getParameter(scene, "media/fog/g")[0], 0.99f);
    expectErrorMentioning([] { boundsForParameter("fog/g/density"); },
                          {"'fog/g/density' cannot be optimised", "media/<medium>/g", "lights/<material>/emission"});
}

}  // namespace
}  // namespace vkdr::test
