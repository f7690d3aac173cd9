// How the optimiser loop stops short: a non-finite loss or gradient names the parameter,
// its values and the likely cause (the learning rate only when a step overflowed), and a
// signal leaves a checkpoint of the last finished iteration.
#include <csignal>
#include <limits>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/interrupt.h"
#include "optimize/optimize_loop.h"
#include "quadratic_loss_gradient.h"
#include "scene/parameters.h"

namespace vkdr::test {
namespace {

OptimizeOptions optionsFor(std::vector<std::string> parameters, OptimizerKind optimizer, double learningRate) {
    OptimizeOptions options;
    options.parameters = std::move(parameters);
    options.optimizer = optimizer;
    options.learningRate = learningRate;
    options.iterations = 10;
    return options;
}

std::string stopMessage(LossGradient& loss, Scene& scene, const OptimizeOptions& options) {
    try {
        optimize(loss, scene, options);
    } catch (const Error& error) {
        return error.what();
    }
    ADD_FAILURE() << "no error";
    return "";
}

TEST(LoopStop, ANonFiniteGradientAtOrdinaryValuesBlamesTheRenderNotTheLearningRate) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/sigma_a", {0.1, 0.1, 0.1}}, {"media/fog/g", {0.0}}});
    loss.failFrom(2, "media/fog/g");
    std::string message = stopMessage(loss, scene, optionsFor({"media/fog/sigma_a", "media/fog/g"}, OptimizerKind::Adam, 0.01));
    EXPECT_NE(message.find("iteration 2: the gradient of media/fog/g is nan at media/fog/g = ["), std::string::npos)
        << message;
    EXPECT_NE(message.find("no value is extreme, so the render itself produced it"), std::string::npos) << message;
    EXPECT_EQ(message.find("learning rate"), std::string::npos) << message;
}

TEST(LoopStop, ANonFiniteGradientAtAnExtremeValueNamesThatValue) {
    Scene scene = sceneWithParameters();
    setParameter(scene, "media/fog/sigma_s", std::vector<float>{2e7f, 0.5f, 0.5f});
    QuadraticLossGradient loss({{"media/fog/sigma_a", {0.1, 0.1, 0.1}}, {"media/fog/sigma_s", {0.5, 0.5, 0.5}}});
    loss.failFrom(0, "media/fog/sigma_a");
    std::string message =
        stopMessage(loss, scene, optionsFor({"media/fog/sigma_a", "media/fog/sigma_s"}, OptimizerKind::Sgd, 1e-9));
    EXPECT_NE(message.find("iteration 0: the gradient of media/fog/sigma_a is nan"), std::string::npos) << message;
    EXPECT_NE(message.find("extreme values"), std::string::npos) << message;
    EXPECT_NE(message.find("media/fog/sigma_s = [2e+07, 0.5, 0.5]"), std::string::npos) << message;
    EXPECT_EQ(message.find("learning rate"), std::string::npos) << message;
}

// A loss that is not finite, whatever gradient comes with it.
class InfiniteLoss : public QuadraticLossGradient {
public:
    using QuadraticLossGradient::QuadraticLossGradient;
    GradientResult evaluate(const Scene& scene, uint32_t seed) override {
        GradientResult result = QuadraticLossGradient::evaluate(scene, seed);
        result.loss = std::numeric_limits<double>::infinity();
        return result;
    }
};

// A render beyond float range, as values that each lie in their range can make together
// (an emission grid's voxels times the medium's emission), and so an infinite loss.
class InfiniteRender : public InfiniteLoss {
public:
    using InfiniteLoss::InfiniteLoss;
    GradientResult evaluate(const Scene& scene, uint32_t seed) override {
        GradientResult result = InfiniteLoss::evaluate(scene, seed);
        result.images = {Image{2, 2, std::vector<float>(12, 0.5f)}};
        result.images[0].rgb[9] = std::numeric_limits<float>::infinity();  // pixel (1, 1), channel R
        return result;
    }
};

TEST(LoopStop, AnInfiniteRenderBlamesTheScenesValues) {
    Scene scene = sceneWithParameters();
    InfiniteRender loss({{"media/fog/g", {0.0}}});
    std::string message = stopMessage(loss, scene, optionsFor({"media/fog/g"}, OptimizerKind::Adam, 0.01));
    EXPECT_NE(message.find("iteration 0: the loss is inf at media/fog/g = ["), std::string::npos) << message;
    EXPECT_NE(message.find("the render of view 0: pixel (1, 1) channel R is +infinity: the scene's values, fitted or "
                           "not, make more light than a float holds"),
              std::string::npos)
        << message;
    EXPECT_EQ(message.find("please report"), std::string::npos) << message;
}

TEST(LoopStop, ANonFiniteLossNamesEveryParameterAndItsValues) {
    Scene scene = sceneWithParameters();
    InfiniteLoss loss({{"media/fog/g", {0.0}}});
    std::string message = stopMessage(loss, scene, optionsFor({"media/fog/g"}, OptimizerKind::Adam, 0.01));
    EXPECT_NE(message.find("iteration 0: the loss is inf at media/fog/g = ["), std::string::npos) << message;
    EXPECT_EQ(message.find("learning rate"), std::string::npos) << message;
}

TEST(LoopStop, AStepBeyondFloatRangeSuggestsASmallerLearningRate) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/sigma_s", {1e30, 1e30, 1e30}}});
    std::string message = stopMessage(loss, scene, optionsFor({"media/fog/sigma_s"}, OptimizerKind::Sgd, 1e20));
    EXPECT_NE(message.find("beyond float range"), std::string::npos) << message;
    EXPECT_NE(message.find("try a smaller learning rate"), std::string::npos) << message;
}

