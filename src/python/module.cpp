// The Python module's native part, vkdiffrender._vkdiffrender: SceneSession as
// vkdiffrender.Scene, images as numpy arrays (docs/python.md). Device work runs with
// Python's lock released and stops on Ctrl-C (python/stop_signal_scope.h).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/setting_names.h"
#include "image/finite_pixels.h"
#include "image/output_paths.h"
#include "python/constructed_instance_caster.h"
#include "python/released_python_lock.h"
#include "python/scene_session.h"
#include "python/stop_signal_scope.h"
#include "render/cut_paths.h"
#include "scene/parameters.h"

namespace py = pybind11;

VKDR_REFUSE_UNCONSTRUCTED_INSTANCES(vkdr::SceneSession, "make a Scene with vkdiffrender.Scene(file)")
VKDR_REFUSE_UNCONSTRUCTED_INSTANCES(vkdr::ParameterInfo, "a Parameter comes from Scene.parameter(name)")

namespace vkdr {
namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// Whether Ctrl-C stops device work that this call waits for: on the main thread, where
// Python handles signals, while SIGINT raises KeyboardInterrupt (Python's default). A
// handler of the user's own is left to run as Python runs it, once the call returns.
bool ctrlCStopsTheWork() {
    const py::module_ threading = py::module_::import("threading");
    if (!threading.attr("current_thread")().is(threading.attr("main_thread")())) return false;
    const py::module_ signal = py::module_::import("signal");
    return signal.attr("getsignal")(signal.attr("SIGINT")).is(signal.attr("default_int_handler"));
}

// Runs `work` with Python's lock released; Ctrl-C stops it with KeyboardInterrupt where
// ctrlCStopsTheWork. Must be entered with the lock held.
template <typename Work>
auto runOnDevice(Work work) {
    const bool stopOnCtrlC = ctrlCStopsTheWork();
    ReleasedPythonLock released;
    StopSignalScope signals(stopOnCtrlC);
    auto result = work();
    throwIfInterrupted();
    return result;
}

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

// Refuses a finite value of a wider float array that float32 cannot hold (numpy would
// make it an infinity, with a warning), naming `what` and the value as the scene
// loader does.
void requireWithinFloatRange(const py::array& numbers, const std::string& what) {
    if (numbers.dtype().kind() != 'f' || numbers.dtype().itemsize() <= 4) {
        return;
    }
    // The least magnitude that rounds to an infinite float: FLT_MAX plus half its ulp.
    const double overflow = std::ldexp(1.0, 128) - std::ldexp(1.0, 103);
    const py::module_ numpy = py::module_::import("numpy");
    const py::object flat = numbers.attr("reshape")(-1);
    const py::object beyond = numpy.attr("logical_and")(
        numpy.attr("isfinite")(flat), numpy.attr("greater_equal")(numpy.attr("abs")(flat), overflow));
    if (py::cast<bool>(numpy.attr("any")(beyond))) {
        // numpy's text of the value: a long double's may lie beyond a double's range too.
        const py::object index = numpy.attr("argmax")(beyond);
        const std::string first = py::str(flat[index]);
        throw Error(what + ": " + whichValue(index.cast<size_t>(), size_t(numbers.size())) + "must be finite, got " +
                    first + ": beyond float range (magnitude at most 3.4e+38)");
    }
}

// Whether every element of an array of objects is a real number: numbers.Real (an
// integer beyond 64 bits, a Fraction), a number that is not complex (a Decimal), or
// numpy's bool; not None, a complex number, or one of numpy's times.
bool allRealNumbers(const py::array& objects) {
    const py::module_ numbers = py::module_::import("numbers");
    const py::module_ numpy = py::module_::import("numpy");
    for (const py::handle item : objects.attr("flat")) {
        if (py::isinstance(item, numpy.attr("datetime64")) || py::isinstance(item, numpy.attr("timedelta64"))) {
            return false;
        }
        const bool real = py::isinstance(item, numbers.attr("Real")) || py::isinstance(item, numpy.attr("bool_")) ||
                          (py::isinstance(item, numbers.attr("Number")) &&
                           !py::isinstance(item, numbers.attr("Complex")));
        if (!real) return false;
    }
    return true;
}

// Refuses, naming `what`, a finite element of an array of real-number objects whose
// magnitude a float cannot hold (an integer, Fraction or Decimal may lie beyond a
// double's range too, where numpy's conversion would fail or give infinity).
void requireObjectsWithinFloatRange(const py::array& objects, const std::string& what) {
    const py::module_ numbers = py::module_::import("numbers");
    const py::module_ math = py::module_::import("math");
    const py::float_ overflow(std::ldexp(1.0, 128) - std::ldexp(1.0, 103));
    const py::object abs = py::module_::import("builtins").attr("abs");
    size_t index = 0;
    for (const py::handle item : objects.attr("flat")) {
        const size_t position = index++;
        const bool finite = py::isinstance(item, numbers.attr("Rational"))
                                ? true
                                : py::hasattr(item, "is_finite") ? py::cast<bool>(item.attr("is_finite")())
                                                                 : py::cast<bool>(math.attr("isfinite")(item));
        // NaN and infinities are named once they are floats; comparing a Decimal NaN raises.
        if (!finite) continue;
        // Python compares integers, Fractions and Decimals with a float exactly.
        const py::object magnitude = abs(item);
        const int beyond = PyObject_RichCompareBool(magnitude.ptr(), overflow.ptr(), Py_GE);
        if (beyond < 0) throw py::error_already_set();
        if (beyond == 1) {
            std::string text = py::str(item);
            if (text.size() > 40) text = text.substr(0, 20) + "... (" + std::to_string(text.size()) + " digits)";
            throw Error(what + ": " + whichValue(position, size_t(objects.size())) + "must be finite, got " + text +
                        ": beyond float range (magnitude at most 3.4e+38)");
        }
    }
}

// Numbers as numpy makes float32 of them. Refused, with a TypeError naming `what`: None
// (numpy would make it NaN), text (numpy would parse "0.1"), complex numbers (numpy
// would drop their imaginary part), a masked array (numpy would take its masked values),
// and what numpy cannot make an array of numbers of,
// with numpy's or PyTorch's reason (a tensor that requires grad, say); with a
// vkdiffrender.Error, values beyond float's range.
// `requireShape` checks the array's shape before its values are read or converted, so
// that a wrong shape is refused however large the array (a broadcast view of terabytes).
FloatArray floatArrayOf(const py::object& value, const std::string& what,
                        const std::function<void(const std::vector<size_t>&)>& requireShape) {
    auto refuse = [&](const std::string& got) { throw py::type_error(what + ": expected numbers, got " + got); };
    if (value.is_none()) refuse("None");
    if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) || py::isinstance<py::bytearray>(value)) {
        refuse("text");
    }
    py::array numbers;
    const py::object numpy = py::module_::import("numpy");
    // numpy.asarray takes a masked array's hidden values as they are.
    if (py::isinstance(value, numpy.attr("ma").attr("MaskedArray"))) {
        refuse("a masked array (its masked values would be taken; pass numpy.ma.filled(value, fill) or its data)");
    }
    try {
        numbers = numpy.attr("asarray")(value);
        // Integers beyond 64 bits, Fractions and Decimals make arrays of objects, which
        // are numbers all the same.
        if (numbers.dtype().kind() == 'O' && allRealNumbers(numbers)) {
            requireObjectsWithinFloatRange(numbers, what);
            numbers = numpy.attr("asarray")(numbers, numpy.attr("float64"));
        }
    } catch (py::error_already_set& error) {
        refuse(std::string(py::str(value.get_type().attr("__name__"))) + " (" +
               std::string(py::str(error.type().attr("__name__"))) + ": " + std::string(py::str(error.value())) +
               ")");
    }
    const char kind = numbers.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b') {
        refuse("an array of dtype " + std::string(py::str(numbers.dtype())));
    }
    requireShape(std::vector<size_t>(numbers.shape(), numbers.shape() + numbers.ndim()));
    requireWithinFloatRange(numbers, what);
    return FloatArray(numbers);
}

