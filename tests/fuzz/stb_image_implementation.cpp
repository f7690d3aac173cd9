// stb_image compiled from Debian's header into the fuzz targets, so that its decoders
// are instrumented (coverage for libFuzzer, checks for the sanitizers). The definitions
// in the executable take precedence over those of the uninstrumented libstb.
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
