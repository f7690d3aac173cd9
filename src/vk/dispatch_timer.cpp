#include "vk/dispatch_timer.h"

#include <algorithm>

#include "core/error.h"
#include "vk/context.h"

namespace vkdr {
namespace {

constexpr uint32_t kQueriesPerPool = 256;

uint64_t timestampMask(const VulkanContext& context) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(context.physicalDevice(), &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(context.physicalDevice(), &count, families.data());
    uint32_t bits = families[context.queueFamily()].timestampValidBits;
    return bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
}

}  // namespace

DispatchTimer::DispatchTimer(const VulkanContext& context)
    : device_(context.device()),
      nanosecondsPerTick_(context.properties().limits.timestampPeriod),
      validMask_(timestampMask(context)) {}

DispatchTimer::~DispatchTimer() {
    for (VkQueryPool pool : pools_) {
        vkDestroyQueryPool(device_, pool, nullptr);
    }
}

void DispatchTimer::begin(VkCommandBuffer commands) {
    // A command buffer that was never submitted leaves nothing to collect.
    written_ = 0;
    labels_.clear();
    for (VkQueryPool pool : pools_) {
        vkCmdResetQueryPool(commands, pool, 0, kQueriesPerPool);
    }
    writeTimestamp(commands);
}

void DispatchTimer::afterDispatch(VkCommandBuffer commands, const std::string& pipeline) {
    labels_.push_back({scope_, pipeline});
    writeTimestamp(commands);
}

void DispatchTimer::writeTimestamp(VkCommandBuffer commands) {
    if (written_ == pools_.size() * kQueriesPerPool) {
        // A long command buffer: a fresh pool, reset before its first use.
        VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        info.queryType = VK_QUERY_TYPE_TIMESTAMP;
        info.queryCount = kQueriesPerPool;
        VkQueryPool pool;
        checkVk(vkCreateQueryPool(device_, &info, nullptr, &pool), "vkCreateQueryPool");
        pools_.push_back(pool);
        vkCmdResetQueryPool(commands, pool, 0, kQueriesPerPool);
    }
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pools_[written_ / kQueriesPerPool],
                        written_ % kQueriesPerPool);
    ++written_;
}

void DispatchTimer::collect() {
    std::vector<uint64_t> ticks(written_);
    for (uint32_t first = 0; first < written_; first += kQueriesPerPool) {
        uint32_t count = std::min(kQueriesPerPool, written_ - first);
        checkVk(vkGetQueryPoolResults(device_, pools_[first / kQueriesPerPool], 0, count, count * sizeof(uint64_t),
                                      ticks.data() + first, sizeof(uint64_t),
                                      VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
                "vkGetQueryPoolResults");
    }
    for (size_t i = 0; i < labels_.size(); ++i) {
        uint64_t elapsed = (ticks[i + 1] - ticks[i]) & validMask_;
        milliseconds_[labels_[i].scope][labels_[i].pipeline] += double(elapsed) * nanosecondsPerTick_ * 1e-6;
    }
    labels_.clear();
    written_ = 0;
}

}  // namespace vkdr