// An (H, W, 3) array as an Image; `what` names it in errors. One that stands for a
// render (an image adjoint, a target) is no larger than a render.
Image imageOfArray(const py::object& value, const std::string& what, bool ofARender) {
    const FloatArray array = floatArrayOf(value, what, [&](const std::vector<size_t>& shape) {
        if (shape.size() != 3 || shape[2] != 3 || shape[0] < 1 || shape[1] < 1) {
            throw Error(what + " must have shape (height, width, 3), got " + shapeText(shape));
        }
        if (ofARender && (shape[0] > size_t(kMaxImageSide) || shape[1] > size_t(kMaxImageSide))) {
            throw Error(what + " of shape " + shapeText(shape) + " is larger than any image rendered (" +
                        std::to_string(kMaxImageSide) + " pixels a side)");
        }
    });
    Image image;
    image.height = int(array.shape(0));
    image.width = int(array.shape(1));
    image.rgb.assign(array.data(), array.data() + array.size());
    return image;
}

// "ValueError: boom" for the Python exception `error` holds, without its traceback.
std::string pythonErrorText(const py::error_already_set& error) {
    return std::string(py::str(error.type().attr("__name__"))) + ": " + std::string(py::str(error.value()));
}

// Python's or numpy's bool: an integer to Python, a mistake as a count or an index.
bool isBool(const py::object& value) {
    return py::isinstance<py::bool_>(value) || py::isinstance(value, py::module_::import("numpy").attr("bool_"));
}

