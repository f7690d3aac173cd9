#pragma once
#include "image/image.h"

namespace vkdr {

// |render - target| per pixel and channel, divided by the largest such difference so
// that it shows as white.
struct DifferenceImage {
    Image image;
    float largestDifference = 0.0f;  // the difference that white stands for; 0: identical
};

// A render can be compared with a target of its own size only: vkdr::Error otherwise.
void requireSameSize(const Image& render, const Image& target);

// Throws vkdr::Error when the sizes differ.
DifferenceImage scaledDifference(const Image& render, const Image& target);

}  // namespace vkdr
