#include "diff/unrepresentable_render.h"

#include "image/finite_pixels.h"

namespace vkdr {

std::optional<std::string> unrepresentableRender(const GradientResult& result) {
    for (size_t view = 0; view < result.images.size(); ++view) {
        if (std::optional<std::string> pixel = unrepresentablePixel(result.images[view])) {
            return "the render of view " + std::to_string(view) + ": " + *pixel;
        }
    }
    return std::nullopt;
}

}  // namespace vkdr