// True or False (or numpy's): what Python would take as true (0.5, 2, a string) is a
// TypeError naming the keyword, as a float is for an integer keyword.
bool flag(const char* keyword, const py::object& value) {
    if (!isBool(value)) {
        throw py::type_error(std::string(keyword) + ": expected True or False, got " +
                             std::string(py::str(value.get_type().attr("__name__"))));
    }
    return value.cast<bool>();
}

// The command line's check of an integer option (cli/number_options.h), with the
// keyword's name where the command line names its option. An int, or what Python takes
// as one (a numpy integer): a float or a bool is a TypeError, not truncated.
uint32_t integerIn(const char* keyword, const py::object& value, int64_t low, int64_t high,
                   const std::string& kind = "") {
    if (isBool(value) || !PyIndex_Check(value.ptr())) {
        throw py::type_error(std::string(keyword) + ": expected an integer, got " +
                             std::string(py::str(value.get_type().attr("__name__"))));
    }
    const auto number = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
    if (!number) {
        // What claims to be an integer and is not one (a numpy array of several, or of one
        // element and a shape): numpy's own message would not name the keyword.
        const py::error_already_set error;
        throw py::type_error(std::string(keyword) + ": expected an integer, got " +
                             std::string(py::str(value.get_type().attr("__name__"))) + " (" +
                             pythonErrorText(error) + ")");
    }
    auto below = [&](int64_t bound) {
        return PyObject_RichCompareBool(number.ptr(), py::int_(bound).ptr(), Py_LT) == 1;
    };
    auto above = [&](int64_t bound) {
        return PyObject_RichCompareBool(number.ptr(), py::int_(bound).ptr(), Py_GT) == 1;
    };
    if (below(low) || above(high)) {
        const std::string expected =
            kind.empty() ? "an integer from " + std::to_string(low) + " to " + std::to_string(high) : kind;
        throw Error(std::string(keyword) + ": must be " + expected + ", got " + std::string(py::str(number)));
    }
    return uint32_t(number.cast<int64_t>());
}

// The keywords every device call takes, with the command line's defaults.
struct RenderKeywords {
    py::object spp, seed, width, height, maxDepth, camera, pathsPerPass, equiangular;

