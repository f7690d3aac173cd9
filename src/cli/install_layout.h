#pragma once
#include <string>

namespace vkdr {

// Where an installed vkdiffrender keeps its data: relative to the binary (PREFIX/bin),
// so that `cmake --install --prefix P`, the .deb and a moved tree all find it; a binary
// run from the build tree, which has none of it beside it, falls back to the source
// tree's docs and scenes (and for docs, once that tree is gone, to the configured
// install prefix).

// Help texts and errors refer to a guide by its title and file:
// docReference("Optimisation guide", "optimisation.md") gives
// "the Optimisation guide, /usr/share/doc/vkdiffrender/optimisation.md".
std::string docReference(const std::string& title, const std::string& file);

// The shipped scenes: PREFIX/share/vkdiffrender/scenes.
std::string shippedScenesDirectory();

}  // namespace vkdr