// Stands in for SIGINT: sets the flag the handler sets, at a chosen evaluation, and
// throws as the renderer does when it notices it mid-iteration.
class SignalledLoss : public QuadraticLossGradient {
public:
    SignalledLoss(Minima minima, size_t signalAt, bool midIteration)
        : QuadraticLossGradient(std::move(minima)), signalAt_(signalAt), midIteration_(midIteration) {}
    ~SignalledLoss() override { interrupt_detail::signalReceived = 0; }
    GradientResult evaluate(const Scene& scene, uint32_t seed) override {
        if (evaluations_++ == signalAt_) {
            interrupt_detail::signalReceived = SIGINT;
            if (midIteration_) throwIfInterrupted();
        }
        return QuadraticLossGradient::evaluate(scene, seed);
    }

private:
    size_t signalAt_;
    bool midIteration_;
    size_t evaluations_ = 0;
};

void expectCheckpointAfter(bool midIteration, uint32_t finished) {
    Scene scene = sceneWithParameters();
    SignalledLoss loss({{"media/fog/g", {0.5}}}, midIteration ? 3 : 2, midIteration);
    OptimizeOptions options = optionsFor({"media/fog/g"}, OptimizerKind::Adam, 0.01);
    options.checkpointEvery = 0;
    std::optional<LoopState> checkpoint;
    OptimizeCallbacks callbacks;
    callbacks.checkpoint = [&](const LoopState& state) { checkpoint = state; };
    EXPECT_THROW(optimize(loss, scene, options, callbacks), Interrupted);
    ASSERT_TRUE(checkpoint.has_value());
    EXPECT_EQ(checkpoint->iteration, finished);
    EXPECT_EQ(checkpoint->losses.size(), finished);
    ASSERT_EQ(checkpoint->values.size(), 1u);
    EXPECT_EQ(float(checkpoint->values[0]), getParameter(scene, "media/fog/g")[0]);  // what the scene holds
}

TEST(LoopStop, ASignalWithinAnIterationCheckpointsTheLastFinishedOne) {
    expectCheckpointAfter(true, 3);
}

TEST(LoopStop, ASignalBetweenIterationsCheckpointsTheLastFinishedOne) {
    // Raised during evaluation 2, noticed before evaluation 3: iterations 0 to 2 finished.
    expectCheckpointAfter(false, 3);
}

// An experiment's held-out view is rendered by the measure callback, which the signal
// may interrupt as it does the evaluation.
TEST(LoopStop, ASignalWhileMeasuringAnIterationCheckpointsTheLastFinishedOne) {
    Scene scene = sceneWithParameters();
    QuadraticLossGradient loss({{"media/fog/g", {0.5}}});
    OptimizeOptions options = optionsFor({"media/fog/g"}, OptimizerKind::Adam, 0.01);
    options.checkpointEvery = 0;
    std::optional<LoopState> checkpoint;
    OptimizeCallbacks callbacks;
    callbacks.measure = [](const Scene&, uint32_t iteration) {
        if (iteration == 4) {
            interrupt_detail::signalReceived = SIGINT;
            throwIfInterrupted();
        }
        return std::vector<Metric>{};
    };
    callbacks.checkpoint = [&](const LoopState& state) { checkpoint = state; };
    EXPECT_THROW(optimize(loss, scene, options, callbacks), Interrupted);
    interrupt_detail::signalReceived = 0;
    ASSERT_TRUE(checkpoint.has_value());
    EXPECT_EQ(checkpoint->iteration, 4u);
    EXPECT_EQ(checkpoint->losses.size(), 4u);
    ASSERT_EQ(checkpoint->values.size(), 1u);
    EXPECT_EQ(float(checkpoint->values[0]), getParameter(scene, "media/fog/g")[0]);
}

TEST(LoopStop, ASignalBeforeAnyIterationFinishedWritesNoCheckpoint) {
    Scene scene = sceneWithParameters();
    SignalledLoss loss({{"media/fog/g", {0.5}}}, 0, true);
    bool written = false;
    OptimizeCallbacks callbacks;
    callbacks.checkpoint = [&](const LoopState&) { written = true; };
    EXPECT_THROW(optimize(loss, scene, optionsFor({"media/fog/g"}, OptimizerKind::Adam, 0.01), callbacks),
                 Interrupted);
    EXPECT_FALSE(written);
}

}  // namespace
}  // namespace vkdr::test
