#include "cli/target_views.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <system_error>

#include "cli/warnings.h"
#include "core/error.h"
#include "core/format_text.h"
#include "image/finite_pixels.h"
#include "image/image.h"
#include "render/camera_setup.h"
#include "render/render_settings.h"

namespace vkdr {
namespace {

std::string cameraList(const Scene& scene) {
    std::string cameras;
    for (const Camera& camera : scene.cameras) cameras += (cameras.empty() ? "" : ", ") + camera.name;
    return cameras;
}

}  // namespace

TargetFile parseTargetArgument(const std::string& argument, const Scene& scene) {
    if (scene.cameras.empty()) {
        throw Error("--target " + argument + ": the scene has no camera");
    }
    const Camera* named = nullptr;
    for (const Camera& camera : scene.cameras) {
        const std::string& name = camera.name;
        bool prefix = argument.size() > name.size() && argument.compare(0, name.size(), name) == 0 &&
                      argument[name.size()] == '=';
        if (prefix && (!named || name.size() > named->name.size())) named = &camera;
    }
    std::error_code error;
    const bool wholeIsFile = std::filesystem::is_regular_file(argument, error);
    if (named) {
        std::string file = argument.substr(named->name.size() + 1);
        if (!wholeIsFile && file.empty()) {
            throw Error("--target " + argument + ": no file after '" + named->name + "='; give CAMERA=FILE");
        }
        if (!wholeIsFile) return {named->name, file};
        if (std::filesystem::is_regular_file(file, error)) {
            throw Error("--target " + argument + ": both the file '" + argument + "' and camera '" + named->name +
                        "' with file '" + file + "'; write ./" + argument + " for the file or " + named->name +
                        "=./" + file + " for the camera");
        }
        return {"", argument};
    }
    size_t equals = argument.find('=');
    if (equals != std::string::npos && !wholeIsFile) {
        throw Error("--target " + argument + ": no camera '" + argument.substr(0, equals) + "' and no file '" +
                    argument + "'; cameras: " + cameraList(scene));
    }
    return {"", argument};
}

namespace {

// A view renders at its target's size, so a target of another shape than the camera's
// aspect ratio widens or narrows the view: its height stays.
void warnOfAnotherAspect(const std::string& argument, const Image& target, const Camera& camera) {
    const double aspect = double(target.width) / double(target.height);
    if (camera.aspectRatio > 0.0f && std::abs(aspect / camera.aspectRatio - 1.0) > 0.01) {
        printWarning(formatText("--target %s is %dx%d (aspect %.4g), but camera '%s' has %s %.4g: the view renders "
                                "at the target's aspect, with the camera's %s",
                                argument.c_str(), target.width, target.height, aspect, camera.name.c_str(),
                                camera.orthographic() ? "xmag / ymag" : "aspectRatio", double(camera.aspectRatio),
                                camera.orthographic() ? "height (ymag)" : "vertical field of view"));
    }
}

}  // namespace

TargetView readTarget(const std::string& argument, const Scene& scene) {
    const TargetFile named = parseTargetArgument(argument, scene);
    const std::string& camera = named.camera;
    const std::filesystem::path& file = named.file;
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
    if (std::optional<std::string> negative = negativePixels(target)) {
        printWarning("--target " + argument + ": " + *negative +
                     "; a render is never negative, so the loss cannot reach 0 there");
    }
    if (lowercaseExtension(file) != ".exr") {
        if (std::optional<std::string> atOne = valuesAtOne(target)) {
            printWarning("--target " + argument + ": " + *atOne +
                         ", the most its format holds; where the scene is brighter the image was clipped, and the "
                         "loss takes 1 there, which biases a fit; give an EXR target");
        }
    }
    warnOfAnotherAspect(argument, target, findCamera(scene, camera));
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
            printWarning("--target " + earlier->second + " and --target " + argument + " both view camera '" +
                         camera + "': the camera is rendered for each, with random numbers of its own, and its "
                                  "loss counts twice");
        }
    }
    return views;
}

}  // namespace vkdr
