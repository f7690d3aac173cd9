#pragma once
#include <array>
#include <cstdint>
#include <span>

namespace vkdr {

// The wavefront stages, in the order a pass runs them, then the loss and the reading of
// the gradients.
enum class Stage { Generate, Intersect, MediumSample, Shade, Shadow, QueuePrepare, Film, Loss, GradientValues };

// Each stage once. Its name is its shader file's stem (shaders/<name>.comp) and is used
// for it everywhere: the pipeline's debug name, the dispatch timer's and the bench's
// key, and the docs. A stage with an adjoint variant is compiled twice from its one
// source, as primal and as adjoint pipeline (specialization constant kAdjoint); the
// others are the same in every pass.
struct StageInfo {
    Stage stage;
    const char* name;
    bool hasAdjointVariant;
};

inline constexpr std::array<StageInfo, 9> kStages{{
    {Stage::Generate, "generate", true},
    {Stage::Intersect, "intersect", false},
    {Stage::MediumSample, "medium_sample", true},
    {Stage::Shade, "shade", true},
    {Stage::Shadow, "shadow", true},
    {Stage::QueuePrepare, "queue_prepare", false},
    {Stage::Film, "film", false},
    {Stage::Loss, "loss", false},
    {Stage::GradientValues, "gradient_values", false},
}};

// stageInfo() indexes the table by stage.
static_assert([] {
    for (size_t i = 0; i < kStages.size(); ++i) {
        if (static_cast<size_t>(kStages[i].stage) != i) return false;
    }
    return true;
}());

constexpr const StageInfo& stageInfo(Stage stage) {
    return kStages[static_cast<size_t>(stage)];
}

// The SPIR-V of a stage's shader.
std::span<const uint32_t> stageSpirv(Stage stage);

}  // namespace vkdr
