// The owners of Vulkan objects and of counted device memory: whatever was made before a
// throw is released, in reverse order, exactly once; a moved-from owner holds nothing.
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "vk/allocation_counter.h"
#include "vk/vulkan_handle.h"

namespace vkdr {
namespace {

// A stand-in for a Vulkan handle type and its destroy entry point, recording each call.
struct FakeObject;
using FakeHandle = FakeObject*;
std::vector<FakeHandle> destroyed;
void recordDestroy(VkDevice, FakeHandle handle, const VkAllocationCallbacks*) {
    destroyed.push_back(handle);
}
void (*fakeDestroy)(VkDevice, FakeHandle, const VkAllocationCallbacks*) = recordDestroy;
using FakeOwner = VulkanHandle<VkDevice, FakeHandle, &fakeDestroy>;

FakeHandle fake(uintptr_t id) {
    return reinterpret_cast<FakeHandle>(id);
}

// Makes two objects and counts 100 bytes, then throws, as a constructor can.
struct ThrowsAfterAcquiring {
    FakeOwner first, second;
    CountedBytes counted;
    explicit ThrowsAfterAcquiring(AllocationCounter& counter)
        : first(VK_NULL_HANDLE, fake(1)), second(VK_NULL_HANDLE, fake(2)), counted(counter, 100) {
        throw std::runtime_error("failed part-way");
    }
};

class VulkanHandleTest : public ::testing::Test {
protected:
    void SetUp() override { destroyed.clear(); }
};

TEST_F(VulkanHandleTest, AThrowPartWayReleasesWhatWasMadeInReverseOrder) {
    AllocationCounter counter;
    EXPECT_THROW(ThrowsAfterAcquiring{counter}, std::runtime_error);
    EXPECT_EQ(destroyed, (std::vector<FakeHandle>{fake(2), fake(1)}));
    EXPECT_EQ(counter.current(), 0u);
    EXPECT_EQ(counter.peak(), 100u);
}

TEST_F(VulkanHandleTest, MovingTransfersOwnership) {
    {
        FakeOwner a(VK_NULL_HANDLE, fake(1));
        FakeOwner b(std::move(a));
        EXPECT_FALSE(a);
        EXPECT_EQ(b.get(), fake(1));
        FakeOwner c(VK_NULL_HANDLE, fake(2));
        c = std::move(b);  // destroys 2, takes 1
        EXPECT_EQ(destroyed, (std::vector<FakeHandle>{fake(2)}));
        EXPECT_EQ(c.get(), fake(1));
    }
    EXPECT_EQ(destroyed, (std::vector<FakeHandle>{fake(2), fake(1)}));
}

TEST_F(VulkanHandleTest, CountedBytesMoveAndRelease) {
    AllocationCounter counter;
    {
        CountedBytes a(counter, 64);
        CountedBytes b(counter, 32);
        EXPECT_EQ(counter.current(), 96u);
        b = std::move(a);  // uncounts b's 32, takes a's 64
        EXPECT_EQ(counter.current(), 64u);
    }
    EXPECT_EQ(counter.current(), 0u);
    EXPECT_EQ(counter.peak(), 96u);
}

}  // namespace
}  // namespace vkdr
