#pragma once
// The small rooms the gradient tests differentiate: a diffuse box lit by a ceiling lamp,
// filled with fog or holding a box of smoke.
#include "test_gltf.h"

namespace vkdr::test {

// Walls "walls" (the box from -1 to 1), lamp "lamp" (emission (6, 5, 4)); the camera
// at z = -0.9 looks along +z.
TestGltf room();
// room() filled with the scene-wide medium "fog".
TestGltf foggyRoom();
// room() with the enclosed medium "smoke" in a box on the floor.
TestGltf smokeRoom();

}  // namespace vkdr::test
