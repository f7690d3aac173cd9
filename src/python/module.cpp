// The Python module's native part, vkdiffrender._vkdiffrender: SceneSession as
// vkdiffrender.Scene, images as numpy arrays (docs/python.md). Device work runs with
// Python's lock released and stops on Ctrl-C (python/stop_signal_scope.h).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>

#include "core/error.h"
#include "core/interrupt.h"
#include "image/finite_pixels.h"
#include "image/output_paths.h"
#include "python/scene_session.h"
#include "python/stop_signal_scope.h"

namespace py = pybind11;

namespace vkdr {
namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// Hands the vector's storage to numpy without a copy: the array owns it.
template <typename T>
py::array_t<T> arrayOf(std::vector<T>&& values, std::vector<size_t> shape) {
    auto* owned = new std::vector<T>(std::move(values));
    py::capsule free(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    return py::array_t<T>(shape, owned->data(), free);
}

py::array_t<float> arrayOfImage(Image&& image) {
    const size_t height = size_t(image.height), width = size_t(image.width);
    return arrayOf(std::move(image.rgb), {height, width, 3});
}

std::string shapeText(const std::vector<size_t>& shape) {
    std::string text = "(";
    for (size_t i = 0; i < shape.size(); ++i) {
        text += std::to_string(shape[i]) + (shape.size() == 1 ? "," : i + 1 < shape.size() ? ", " : "");
    }
    return text + ")";
}

std::vector<size_t> shapeOf(const FloatArray& array) {
    return std::vector<size_t>(array.shape(), array.shape() + array.ndim());
}

// An (H, W, 3) array as an Image; `what` names it in errors.
Image imageOfArray(const FloatArray& array, const std::string& what) {
    if (array.ndim() != 3 || array.shape(2) != 3 || array.shape(0) < 1 || array.shape(1) < 1) {
        throw Error(what + " must have shape (height, width, 3), got " + shapeText(shapeOf(array)));
    }
    Image image;
    image.height = int(array.shape(0));
    image.width = int(array.shape(1));
    image.rgb.assign(array.data(), array.data() + array.size());
    return image;
}

RenderSettings settingsOf(uint32_t spp, uint32_t seed, int width, int height, uint32_t maxDepth,
                          const std::string& camera, uint32_t pathsPerPass) {
    if (width < 0 || width > kMaxImageSide || height < 0 || height > kMaxImageSide) {
        throw Error("width and height must be in [1, " + std::to_string(kMaxImageSide) +
                    "], or 0 for the camera's default");
    }
    if (spp < 1 || spp > kMaxSamplesPerPixel) {
        throw Error("spp must be in [1, " + std::to_string(kMaxSamplesPerPixel) + "], got " + std::to_string(spp));
    }
    if (maxDepth > kMaxScatteringVertices) {
        throw Error("max_depth must be in [0, " + std::to_string(kMaxScatteringVertices) + "], got " +
                    std::to_string(maxDepth));
    }
    RenderSettings settings;
    settings.spp = spp;
    settings.seed = seed;
    settings.width = width;
    settings.height = height;
    settings.maxDepth = maxDepth;
    settings.camera = camera;
    settings.pathsPerPass = pathsPerPass;
    return settings;
}

void setParameter(SceneSession& session, const std::string& name, const FloatArray& value) {
    const ParameterInfo info = session.parameter(name);
    std::vector<float> values(value.data(), value.data() + value.size());
    if (value.size() != 1 && shapeOf(value) != info.shape) {
        throw Error(name + ": expected shape " + shapeText(info.shape) + " or one value, got " +
                    shapeText(shapeOf(value)));
    }
    session.set(name, values);
}

py::array_t<float> getParameter(const SceneSession& session, const std::string& name) {
    const ParameterInfo info = session.parameter(name);
    return arrayOf(session.get(name), info.shape);
}

// Each parameter's gradient, shaped as the parameter, by name in the order asked for.
py::dict gradientDictionary(const SceneSession& session, std::vector<ParameterGradient>& gradients) {
    py::dict result;
    for (ParameterGradient& g : gradients) {
        result[py::str(g.name)] = arrayOf(std::move(g.gradient), session.parameter(g.name).shape);
    }
    return result;
}

// The render settings every device call takes, with their defaults (as the CLI's).
#define VKDR_RENDER_ARGUMENTS                                                                              \
    py::kw_only(), py::arg("spp") = 16u, py::arg("seed") = 0u, py::arg("width") = 0, py::arg("height") = 0, \
        py::arg("max_depth") = 8u, py::arg("camera") = "", py::arg("paths_per_pass") = 0u

}  // namespace
}  // namespace vkdr

