#include "render/camera_setup.h"

#include <cmath>
#include <numbers>

#include "core/error.h"
#include "core/format_text.h"
#include "core/setting_names.h"
#include "scene/medium_at.h"
#include "scene/orthographic_view.h"

namespace vkdr {
namespace {

constexpr int kDefaultWidth = 512;

}  // namespace

const Camera& findCamera(const Scene& scene, const std::string& name) {
    requireCamera(scene, "");
    if (name.empty()) {
        return scene.cameras.front();
    }
    std::string names;
    for (const Camera& c : scene.cameras) {
        if (c.name == name) {
            return c;
        }
        names += (names.empty() ? "" : ", ") + c.name;
    }
    throw Error(settingName(Setting::Camera) + " " + name + ": no such camera; the scene has: " + names);
}

void requireCamera(const Scene& scene, const std::string& file) {
    if (scene.cameras.empty()) {
        throw Error((file.empty() ? "" : file + ": ") +
                    "the scene has no camera; for a scene exported from Blender, tick Include > Cameras in the glTF "
                    "exporter, or export it with the vkdiffrender Blender add-on");
    }
}

gpu::GpuCamera setUpCamera(const Scene& scene, const RenderSettings& settings) {
    const Camera& camera = findCamera(scene, settings.camera);
    if (!camera.orthographic() && !(camera.yfov > 0.0f && camera.yfov < std::numbers::pi_v<float>)) {
        throw Error("camera " + camera.name + ": yfov must be in (0, pi), got " + std::to_string(camera.yfov));
    }
    if (settings.width < 0 || settings.height < 0 || settings.width > kMaxImageSide ||
        settings.height > kMaxImageSide) {
        throw Error(imageSizeSettingNames() + " must be between 1 and " + std::to_string(kMaxImageSide));
    }
    float aspect = camera.aspectRatio > 0.0f ? camera.aspectRatio : 1.0f;
    int width = settings.width;
    int height = settings.height;
    if (width > 0 && height > 0) {
        aspect = float(width) / float(height);
    } else if (width > 0) {
        height = std::max(1, int(std::lround(width / aspect)));
    } else if (height > 0) {
        width = std::max(1, int(std::lround(height * aspect)));
    } else {
        width = kDefaultWidth;
        height = std::max(1, int(std::lround(width / aspect)));
    }

    if (width > kMaxImageSide || height > kMaxImageSide) {
        throw Error("camera " + camera.name + ": its aspect ratio " + std::to_string(aspect) + " makes the image " +
                    std::to_string(width) + "x" + std::to_string(height) + ", over " +
                    std::to_string(kMaxImageSide) + " pixels a side; give both " + settingName(Setting::Width) +
                    " and " + settingName(Setting::Height));
    }

    gpu::GpuCamera out{};
    for (int row = 0; row < 3; ++row) {
        out.cameraToWorld[row] = glm::vec4(camera.cameraToWorld[0][row], camera.cameraToWorld[1][row],
                                           camera.cameraToWorld[2][row], camera.cameraToWorld[3][row]);
    }
    out.tanHalfFovY = camera.orthographic() ? 0.0f : std::tan(0.5f * camera.yfov);
    out.orthographicHalfHeight = camera.orthographicHalfHeight;
    out.aspect = aspect;
    out.width = static_cast<uint32_t>(width);
    out.height = static_cast<uint32_t>(height);
    if (camera.orthographic()) {
        // The image's aspect ratio widens or narrows the view, as it does a perspective
        // camera's field of view: the height stays.
        const double halfHeight = camera.orthographicHalfHeight, halfWidth = halfHeight * double(aspect);
        // Rays start at the camera's position plus a point of the view, in floats.
        const double farthestStart = glm::length(glm::dvec3(camera.cameraToWorld[3])) + std::hypot(halfWidth, halfHeight);
        if (!std::isfinite(float(farthestStart))) {
            throw Error(formatText("orthographic camera '%s': its view, %g x %g about the camera (the image's aspect "
                                   "ratio widens it), puts ray origins beyond float range; give it a smaller "
                                   "height, or the image a smaller aspect ratio",
                                   camera.name.c_str(), 2.0 * halfWidth, 2.0 * halfHeight));
        }
        const std::optional<uint32_t> boundary = boundaryAcrossOrthographicView(scene, camera, halfWidth, halfHeight);
        if (boundary) {
            const Material& material = scene.materials[*boundary];
            throw Error(formatText("orthographic camera '%s': the boundary of medium '%s' (material '%s') crosses its "
                                   "view, %g x %g about the camera, where its rays start: they would start in "
                                   "different media, and every ray starts in one; move the camera out of the "
                                   "boundary's way",
                                   camera.name.c_str(), scene.media[size_t(material.interiorMedium)].name.c_str(),
                                   material.name.c_str(), 2.0 * halfWidth, 2.0 * halfHeight));
        }
    }
    int32_t medium = mediumAt(scene, glm::vec3(camera.cameraToWorld[3]));
    out.medium = medium < 0 ? gpu::kNoMediumIndex : static_cast<uint32_t>(medium);
    return out;
}

}  // namespace vkdr