    RenderSettings settings() const {
        RenderSettings settings;
        settings.spp = integerIn("spp", spp, 1, kMaxSamplesPerPixel);
        constexpr int64_t kMaxSeed = std::numeric_limits<uint32_t>::max();
        settings.seed = integerIn("seed", seed, 0, kMaxSeed,
                                  "a 32-bit unsigned integer (0.." + std::to_string(kMaxSeed) + ")");
        settings.width = int(integerIn("width", width, 0, kMaxImageSide));
        settings.height = int(integerIn("height", height, 0, kMaxImageSide));
        settings.maxDepth = integerIn("max_depth", maxDepth, 0, kMaxScatteringVertices);
        if (!py::isinstance<py::str>(camera)) {
            throw py::type_error("camera: expected a camera's name (\"\" for the scene's first), got " +
                                 std::string(py::str(camera.get_type().attr("__name__"))));
        }
        settings.camera = camera.cast<std::string>();
        settings.pathsPerPass = integerIn("paths_per_pass", pathsPerPass, 0, 1 << 21);
        settings.equiangularSampling = flag("equiangular", equiangular);
        return settings;
    }
};

#define VKDR_RENDER_KEYWORDS                                                                                \
    py::kw_only(), py::arg("spp") = 16, py::arg("seed") = 0, py::arg("width") = 0, py::arg("height") = 0, \
        py::arg("max_depth") = 8, py::arg("camera") = "", py::arg("paths_per_pass") = 0,              \
        py::arg("equiangular") = true

#define VKDR_RENDER_KEYWORD_PARAMETERS                                                                 \
    const py::object &spp, const py::object &seed, const py::object &width, const py::object &height, \
        const py::object &maxDepth, const py::object &camera, const py::object &pathsPerPass,          \
        const py::object &equiangular

#define VKDR_RENDER_KEYWORD_VALUES \
    RenderKeywords { spp, seed, width, height, maxDepth, camera, pathsPerPass, equiangular }

// The session's calls wait for another thread's render to finish: with Python's lock
// released, so that other threads go on meanwhile, and as device work, so that Ctrl-C
// stops that render and the wait.
ParameterInfo parameterInfo(const SceneSession& session, const std::string& name) {
    return runOnDevice([&] { return session.parameter(name); });
}

std::vector<ParameterInfo> allParameters(const SceneSession& session) {
    return runOnDevice([&] { return session.parameters(); });
}

// Each parameter's gradient, shaped as the parameter, by name in the order asked for.
py::dict gradientDictionary(const SceneSession& session, std::vector<ParameterGradient>& gradients) {
    py::dict result;
    for (ParameterGradient& g : gradients) {
        result[py::str(g.name)] = arrayOf(std::move(g.gradient), parameterInfo(session, g.name).shape);
    }
    return result;
}

// Names arrive as py::str, not std::string, which pybind11 would also fill from bytes:
// a name is a str, as in the lists of names and the keys of the gradients' dicts.
void setParameter(SceneSession& session, const py::str& nameText, const py::object& value) {
    const std::string name(nameText);
    const ParameterInfo info = parameterInfo(session, name);
    const FloatArray array = floatArrayOf(value, name, [&](const std::vector<size_t>& shape) {
        const bool oneValue = std::all_of(shape.begin(), shape.end(), [](size_t side) { return side == 1; });
        if (!oneValue && shape != info.shape) {
            throw Error(name + ": expected shape " + shapeText(info.shape) + " or one value, got " +
                        shapeText(shape));
        }
    });
    std::vector<float> values(array.data(), array.data() + array.size());
    runOnDevice([&] {
        session.set(name, values);
        return true;
    });
}

py::array_t<float> getParameter(const SceneSession& session, const py::str& nameText) {
    const std::string name(nameText);
    const ParameterInfo info = parameterInfo(session, name);
    return arrayOf(runOnDevice([&] { return session.get(name); }), info.shape);
}

// A RuntimeWarning, as the command line warns, when paths of the call were cut short.
void warnOfCutPaths(uint64_t paths) {
    if (paths > 0 && PyErr_WarnEx(PyExc_RuntimeWarning, cutPathsMessage(paths, "the render").c_str(), 1) != 0) {
        throw py::error_already_set();  // warnings turned into errors
    }
}

py::array_t<float> render(SceneSession& session, const RenderKeywords& keywords) {
    const RenderSettings settings = keywords.settings();
    SceneSession::Rendered rendered = runOnDevice([&] { return session.render(settings); });
    warnOfCutPaths(rendered.cutPaths);
    return arrayOfImage(std::move(rendered.image));
}