PYBIND11_MODULE(_vkdiffrender, m) {
    using namespace vkdr;
    m.doc() = "vkdiffrender's native module; import vkdiffrender instead (docs/python.md)";
    m.attr("__version__") = VKDR_VERSION;
    static py::exception<Error> error(m, "Error");
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Error& e) {
            error(e.what());
        } catch (const Interrupted& e) {
            PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
        }
    });

    py::class_<ParameterInfo>(m, "Parameter", "A named scene parameter: its array shape and valid range")
        .def_readonly("name", &ParameterInfo::name)
        .def_property_readonly("shape", [](const ParameterInfo& p) { return py::tuple(py::cast(p.shape)); })
        .def_property_readonly("lower", [](const ParameterInfo& p) { return p.range.lower; })
        .def_property_readonly("upper", [](const ParameterInfo& p) { return p.range.upper; })
        .def("__repr__", [](const ParameterInfo& p) {
            return "Parameter('" + p.name + "', shape=" + shapeText(p.shape) + ", range=[" +
                   py::str(py::float_(p.range.lower)).cast<std::string>() + ", " +
                   py::str(py::float_(p.range.upper)).cast<std::string>() + "])";
        });

    py::class_<SceneSession>(m, "Scene", "A glTF scene loaded onto a Vulkan device")
        .def(py::init([](const std::filesystem::path& file, const std::string& device, bool allowOutsideFiles) {
                 py::gil_scoped_release release;
                 return std::make_unique<SceneSession>(file, device, allowOutsideFiles);
             }),
             py::arg("file"), py::kw_only(), py::arg("device") = "", py::arg("allow_outside_files") = false)
        .def_property_readonly("file", &SceneSession::file)
        .def_property_readonly("warnings", &SceneSession::warnings)
        .def_property_readonly("device", [](const SceneSession& s) { return s.context().description().name; })
        .def("parameters", &SceneSession::parameters)
        .def("parameter", &SceneSession::parameter, py::arg("name"))
        .def("__getitem__", &getParameter, py::arg("name"))
        .def("__setitem__", &setParameter, py::arg("name"), py::arg("value"))
        .def("__contains__", [](const SceneSession& s, const std::string& name) {
            const std::vector<ParameterInfo> all = s.parameters();
            return std::any_of(all.begin(), all.end(), [&](const ParameterInfo& p) { return p.name == name; });
        })
        .def(
            "render",
            [](SceneSession& s, uint32_t spp, uint32_t seed, int width, int height, uint32_t maxDepth,
               const std::string& camera, uint32_t pathsPerPass) {
                const RenderSettings settings = settingsOf(spp, seed, width, height, maxDepth, camera, pathsPerPass);
                Image image;
                {
                    py::gil_scoped_release release;
                    StopSignalScope signals;
                    image = s.render(settings);
                    throwIfInterrupted();
                }
                return arrayOfImage(std::move(image));
            },
            VKDR_RENDER_ARGUMENTS)
        .def(
            "backpropagate",
            [](SceneSession& s, const FloatArray& imageAdjoint, const std::vector<std::string>& names, uint32_t spp,
               uint32_t seed, int width, int height, uint32_t maxDepth, const std::string& camera,
               uint32_t pathsPerPass) {
                const RenderSettings settings = settingsOf(spp, seed, width, height, maxDepth, camera, pathsPerPass);
                const Image adjoint = imageOfArray(imageAdjoint, "the image adjoint");
                std::vector<ParameterGradient> gradients;
                {
                    py::gil_scoped_release release;
                    StopSignalScope signals;
                    gradients = s.backpropagate(settings, adjoint, names);
                    throwIfInterrupted();
                }
                return gradientDictionary(s, gradients);
            },
            py::arg("image_adjoint"), py::arg("parameters"), VKDR_RENDER_ARGUMENTS)
        .def(
            "loss_gradient",
            [](SceneSession& s, const FloatArray& targetArray, const std::vector<std::string>& names,
               const std::string& lossName, uint32_t spp, uint32_t seed, int width, int height, uint32_t maxDepth,
               const std::string& camera, uint32_t pathsPerPass) {
                const RenderSettings settings = settingsOf(spp, seed, width, height, maxDepth, camera, pathsPerPass);
                const Image target = imageOfArray(targetArray, "the target");
                if (lossName != "l2" && lossName != "l1") {
                    throw Error("loss must be \"l2\" or \"l1\", got \"" + lossName + "\"");
                }
                const LossKind loss = lossName == "l2" ? LossKind::L2 : LossKind::L1;
                SceneSession::LossGradient result;
                {
                    py::gil_scoped_release release;
                    StopSignalScope signals;
                    result = s.lossGradient(settings, target, loss, names);
                    throwIfInterrupted();
                }
                return py::make_tuple(result.loss, arrayOfImage(std::move(result.image)),
                                      gradientDictionary(s, result.gradients));
            },
            py::arg("target"), py::arg("parameters"), py::arg("loss") = "l2", VKDR_RENDER_ARGUMENTS)
        .def(
            "write",
            [](const SceneSession& s, const std::filesystem::path& out) {
                py::gil_scoped_release release;
                s.write(out);
            },
            py::arg("path"));

    m.def(
        "read_image",
        [](const std::filesystem::path& file) {
            Image image;
            {
                py::gil_scoped_release release;
                image = readImage(file);
            }
            return arrayOfImage(std::move(image));
        },
        py::arg("path"));
    m.def(
        "write_image",
        [](const std::filesystem::path& file, const FloatArray& array) {
            const Image image = imageOfArray(array, "the image");
            requireOutputFile("write_image", file);
            const std::optional<ImageFileType> type = imageFileTypeOf(file);
            if (!type) {
                throw Error(file.string() + ": the extension sets the file type: .exr (32-bit float linear RGB) "
                            "or .png (8-bit sRGB, clamped to [0, 1])");
            }
            if (std::optional<std::string> bad = unrepresentablePixel(image)) {
                throw Error("the image's " + *bad + "; nothing was written");
            }
            py::gil_scoped_release release;
            if (*type == ImageFileType::Exr) {
                writeExr(file, image);
            } else {
                writePng(file, image);
            }
        },
        py::arg("path"), py::arg("image"));
    m.def(
        "devices",
        []() {
            py::gil_scoped_release release;
            VulkanContext context(ContextOptions{});
            std::vector<std::string> names;
            for (const DeviceDescription& device : context.allDevices()) names.push_back(device.name);
            return names;
        },
        "The Vulkan devices a Scene can be loaded on: pass an index or part of a name as device=");

    // Shown as vkdiffrender.Scene, not as the native module's vkdiffrender._vkdiffrender.Scene.
    for (const char* name : {"Error", "Parameter", "Scene"}) {
        m.attr(name).attr("__module__") = "vkdiffrender";
    }
}
