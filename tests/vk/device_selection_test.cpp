// `--device`: digits are an index and only an index; anything else is part of a name.
#include <gtest/gtest.h>

#include "core/error.h"
#include "expect_error.h"
#include "vk/device_selection.h"

namespace vkdr {
namespace {

std::vector<DeviceDescription> devices(std::initializer_list<const char*> names) {
    std::vector<DeviceDescription> result;
    for (const char* name : names) {
        result.push_back({.index = uint32_t(result.size()), .name = name});
    }
    return result;
}

TEST(DeviceNamedBy, DigitsAreAnIndexEvenWhenANameContainsThem) {
    const auto one = devices({"llvmpipe (LLVM 15.0.6, 256 bits)"});
    EXPECT_EQ(deviceNamedBy("0", one), 0u);
    const auto two = devices({"llvmpipe (LLVM 15.0.6, 256 bits)", "NVIDIA H100 80GB HBM3"});
    EXPECT_EQ(deviceNamedBy("1", two), 1u);
    EXPECT_EQ(deviceNamedBy("01", two), 1u);
    EXPECT_EQ(deviceNamedBy("15", devices({"A", "B", "C", "D", "E", "F", "G", "H", "I", "J", "K", "L", "M", "N",
                                           "O", "P", "device 15"})),
              15u);
}

TEST(DeviceNamedBy, AnIndexOutOfRangeNamesTheDevices) {
    const auto one = devices({"llvmpipe (LLVM 15.0.6, 256 bits)"});
    for (const char* request : {"1", "5", "99999999999999999999999"}) {
        SCOPED_TRACE(request);
        test::expectErrorMentioning([&] { deviceNamedBy(request, one); },
                                    {"--device " + std::string(request), "no device has that index",
                                     "[0] llvmpipe (LLVM 15.0.6, 256 bits)"});
    }
}

TEST(DeviceNamedBy, AnythingElseIsPartOfAName) {
    const auto two = devices({"llvmpipe (LLVM 15.0.6, 256 bits)", "NVIDIA H100 80GB HBM3"});
    EXPECT_EQ(deviceNamedBy("H100", two), 1u);
    EXPECT_EQ(deviceNamedBy("llvm", two), 0u);
    EXPECT_EQ(deviceNamedBy("15.0", two), 0u);  // not only digits: a name
    test::expectErrorMentioning([&] { deviceNamedBy("radeon", two); },
                                {"--device radeon", "'radeon'", "[0] llvmpipe", "[1] NVIDIA H100 80GB HBM3"});
}

}  // namespace
}  // namespace vkdr
