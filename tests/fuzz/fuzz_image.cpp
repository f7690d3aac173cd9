// libFuzzer target for target-image reading: OpenEXR, and PNG or JPEG through stb_image.
// Rejecting an input with vkdr::Error is the expected outcome; anything else that
// escapes, and any crash, leak or sanitizer report, is a bug.
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "fuzz_input_file.h"
#include "image/image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // OpenEXR's magic number is 0x762f3101, little-endian.
    bool exr = vkdr::fuzz::startsWith(data, size, "\x76\x2f\x31\x01");
    try {
        vkdr::readImage(vkdr::fuzz::writeInputFile(data, size, exr ? "input.exr" : "input.png"));
    } catch (const vkdr::Error&) {
    }
    return 0;
}
