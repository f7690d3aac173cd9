#include "cli/target_views.h"

#include <cstdio>
#include <map>

#include "core/error.h"
#include "image/finite_pixels.h"
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
    // The loss of such a target is NaN or infinite whatever the render.
    if (std::optional<std::string> pixel = unrepresentablePixel(target)) {
        throw Error("--target " + argument + ": " + *pixel);
    }
    return {camera, std::move(target)};
}

std::vector<TargetView> readTargets(const std::vector<std::string>& arguments, const Scene& scene) {
    std::vector<TargetView> views;
    std::map<std::string, std::string> argumentOfCamera;
    for (const std::string& argument : arguments) {
        views.push_back(readTarget(argument, scene));
        const std::string& camera = views.back().camera.empty() ? scene.cameras.front().name : views.back().camera;
        auto [earlier, first] = argumentOfCamera.emplace(camera, argument);
        if (!first) {
            std::fprintf(stderr,
                         "warning: --target %s and --target %s both view camera '%s': the loss compares its one "
                         "render with both\n",
                         earlier->second.c_str(), argument.c_str(), camera.c_str());
        }
    }
    return views;
}

}  // namespace vkdr