// The parameters' names: a list (or other iterable) of str. A lone str is refused rather
// than taken as the names of its characters.
std::vector<std::string> parameterNamesOf(const py::object& names) {
    if (py::isinstance<py::str>(names) || py::isinstance<py::bytes>(names)) {
        throw py::type_error("parameters: expected a list of names, got " +
                             std::string(py::str(names.get_type().attr("__name__"))) + " (a list of one name: [" +
                             std::string(py::repr(names)) + "])");
    }
    if (!py::isinstance<py::iterable>(names)) {
        throw py::type_error("parameters: expected a list of names, got " +
                             std::string(py::str(names.get_type().attr("__name__"))));
    }
    std::vector<std::string> result;
    for (const py::handle name : names) {
        if (!py::isinstance<py::str>(name)) {
            throw py::type_error("parameters: a name must be a str, got " +
                                 std::string(py::str(name.get_type().attr("__name__"))));
        }
        result.push_back(name.cast<std::string>());
    }
    return result;
}

py::dict backpropagate(SceneSession& session, const py::object& imageAdjoint, const py::object& parameters,
                       const RenderKeywords& keywords) {
    const std::vector<std::string> names = parameterNamesOf(parameters);
    const RenderSettings settings = keywords.settings();
    const Image adjoint = imageOfArray(imageAdjoint, "the image adjoint", true);
    SceneSession::Backpropagated result = runOnDevice([&] { return session.backpropagate(settings, adjoint, names); });
    warnOfCutPaths(result.cutPaths);
    return gradientDictionary(session, result.gradients);
}

py::tuple lossGradient(SceneSession& session, const py::object& targetArray, const py::object& parameters,
                       const py::str& lossText, const RenderKeywords& keywords) {
    const std::string lossName(lossText);
    const std::vector<std::string> names = parameterNamesOf(parameters);
    const RenderSettings settings = keywords.settings();
    const Image target = imageOfArray(targetArray, "the target", true);
    if (lossName != "l2" && lossName != "l1") {
        throw Error("loss: " + lossName + " not in {l2,l1}");
    }
    const LossKind loss = lossName == "l2" ? LossKind::L2 : LossKind::L1;
    SceneSession::LossGradient result =
        runOnDevice([&] { return session.lossGradient(settings, target, loss, names); });
    warnOfCutPaths(result.cutPaths);
    return py::make_tuple(result.loss, arrayOfImage(std::move(result.image)),
                          gradientDictionary(session, result.gradients));
}

void writeImage(const std::filesystem::path& file, const py::object& array) {
    const Image image = imageOfArray(array, "the image", false);
    requireOutputFile("write_image", file);
    const std::optional<ImageFileType> type = imageFileTypeOf(file);
    if (!type) {
        throw Error(file.string() + ": the extension sets the file type: .exr (32-bit float linear RGB) "
                    "or .png (8-bit sRGB, clamped to [0, 1])");
    }
    if (std::optional<std::string> bad = unrepresentablePixel(image)) {
        throw Error("the image's " + *bad + "; nothing was written");
    }
    ReleasedPythonLock released;
    if (*type == ImageFileType::Exr) {
        writeExr(file, image);
    } else {
        writePng(file, image);
    }
}

void bindParameter(py::module_& m) {
    py::class_<ParameterInfo>(m, "Parameter", "A named scene parameter: its array shape and valid range.")
        .def_readonly("name", &ParameterInfo::name, "media/<medium>/sigma_a and so on")
        .def_property_readonly(
            "shape", [](const ParameterInfo& p) { return py::tuple(py::cast(p.shape)); },
            "(3,) for RGB, (1,) for g, (height, width, 3) for a base colour texture, (z, y, x) for a density or "
            "emission grid's voxels, (z, y, x, 3) for an albedo grid's")
        .def_property_readonly(
            "lower", [](const ParameterInfo& p) { return p.range.lower; }, "the smallest valid value")
        .def_property_readonly(
            "upper", [](const ParameterInfo& p) { return p.range.upper; }, "the largest valid value (inf: none)")
        .def_property_readonly(
            "aliases", [](const ParameterInfo& p) { return py::tuple(py::cast(p.aliases)); },
            "the other names of the same values: the base colour textures of materials that share this one's "
            "texture")
        .def("__repr__", [](const ParameterInfo& p) {
            return "Parameter(" + py::repr(py::str(p.name)).cast<std::string>() + ", shape=" + shapeText(p.shape) +
                   ", range=[" +
                   py::str(py::float_(p.range.lower)).cast<std::string>() + ", " +
                   py::str(py::float_(p.range.upper)).cast<std::string>() + "])";
        });
}

