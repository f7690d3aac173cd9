// tinygltf's implementation, compiled from Debian's header for sanitizer and fuzz builds
// (VKDR_TINYGLTF_FROM_HEADER), so that its parser is instrumented like our own code.
// Normal builds link Debian's libtinygltf instead. stb_image comes from libstb either way.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
