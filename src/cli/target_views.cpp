#include "cli/target_views.h"

#include "core/error.h"
#include "image/image.h"
#include "render/render_settings.h"

namespace vkdr {

TargetView readTarget(const std::string& argument, const Scene& scene) {
    size_t equals = argument.find('=');
    std::string camera = equals == std::string::npos ? "" : argument.substr(0, equals);
    std::string file = equals == std::string::npos ? argument : argument.substr(equals + 1);
    if (scene.cameras.empty()) {
        throw Error("--target " + argument + ": the scene has no camera");
    }
    if (!camera.empty()) {
        std::string cameras;
        bool found = false;
        for (const Camera& candidate : scene.cameras) {
            found = found || candidate.name == camera;
            cameras += (cameras.empty() ? "" : ", ") + candidate.name;
        }
        if (!found) throw Error("--target " + argument + ": no camera '" + camera + "'; cameras: " + cameras);
    }
    Image target;
    try {
        target = readImage(file);
    } catch (const Error& e) {
        throw Error("--target: " + std::string(e.what()));
    }
    // A view renders at its target's size.
    if (target.width > kMaxImageSide || target.height > kMaxImageSide) {
        throw Error("--target " + argument + " is " + std::to_string(target.width) + "x" +
                    std::to_string(target.height) + "; images of at most " + std::to_string(kMaxImageSide) +
                    " pixels a side render");
    }
    return {camera, std::move(target)};
}

}  // namespace vkdr