// The command line's --device text for `device`: an index (an int or a numpy integer, as
// the command line's digits) or part of a device's name.
std::string deviceSelector(const py::object& device) {
    if (!isBool(device) && !py::isinstance<py::str>(device) && PyIndex_Check(device.ptr())) {
        const auto number = py::reinterpret_steal<py::object>(PyNumber_Index(device.ptr()));
        if (!number) {
            const py::error_already_set error;
            throw py::type_error("device: expected an index or part of a device's name, got " +
                                 std::string(py::str(device.get_type().attr("__name__"))) + " (" +
                                 pythonErrorText(error) + ")");
        }
        const std::string index = py::str(number);
        if (index.starts_with('-')) {
            throw Error("device: an index is at least 0, got " + index + " (vkdiffrender.devices() lists them)");
        }
        return index;
    }
    if (py::isinstance<py::str>(device)) return device.cast<std::string>();
    throw py::type_error("device: expected an index or part of a device's name, got " +
                         std::string(py::str(device.get_type().attr("__name__"))));
}

void bindScene(py::module_& m) {
    py::class_<SceneSession>(m, "Scene", "A glTF scene loaded onto a Vulkan device (docs/python.md).")
        .def(py::init([](const std::filesystem::path& file, const py::object& device,
                         const py::object& allowOutsideFiles) {
                 const std::string selector = deviceSelector(device);
                 const bool outside = flag("allow_outside_files", allowOutsideFiles);
                 ReleasedPythonLock released;
                 return std::make_unique<SceneSession>(file, selector, outside);
             }),
             py::arg("file"), py::kw_only(), py::arg("device") = "", py::arg("allow_outside_files") = false,
             "Loads a .gltf or .glb. device: an index or part of a name (vkdiffrender.devices()); "
             "allow_outside_files: let the scene read files outside its own directory.")
        .def_property_readonly("file", &SceneSession::file, "The absolute path the scene was loaded from")
        .def("__repr__",
             [](const SceneSession& s) {
                 return "<vkdiffrender.Scene " + py::repr(py::str(s.file().string())).cast<std::string>() + " on " +
                        s.context().description().name + ">";
             })
        .def_property_readonly("warnings", &SceneSession::warnings, "What the loader ignored or approximated")
        .def_property_readonly(
            "device", [](const SceneSession& s) { return s.context().description().name; },
            "The name of the Vulkan device the scene renders on")
        .def("parameters", &allParameters, "Every named parameter, as Parameter objects")
        .def(
            "parameter", [](const SceneSession& s, const py::str& name) { return parameterInfo(s, std::string(name)); },
            py::arg("name"), "One named parameter, as a Parameter")
        .def("__getitem__", &getParameter, py::arg("name"), "A copy of the parameter's values, float32")
        .def("__setitem__", &setParameter, py::arg("name"), py::arg("value"),
             "Sets a parameter: one value sets every channel (and texel), else the parameter's exact shape")
        .def(
            "__contains__",
            [](const SceneSession& s, const py::str& nameText) {
                const std::string name(nameText);
                const std::vector<ParameterInfo> all = allParameters(s);
                return std::any_of(all.begin(), all.end(), [&](const ParameterInfo& p) { return p.name == name; });
            },
            py::arg("name"), "Whether the scene has a parameter of that name")
        .def(
            "render", [](SceneSession& s, VKDR_RENDER_KEYWORD_PARAMETERS) { return render(s, VKDR_RENDER_KEYWORD_VALUES); },
            VKDR_RENDER_KEYWORDS,
            "Renders the camera; returns an (H, W, 3) float32 array of linear RGB. The same seed and settings "
            "give the same image bit for bit, the image of `vkdiffrender render`.")
        .def(
            "backpropagate",
            [](SceneSession& s, const py::object& adjoint, const py::object& names, VKDR_RENDER_KEYWORD_PARAMETERS) {
                return backpropagate(s, adjoint, names, VKDR_RENDER_KEYWORD_VALUES);
            },
            py::arg("image_adjoint"), py::arg("parameters"), VKDR_RENDER_KEYWORDS,
            "dLoss/dparameter for each named parameter, given dLoss/dI (an (H, W, 3) array) of the image "
            "render() gives with the same keywords; a dict of float64 arrays shaped as the parameters. The "
            "paths are replayed with random numbers independent of that image's (docs/python.md).")
        .def(
            "loss_gradient",
            [](SceneSession& s, const py::object& target, const py::object& names, const py::str& loss,
               VKDR_RENDER_KEYWORD_PARAMETERS) {
                return lossGradient(s, target, names, loss, VKDR_RENDER_KEYWORD_VALUES);
            },
            py::arg("target"), py::arg("parameters"), py::arg("loss") = "l2", VKDR_RENDER_KEYWORDS,
            "The command line's loss (\"l2\" or \"l1\") against target and its gradient, as `vkdiffrender grad`: "
            "returns (loss, image, gradients).")
        .def(
            "write",
            [](const SceneSession& s, const std::filesystem::path& out) {
                ReleasedPythonLock released;
                s.write(out);
            },
            py::arg("path"),
            "Writes the scene with the current parameter values as a .gltf, as `vkdiffrender optimize` does; "
            "never over the scene or a file it reads.");
}

