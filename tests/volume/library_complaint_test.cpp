// What OpenVDB says of a damaged file can quote gigabytes it read there; a message keeps
// one bounded line of it.
#include <gtest/gtest.h>

#include <string>

#include "volume/library_complaint.h"

namespace vkdr {
namespace {

TEST(LibraryComplaint, RunsOfSpaceBecomeOneAndTheTextIsCut) {
    EXPECT_EQ(boundedComplaint("KeyError: Map UniformScaleMap is not registered"),
              "KeyError: Map UniformScaleMap is not registered");
    EXPECT_EQ(boundedComplaint("  KeyError:\n\tMap" + std::string(1 << 20, ' ') + "is not registered  "),
              "KeyError: Map is not registered");
    const std::string cut = boundedComplaint("KeyError: Map " + std::string(1 << 20, 'x'));
    EXPECT_EQ(cut.size(), 203u);
    EXPECT_EQ(cut.substr(0, 14), "KeyError: Map ");
    EXPECT_EQ(cut.substr(200), "...");
    EXPECT_EQ(boundedComplaint(std::string(200, 'y')), std::string(200, 'y'));
    EXPECT_EQ(boundedComplaint(""), "");
}

}  // namespace
}  // namespace vkdr
