#pragma once
// Whether a .nvdb file's segments lie within it, as their headers describe them, before
// NanoVDB's reader follows those numbers: it reads a grid's name by the size the file
// gives (none at all reads past a buffer of no bytes; an unterminated one reads on past
// it), allocates a grid's buffer by the size the file gives, and seeks past grids by
// their sizes on disk, checking none of them.
#include <filesystem>

namespace vkdr {

// Throws vkdr::Error, naming what is damaged, unless every segment's header and grid
// descriptions lie within `file`, every grid name is terminated, every grid's bytes on
// disk lie within the file, and every grid's size in memory is what those bytes can hold
// (the same bytes uncompressed; at most 1100 times them compressed, deflate's largest
// ratio being 1032 and LZ4's about 255). Leaves a wrong magic number or version to
// NanoVDB's reader, whose messages name them.
void requireSoundNanoVdbLayout(const std::filesystem::path& file);

}  // namespace vkdr