void bindFunctions(py::module_& m) {
    m.def(
        "read_image",
        [](const std::filesystem::path& file) {
            Image image;
            {
                ReleasedPythonLock released;
                image = readImage(file);
            }
            // As a --target is read: a loss against such an image is NaN or infinite.
            if (std::optional<std::string> bad = unrepresentablePixel(image)) {
                throw Error(file.string() + ": " + *bad);
            }
            return arrayOfImage(std::move(image));
        },
        py::arg("path"),
        "Reads an EXR (linear), PNG or JPEG (sRGB, decoded to linear) as an (H, W, 3) float32 array; refuses NaN, "
        "infinite and larger than 1e18 pixels.");
    m.def("write_image", &writeImage, py::arg("path"), py::arg("image"),
          "Writes an (H, W, 3) array as .exr (32-bit float linear RGB) or .png (8-bit sRGB, clamped to [0, 1]), "
          "atomically; refuses NaN and infinite pixels.");
    m.def(
        "devices",
        []() {
            ReleasedPythonLock released;
            VulkanContext context(ContextOptions{});
            std::vector<std::string> names;
            for (const DeviceDescription& device : context.allDevices()) names.push_back(device.name);
            return names;
        },
        "The Vulkan devices a Scene can be loaded on, in index order: pass an index or part of a name as device=.");
}

}  // namespace

}  // namespace vkdr

PYBIND11_MODULE(_vkdiffrender, m) {
    using namespace vkdr;
    m.doc() = "vkdiffrender's native module; import vkdiffrender instead (docs/python.md)";
    m.attr("__version__") = VKDR_VERSION;
    settingSpelling() = SettingSpelling::PythonKeywords;  // errors name the keywords, not the options
    finishModuleWorkAtExit();
    static py::exception<Error> error(m, "Error");
    error.doc() = "What vkdiffrender refuses or cannot do: a file it cannot read, a value out of range, an "
                  "unknown name; the message names what is at fault";
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Error& e) {
            error(e.what());
        } catch (const Interrupted& e) {
            PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
        }
    });
    bindParameter(m);
    bindScene(m);
    bindFunctions(m);
    // Shown as vkdiffrender.Scene, not as the native module's vkdiffrender._vkdiffrender.Scene.
    for (const char* name : {"Error", "Parameter", "Scene"}) {
        m.attr(name).attr("__module__") = "vkdiffrender";
    }
}
