#include "volume/nanovdb_grid_extent.h"

#include "core/format_text.h"

namespace vkdr {

void requireGridWithinBuffer(const uint8_t* bytes, uint64_t held) {
    constexpr uint64_t kHeaders = sizeof(nanovdb::GridData) + sizeof(nanovdb::NanoTree<float>::DataType);
    if (held < kHeaders) {
        throw Error(formatText("the grid is damaged (the file gives it %llu bytes, fewer than its headers' %llu)",
                               (unsigned long long)held, (unsigned long long)kHeaders));
    }
    const uint64_t size = reinterpret_cast<const nanovdb::GridData*>(bytes)->mGridSize;
    if (size < kHeaders || size > held) {
        throw Error(formatText("the grid is damaged (its header gives it %llu bytes, the file %llu)",
                               (unsigned long long)size, (unsigned long long)held));
    }
}

}  // namespace vkdr
