// libFuzzer target for the scene loader: glTF JSON (with data URIs) and GLB (with its
// binary chunk). Rejecting an input with vkdr::Error is the expected outcome; anything
// else that escapes, and any crash, leak or sanitizer report, is a bug.
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "fuzz_input_file.h"
#include "scene/load_scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    bool binary = vkdr::fuzz::startsWith(data, size, "glTF");
    try {
        vkdr::loadScene(vkdr::fuzz::writeInputFile(data, size, binary ? "input.glb" : "input.gltf"));
    } catch (const vkdr::Error&) {
    }
    return 0;
}
