"""Bad input raises vkdiffrender.Error with the command line's message and leaves the
interpreter (and the scene) usable; Ctrl-C interrupts a render; the device works with
Python's lock released."""
import json
import os
import re
import select
import signal
import subprocess
import sys
import threading
import time
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest
import vkdiffrender
from conftest import SCENES
from textured_scene import write_textured_fog_scene

WIDTH = 16
MALFORMED = SCENES.parent / "tests" / "cli" / "data" / "malformed"


@pytest.fixture(scope="module")
def scene(fog_scene_file):
    return vkdiffrender.Scene(fog_scene_file)


def cli_error(cli, *arguments):
    """The message the command line prints after 'error: ', which must exit with 2, without
    the pointer to the command's --help that a usage error ends with (the module has none)."""
    result = subprocess.run([cli, *arguments], capture_output=True, text=True)
    assert result.returncode == 2, result.stderr
    line = next(line for line in result.stderr.splitlines() if line.startswith("error: "))
    return re.sub(r"; see 'vkdiffrender [a-z]+ --help'$", "", line.removeprefix("error: "))


def test_messages_are_the_command_lines(cli, fog_scene_file, tmp_path):
    for missing in [tmp_path / "missing.gltf", ""]:
        with pytest.raises(vkdiffrender.Error) as raised:
            vkdiffrender.Scene(missing)
        assert str(raised.value) == cli_error(cli, "render", str(missing), "-o", str(tmp_path / "a.exr"))
    scene = vkdiffrender.Scene(fog_scene_file)
    for assignment in ["media/smoke/sigma_a=1", "media/fog/g=1.5", "media/fog/sigma_a=-1"]:
        name, value = assignment.split("=")
        with pytest.raises(vkdiffrender.Error) as raised:
            scene[name] = float(value)
        assert str(raised.value) == cli_error(cli, "render", str(fog_scene_file), "-o", str(tmp_path / "a.exr"),
                                              "--set", assignment)


def test_keyword_messages_are_the_command_lines_options(cli, fog_scene_file, tmp_path):
    """A keyword's error is the command line's for its option, naming the keyword."""
    scene = vkdiffrender.Scene(fog_scene_file)
    for keyword, option, value in [("spp", "--spp", 0), ("max_depth", "--max-depth", 100001),
                                   ("seed", "--seed", 1 << 32)]:
        with pytest.raises(vkdiffrender.Error) as raised:
            scene.render(width=WIDTH, **{keyword: value})
        expected = cli_error(cli, "render", str(fog_scene_file), "-o", str(tmp_path / "a.exr"), option, str(value))
        assert str(raised.value) == expected.replace(option, keyword, 1)
    with pytest.raises(vkdiffrender.Error) as raised:
        scene.loss_gradient(np.zeros((WIDTH, WIDTH, 3), np.float32), ["media/fog/g"], loss="l3", width=WIDTH)
    target = tmp_path / "target.exr"
    vkdiffrender.write_image(target, np.zeros((WIDTH, WIDTH, 3), np.float32))
    expected = cli_error(cli, "grad", str(fog_scene_file), "--target", str(target), "--param", "media/fog/g",
                         "--loss", "l3")
    assert str(raised.value) == expected.replace("--loss", "loss", 1)


@pytest.mark.parametrize("value,problem", [
    (np.float32("nan"), "finite"),
    (np.array([0.1, 0.2], np.float32), "expected shape (3,)"),
    (np.zeros((1, 3), np.float32), "expected shape (3,)"),
    (1e300, "media/fog/sigma_a: must be finite, got 1e+300: beyond float range (magnitude at most 3.4e+38)"),
    ([0.1, -1e39, 0.1], "media/fog/sigma_a: value 1 of 3 (counted from 0): must be finite, got -1e+39: beyond float "
                        "range"),
    (Decimal("NaN"), "media/fog/sigma_a: must be finite, got nan"),  # comparing it with a float raises
    ([Decimal("-Infinity"), 1, 1], "media/fog/sigma_a: value 0 of 3 (counted from 0): must be finite, got -inf"),
])
def test_bad_parameter_values_are_refused(scene, value, problem):
    before = scene["media/fog/sigma_a"].copy()
    with pytest.raises(vkdiffrender.Error, match=re.escape(problem)):
        scene["media/fog/sigma_a"] = value
    assert np.array_equal(scene["media/fog/sigma_a"], before)


@pytest.mark.parametrize("value,problem", [
    (None, "got None"),
    ("0.1", "got text"),
    (b"0.1", "got text"),
    (bytearray(b"0.1"), "got text"),
    ({}, "got an array of dtype object"),
    (1 + 2j, "got an array of dtype complex128"),
    (np.array(["1", "2", "3"]), "got an array of dtype <U1"),
    ([0.1, "x", 0.2], "got an array of dtype <U32"),
    (np.ma.masked_array([0.1, 5.0, 0.1], mask=[0, 1, 0]),
     "got a masked array (its masked values would be taken; pass numpy.ma.filled(value, fill) or its data)"),
])
def test_values_that_are_not_numbers_are_type_errors_naming_the_parameter(scene, value, problem):
    """numpy would parse text, make None NaN, drop an imaginary part and take a masked
    array's hidden values: each is refused."""
    before = scene["media/fog/sigma_a"].copy()
    with pytest.raises(TypeError, match="^media/fog/sigma_a: expected numbers, " + re.escape(problem) + "$"):
        scene["media/fog/sigma_a"] = value
    assert np.array_equal(scene["media/fog/sigma_a"], before)
    with pytest.raises(TypeError, match="^the image adjoint: expected numbers, "):
        scene.backpropagate(value, ["media/fog/sigma_a"], width=WIDTH)


@pytest.mark.parametrize("value,expected", [
    (2**64, np.float32(2.0**64)),
    (Fraction(1, 20), np.float32(0.05)),
    (Decimal("0.05"), np.float32(0.05)),
    ([Fraction(1, 4), 2**70, 1], np.array([0.25, 2.0**70, 1.0], np.float32)),
    ([np.True_, Fraction(1, 2), 2**64], np.array([1.0, 0.5, 2.0**64], np.float32)),
])
def test_numbers_numpy_holds_as_objects_are_numbers(scene, value, expected):
    """Integers beyond 64 bits, Fractions and Decimals: numpy makes arrays of objects of them."""
    before = scene["media/fog/sigma_a"].copy()
    try:
        scene["media/fog/sigma_a"] = value
        assert np.array_equal(scene["media/fog/sigma_a"], np.broadcast_to(expected, (3,)))
    finally:
        scene["media/fog/sigma_a"] = before


@pytest.mark.parametrize("value", [
    [None, 0.1, Fraction(1, 5)],
    [np.complex128(0.5 + 2j), Fraction(1, 2), 0.1],
    [np.timedelta64(3, "D"), Fraction(1, 2), 0.1],
])
def test_objects_that_are_not_all_real_numbers_stay_refused(scene, value):
    with pytest.raises(TypeError, match="^media/fog/sigma_a: expected numbers, got an array of dtype object$"):
        scene["media/fog/sigma_a"] = value


@pytest.mark.parametrize("value", [10**40, 10**400, Fraction(10**400, 3), Decimal("1e400"), [Fraction(1, 2), -10**39]])
def test_numbers_beyond_float_range_are_named_whatever_holds_them(scene, value):
    with pytest.raises(vkdiffrender.Error, match="media/fog/sigma_a: (value 1 of 2 \\(counted from 0\\): )?must be "
                                                 "finite, got .*: beyond float range"):
        scene["media/fog/sigma_a"] = value


def test_what_numpy_cannot_convert_is_refused_with_its_reason(scene):
    torch = pytest.importorskip("torch")
    with pytest.raises(TypeError, match=r"^media/fog/sigma_a: expected numbers, got Tensor \(RuntimeError: "
                                        r"Can't call numpy\(\) on Tensor that requires grad"):
        scene["media/fog/sigma_a"] = torch.tensor([0.1] * 3, requires_grad=True)


@pytest.mark.parametrize("call,problem", [
    (lambda s: s.render(spp=0, width=WIDTH), "spp"),
    (lambda s: s.render(width=-1), "width"),
    (lambda s: s.render(width=WIDTH, max_depth=10**6), "max_depth"),
    (lambda s: s.render(width=WIDTH, camera="nope"), "^camera nope: no such camera"),
    (lambda s: s["nope"], "nope"),
    (lambda s: s.render(width=WIDTH, paths_per_pass=1 << 22), "paths_per_pass"),
    (lambda s: s.loss_gradient(np.full((WIDTH, WIDTH, 3), np.nan, np.float32), ["media/fog/g"], width=WIDTH,
                               spp=2), "target"),
    (lambda s: s.backpropagate(np.zeros((WIDTH, WIDTH, 3), np.float32), ["media/fog/nope"], width=WIDTH,
                               spp=1), "media/fog/nope"),
    (lambda s: s.backpropagate(np.zeros((WIDTH, 3), np.float32), ["media/fog/g"], width=WIDTH), "shape"),
    (lambda s: s.backpropagate(np.zeros((WIDTH + 1, WIDTH, 3), np.float32), ["media/fog/g"], width=WIDTH,
                               spp=1), "image adjoint"),
    (lambda s: s.backpropagate(np.zeros((WIDTH + 1, WIDTH, 3), np.float32), [], width=WIDTH, spp=1),
     "image adjoint"),
    (lambda s: s.backpropagate(np.full((WIDTH, WIDTH, 3), np.inf, np.float32), ["media/fog/g"], width=WIDTH,
                               spp=1), "not finite"),
    # Arrays of terabytes as views, refused by their shape before a copy is made.
    (lambda s: s.backpropagate(np.broadcast_to(np.float32(0), (1 << 20, 1 << 20, 3)), ["media/fog/g"], width=WIDTH,
                               spp=1), r"the image adjoint of shape \(1048576, 1048576, 3\) is larger than any image"),
    (lambda s: s.loss_gradient(np.broadcast_to(np.float32(0), (1 << 20, 1 << 20, 3)), ["media/fog/g"], width=WIDTH,
                               spp=1), r"the target of shape \(1048576, 1048576, 3\) is larger than any image"),
    (lambda s: s.__setitem__("media/fog/g", np.broadcast_to(np.float32(0), (1 << 40,))),
     r"media/fog/g: expected shape \(1,\) or one value, got \(1099511627776,\)"),
])
def test_bad_calls_raise(scene, call, problem):
    with pytest.raises(vkdiffrender.Error, match=problem):
        call(scene)
    assert scene.render(spp=1, width=WIDTH).shape == (WIDTH, WIDTH, 3)  # still usable


@pytest.mark.parametrize("call,problem", [
    (lambda s: s.backpropagate(np.zeros((WIDTH, WIDTH, 3), np.float32), "media/fog/g", width=WIDTH),
     "parameters: expected a list of names, got str (a list of one name: ['media/fog/g'])"),
    (lambda s: s.loss_gradient(np.zeros((WIDTH, WIDTH, 3), np.float32), 3, width=WIDTH),
     "parameters: expected a list of names, got int"),
    (lambda s: s.backpropagate(np.zeros((WIDTH, WIDTH, 3), np.float32), ["media/fog/g", None], width=WIDTH),
     "parameters: a name must be a str, got NoneType"),
    (lambda s: s.render(width=WIDTH, camera=None), 'camera: expected a camera\'s name ("" for the scene\'s first), '
                                                   "got NoneType"),
    (lambda s: s.render(width=WIDTH, camera=0), 'camera: expected a camera\'s name ("" for the scene\'s first), got int'),
    (lambda s: s.loss_gradient(np.zeros((WIDTH, WIDTH, 3), np.float32), ["media/fog/g"], loss=b"l2", width=WIDTH),
     "loss_gradient(): loss: expected a str, got bytes"),
])
def test_names_that_are_not_text_are_type_errors_naming_the_argument(scene, call, problem):
    """pybind11's own message would list the signatures and print the arrays passed."""
    with pytest.raises(TypeError, match="^" + re.escape(problem) + "$"):
        call(scene)
    assert scene.backpropagate(np.zeros((8, 8, 3), np.float32), ("media/fog/g" for _ in range(1)), width=8,
                               spp=2)["media/fog/g"].shape == (1,)


def test_objects_made_without_init_raise_instead_of_crashing(tmp_path):
    bare = vkdiffrender.Scene.__new__(vkdiffrender.Scene)
    image = np.zeros((WIDTH, WIDTH, 3), np.float32)
    calls = [
        lambda: bare.file, lambda: bare.warnings, lambda: bare.device, bare.parameters,
        lambda: bare.parameter("media/fog/g"), lambda: bare["media/fog/g"],
        lambda: bare.__setitem__("media/fog/g", 0.1), lambda: "media/fog/g" in bare,
        lambda: bare.render(width=WIDTH), lambda: bare.backpropagate(image, [], width=WIDTH),
        lambda: bare.loss_gradient(image, [], width=WIDTH), lambda: bare.write(str(tmp_path / "out.gltf")),
    ]
    for call in calls:
        with pytest.raises(TypeError):
            call()
    bare_parameter = vkdiffrender.Parameter.__new__(vkdiffrender.Parameter)
    for call in [lambda: bare_parameter.name, lambda: bare_parameter.shape, lambda: bare_parameter.lower,
                 lambda: bare_parameter.upper, lambda: repr(bare_parameter)]:
        with pytest.raises(TypeError):
            call()
    assert not list(tmp_path.iterdir())


def test_init_is_refused_on_a_loaded_scene_and_retried_after_a_failed_one(fog_scene_file, tmp_path):
    scene = vkdiffrender.Scene(fog_scene_file)
    with pytest.raises(TypeError, match="this Scene already holds .*; make a new vkdiffrender.Scene"):
        scene.__init__(fog_scene_file)
    assert scene.file == fog_scene_file.resolve() and scene.render(width=4, spp=1).shape == (4, 4, 3)
    bare = vkdiffrender.Scene.__new__(vkdiffrender.Scene)
    with pytest.raises(vkdiffrender.Error):
        bare.__init__(tmp_path / "missing.gltf")
    bare.__init__(fog_scene_file)
    assert "media/fog/g" in bare
    assert "file" in vkdiffrender.Scene.__init__.__doc__  # the signature help is kept


def test_arguments_that_do_not_fit_are_named_in_one_line(scene, fog_scene_file):
    adjoint = np.ones((WIDTH, WIDTH, 3), np.float32)
    cases = [
        (lambda: scene.render(spp=1, width=WIDTH, sed=3),
         "render() got an unexpected keyword argument 'sed' (did you mean 'seed'?)"),
        (lambda: scene.backpropagate(adjoint, ["media/fog/g"], spp=1, width=WIDTH, zzz=1),
         "backpropagate() got an unexpected keyword argument 'zzz' (it takes image_adjoint, parameters, spp, "),
        (lambda: vkdiffrender.Scene(fog_scene_file, devise=0),
         "Scene() got an unexpected keyword argument 'devise' (did you mean 'device'?)"),
        (lambda: scene.render(2), "render() takes 0 positional arguments but 1 were given (pass spp, "),
        (lambda: scene.backpropagate(adjoint), "backpropagate() missing required argument 'parameters'"),
        (lambda: scene.backpropagate(adjoint, [], image_adjoint=adjoint),
         "backpropagate() got multiple values for argument 'image_adjoint'"),
        (lambda: scene.loss_gradient(adjoint, ["media/fog/g"], loss=None),
         "loss_gradient(): loss: expected a str, got NoneType"),
        (lambda: scene.write(None), "write(): path: expected a path (a str or os.PathLike), got NoneType"),
        (lambda: scene[0], "__getitem__(): name: expected a str, got int"),
        # A name is a str wherever it is taken, as in backpropagate's list and its dict's keys.
        (lambda: scene[b"media/fog/g"], "__getitem__(): name: expected a str, got bytes"),
        (lambda: scene.__setitem__(b"media/fog/g", 0.5), "__setitem__(): name: expected a str, got bytes"),
        (lambda: scene.parameter(b"media/fog/g"), "parameter(): name: expected a str, got bytes"),
        (lambda: b"media/fog/g" in scene, "__contains__(): name: expected a str, got bytes"),
        (lambda: vkdiffrender.write_image("a.exr", adjoint, 3),
         "write_image() takes 2 positional arguments but 3 were given"),
    ]
    for call, message in cases:
        with pytest.raises(TypeError) as raised:
            call()
        assert str(raised.value).startswith(message), str(raised.value)
        assert "\n" not in str(raised.value), str(raised.value)
    with pytest.raises(TypeError, match="object is not iterable"):
        list(scene)
    assert "spp: object = 16" in vkdiffrender.Scene.render.__doc__  # the signature help is kept


def test_none_is_a_type_error(scene):
    with pytest.raises(TypeError, match="None"):
        scene["media/fog/sigma_a"] = None
    with pytest.raises(TypeError, match="None"):
        scene.backpropagate(None, ["media/fog/g"], width=WIDTH)


def test_an_unsummable_image_adjoint_is_an_error_not_an_infinite_gradient(scene):
    huge = np.full((WIDTH, WIDTH, 3), 3e38, np.float32)
    with pytest.raises(vkdiffrender.Error, match="not finite"):
        scene.backpropagate(huge, ["media/fog/sigma_a"], spp=2, width=WIDTH)
    assert scene.backpropagate(huge, [], spp=2, width=WIDTH) == {}


def test_a_render_too_bright_for_floats_is_an_error_from_every_call():
    """Each value in its range, their product beyond float's: render refuses the image, and
    so must loss_gradient, which would otherwise return an infinite loss and image."""
    fire = vkdiffrender.Scene(SCENES / "cornell_fire.gltf")
    fire["media/fire/emission_grid"] = 1e30
    fire["media/fire/emission"] = 1e12
    target = np.zeros((WIDTH, WIDTH, 3), np.float32)
    with pytest.raises(vkdiffrender.Error, match="the render's pixel .* is"):
        fire.render(width=WIDTH, height=WIDTH, spp=2)
    for names in ([], ["media/fire/g"]):
        with pytest.raises(vkdiffrender.Error, match="the render's pixel .* is"):
            fire.loss_gradient(target, names, width=WIDTH, height=WIDTH, spp=2)


def test_write_refuses_to_replace_a_file_the_scene_reads(tmp_path):
    """Writing out.gltf writes its texture as out.image0.png: here the very file the scene
    reads its texture from, which must be left as it was."""
    scene_file = write_textured_fog_scene(tmp_path)
    (tmp_path / "poster.png").rename(tmp_path / "out.image0.png")
    gltf = scene_file.read_text().replace('"poster.png"', '"out.image0.png"')
    scene_file.write_text(gltf)
    texture = (tmp_path / "out.image0.png").read_bytes()
    scene = vkdiffrender.Scene(scene_file)
    scene["materials/poster/base_color_texture"] = 0.9
    with pytest.raises(vkdiffrender.Error, match="out.image0.png: the written scene would replace this file"):
        scene.write(tmp_path / "out.gltf")
    assert (tmp_path / "out.image0.png").read_bytes() == texture
    scene.write(tmp_path / "other.gltf")  # the scene's files are as loaded
    vkdiffrender.write_image(tmp_path / "texel.png", np.full((1, 1, 3), 0.9, np.float32))
    eight_bit = vkdiffrender.read_image(tmp_path / "texel.png")[0, 0, 0]  # as the written texture holds 0.9
    assert np.all(vkdiffrender.Scene(tmp_path / "other.gltf")["materials/poster/base_color_texture"] == eight_bit)


@pytest.mark.parametrize("value, problem", [(float("nan"), "NaN"), (float("inf"), "+infinity"), (1e19, "beyond")])
def test_read_image_refuses_what_a_target_may_not_hold(tmp_path, value, problem):
    """The EXR of 4 x 4 pixels of 0.5 with its last value (pixel (3, 3), channel R) changed."""
    data = bytearray((MALFORMED / "valid_target.exr").read_bytes())
    data[-4:] = np.float32(value).tobytes()
    (tmp_path / "bad.exr").write_bytes(data)
    with pytest.raises(vkdiffrender.Error, match=f"bad.exr: pixel \\(3, 3\\) channel R .*{re.escape(problem)}"):
        vkdiffrender.read_image(tmp_path / "bad.exr")


@pytest.mark.parametrize("call,problem", [
    (lambda s, d: vkdiffrender.Scene(str(d / "a\0.gltf")), "Scene(): file: embedded null byte"),
    (lambda s, d: vkdiffrender.read_image(str(d / "a\0.exr")), "read_image(): path: embedded null byte"),
    (lambda s, d: vkdiffrender.write_image(str(d / "a\0.exr"), np.zeros((2, 2, 3), np.float32)),
     "write_image(): path: embedded null byte"),
    (lambda s, d: s.write(str(d / "a\0.gltf")), "write(): path: embedded null byte"),
])
def test_a_path_with_a_null_byte_is_a_value_error_naming_the_argument(scene, tmp_path, call, problem):
    """As Python's open() says: no file's name holds one."""
    with pytest.raises(ValueError, match="^" + re.escape(problem) + "$"):
        call(scene, tmp_path)
    assert list(tmp_path.iterdir()) == []


def test_the_error_and_every_scene_method_say_what_they_are(scene):
    assert "refuses" in vkdiffrender.Error.__doc__
    assert repr(scene) == f"<vkdiffrender.Scene {str(scene.file)!r} on {scene.device}>"
    for name in ("render", "backpropagate", "loss_gradient", "write", "parameter", "parameters", "__getitem__",
                 "__setitem__", "__contains__"):
        assert len(getattr(vkdiffrender.Scene, name).__doc__.splitlines()) > 1, name  # more than the signature


def test_a_parameters_repr_quotes_its_name_as_python_does(tmp_path):
    """A material's name may hold quotes and newlines."""
    gltf = json.loads((SCENES / "cornell_fog.gltf").read_text())
    gltf["materials"][0]["name"] = "it's\nwhite"
    (tmp_path / "named.gltf").write_text(json.dumps(gltf))
    parameter = vkdiffrender.Scene(str(tmp_path / "named.gltf")).parameter("materials/it's\nwhite/base_color")
    assert repr(parameter) == "Parameter(\"materials/it's\\nwhite/base_color\", shape=(3,), range=[0.0, 1.0])"


LONE_SURROGATE = "\udcff"  # what Python makes of a byte it cannot decode


@pytest.mark.parametrize("call,problem", [
    (lambda s: s.render(spp=1, width=WIDTH, camera=LONE_SURROGATE), "render(): camera"),
    (lambda s: vkdiffrender.Scene(s.file, device=LONE_SURROGATE), "Scene(): device"),
    (lambda s: s.backpropagate(np.ones((WIDTH, WIDTH, 3), np.float32), ["media/fog/" + LONE_SURROGATE], spp=1,
                               width=WIDTH), "backpropagate(): parameters"),
    (lambda s: s["media/fog/" + LONE_SURROGATE], "__getitem__(): name"),
    (lambda s: s.__setitem__("media/fog/" + LONE_SURROGATE, 0.1), "__setitem__(): name"),
])
def test_a_str_that_is_not_unicode_is_a_value_error_naming_the_argument(scene, call, problem):
    """pybind11 cannot pass it on as UTF-8, and says so without naming it."""
    with pytest.raises(ValueError, match="^" + re.escape(problem + ": holds a character that is not valid Unicode")):
        call(scene)
    assert scene.render(spp=1, width=WIDTH).shape == (WIDTH, WIDTH, 3)


def test_write_image_takes_an_image_wider_than_a_render(tmp_path):
    """Renders placed side by side: the limit on a render's size is not an image's."""
    wide = np.zeros((2, 20000, 3), np.float32)
    wide[1, 19999] = 0.5
    vkdiffrender.write_image(tmp_path / "wide.exr", wide)
    assert np.array_equal(vkdiffrender.read_image(tmp_path / "wide.exr"), wide)


def test_files_are_checked(scene, fog_scene_file, tmp_path):
    with pytest.raises(vkdiffrender.Error, match="expected a .gltf or .glb file"):
        vkdiffrender.Scene(tmp_path)
    (tmp_path / "folder.gltf").mkdir()
    with pytest.raises(vkdiffrender.Error, match="is a directory"):
        vkdiffrender.Scene(tmp_path / "folder.gltf")
    with pytest.raises(vkdiffrender.Error, match=".gltf"):
        scene.write(tmp_path / "fitted.txt")
    with pytest.raises(vkdiffrender.Error, match="a file the scene reads"):
        scene.write(fog_scene_file)
    with pytest.raises(vkdiffrender.Error, match="extension"):
        vkdiffrender.write_image(tmp_path / "a.jpg", np.zeros((2, 2, 3), np.float32))
    good = tmp_path / "a.exr"
    vkdiffrender.write_image(good, np.ones((2, 2, 3), np.float32))
    with pytest.raises(vkdiffrender.Error, match="NaN"):
        vkdiffrender.write_image(good, np.full((2, 2, 3), np.nan, np.float32))
    assert np.array_equal(vkdiffrender.read_image(good), np.ones((2, 2, 3), np.float32))  # not written over
    with pytest.raises(vkdiffrender.Error, match="missing.exr"):
        vkdiffrender.read_image(tmp_path / "missing.exr")
    with pytest.raises(vkdiffrender.Error):
        vkdiffrender.Scene(fog_scene_file, device="no such device")


def test_a_file_outside_the_scenes_directory_is_refused_naming_the_keyword(tmp_path):
    inner = tmp_path / "inner"
    inner.mkdir()
    path = write_textured_fog_scene(inner)
    (inner / "poster.png").rename(tmp_path / "poster.png")
    gltf = json.loads(path.read_text())
    gltf["images"] = [{"uri": "../poster.png"}]
    path.write_text(json.dumps(gltf))
    with pytest.raises(vkdiffrender.Error) as raised:
        vkdiffrender.Scene(path)
    assert "unless allow_outside_files=True is given" in str(raised.value), str(raised.value)
    assert vkdiffrender.Scene(path, allow_outside_files=True).parameter("materials/poster/base_color_texture")


def test_a_device_is_an_index_or_part_of_a_name(fog_scene_file):
    name = vkdiffrender.devices()[0]
    assert vkdiffrender.Scene(fog_scene_file, device=0).device == name
    assert vkdiffrender.Scene(fog_scene_file, device=name[:4]).device == name
    with pytest.raises(vkdiffrender.Error, match=f"^device {len(vkdiffrender.devices())}: no device has that index"):
        vkdiffrender.Scene(fog_scene_file, device=len(vkdiffrender.devices()))
    assert vkdiffrender.Scene(fog_scene_file, device=np.int64(0)).device == name
    with pytest.raises(vkdiffrender.Error, match=r"^device: an index is at least 0, got -1 "):
        vkdiffrender.Scene(fog_scene_file, device=-1)
    for wrong in [1.0, True, np.bool_(False), None]:
        with pytest.raises(TypeError, match="^device: expected an index or part of a device's name"):
            vkdiffrender.Scene(fog_scene_file, device=wrong)


def test_integer_keywords_take_integers_only(scene):
    """numpy integers are integers; a float (numpy's too) or a bool is a TypeError rather than
    truncated, and an integer beyond 64 bits gets the keyword's range message."""
    assert scene.render(width=np.int64(WIDTH), spp=np.uint8(1)).shape == (WIDTH, WIDTH, 3)
    for keyword, value in [("spp", np.float32(1.7)), ("width", 8.0), ("spp", True), ("width", np.bool_(True))]:
        with pytest.raises(TypeError, match=f"^{keyword}: expected an integer, got {type(value).__name__}$"):
            scene.render(**{"width": WIDTH, "spp": 1, keyword: value})
    # numpy arrays claim to be integers, and are not one unless of one element and no shape.
    with pytest.raises(TypeError, match="^width: expected an integer, got ndarray"):
        scene.render(width=np.array([WIDTH]), spp=1)
    # An __index__ that raises is named with its reason, not its traceback.
    class BadIndex:
        def __index__(self):
            raise ValueError("no index here")
    with pytest.raises(TypeError, match=r"^spp: expected an integer, got BadIndex \(ValueError: no index here\)$"):
        scene.render(width=WIDTH, spp=BadIndex())
    with pytest.raises(vkdiffrender.Error, match=r"^spp: must be an integer from 1 to \d+, got 9223372036854775808$"):
        scene.render(width=WIDTH, spp=2**63)
    with pytest.raises(vkdiffrender.Error, match=r"^seed: must be a 32-bit unsigned integer .*, got 18446744073709551616$"):
        scene.render(width=WIDTH, spp=1, seed=2**64)


def test_only_true_and_false_are_booleans(scene, fog_scene_file):
    for value, kind in ((None, "NoneType"), (0.5, "float"), (1, "int"), (np.float64(0.0), "float64"),
                        (np.int64(0), "int64"), ("yes", "str")):
        with pytest.raises(TypeError, match=rf"^allow_outside_files: expected True or False, got {kind}$"):
            vkdiffrender.Scene(fog_scene_file, allow_outside_files=value)
        with pytest.raises(TypeError, match=rf"^equiangular: expected True or False, got {kind}$"):
            scene.render(width=WIDTH, spp=1, equiangular=value)
    assert scene.render(width=WIDTH, spp=1, equiangular=np.bool_(False)).shape == (WIDTH, WIDTH, 3)


def test_write_gives_a_scene_that_loads_with_the_values(scene, tmp_path):
    scene["media/fog/sigma_a"] = np.array([0.02, 0.03, 0.04], np.float32)
    scene.write(tmp_path / "fitted.gltf")
    assert np.array_equal(vkdiffrender.Scene(tmp_path / "fitted.gltf")["media/fog/sigma_a"],
                          np.array([0.02, 0.03, 0.04], np.float32))


def test_write_refuses_a_scene_that_would_not_load(fog_scene_file, tmp_path):
    """Each value in range, together a scene-wide medium that emits without attenuating."""
    fog = vkdiffrender.Scene(fog_scene_file)
    fog["media/fog/sigma_a"] = 0
    fog["media/fog/sigma_s"] = 0
    fog["media/fog/emission"] = 1
    with pytest.raises(vkdiffrender.Error, match="unbounded.gltf: the scene would not load again: "):
        fog.write(tmp_path / "unbounded.gltf")
    assert not (tmp_path / "unbounded.gltf").exists()


def test_a_scene_named_from_a_removed_working_directory_is_an_error(tmp_path):
    here = os.getcwd()
    gone = tmp_path / "gone"
    gone.mkdir()
    os.chdir(gone)
    try:
        gone.rmdir()
        with pytest.raises(vkdiffrender.Error, match="scene.gltf: .*the working directory cannot be read"):
            vkdiffrender.Scene("scene.gltf")
    finally:
        os.chdir(here)


def test_the_device_works_without_pythons_lock(scene):
    ticks = 0
    done = threading.Event()

    def count():
        nonlocal ticks
        while not done.is_set():
            ticks += 1
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    try:
        scene.render(spp=64, width=64)
    finally:
        done.set()
        counter.join()
    assert ticks > 10


def test_a_thread_waiting_for_a_parameter_lets_other_threads_go_on(scene):
    """Reading a parameter waits for another thread's render, with Python's lock released."""
    scene.render(spp=1, width=48)  # sets up the view, so that the render below starts at once
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)

    renderer = threading.Thread(target=lambda: scene.render(spp=64, width=48))
    counter = threading.Thread(target=count)
    renderer.start()
    time.sleep(0.2)
    counter.start()
    try:
        started = time.monotonic()
        scene["media/fog/g"]
        finished = time.monotonic()
    finally:
        done.set()
        counter.join()
        renderer.join()
    assert finished - started > 0.1, "the render ended before the read began; render more samples"
    assert sum(started <= t <= finished for t in ticks) > 10


def test_threads_sharing_a_scene_take_turns(scene):
    """Calls on one Scene from several threads wait for each other; each gets the image a
    call on its own would."""
    settings = [dict(spp=1, width=8 + k % 3, seed=k) for k in range(9)]
    expected = [scene.render(**s) for s in settings]
    results = [None] * len(settings)

    def work(first):
        for k in range(first, len(settings), 3):
            results[k] = scene.render(**settings[k])

    threads = [threading.Thread(target=work, args=(first,)) for first in range(3)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert all(np.array_equal(a, b) for a, b in zip(results, expected))


CHILD = """
import sys, time, vkdiffrender
scene = vkdiffrender.Scene(sys.argv[1])
print("rendering", flush=True)
start = time.monotonic()
try:
    scene.render(spp=1 << 16, width=256)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted after %.1f s" % (time.monotonic() - start), flush=True)
print("still works:", scene.render(spp=1, width=8).shape, flush=True)
"""


DAEMONS_AT_EXIT = """
import sys, threading, time, numpy as np, vkdiffrender
scene = vkdiffrender.Scene(sys.argv[1])
scene.render(spp=1, width=8)
def render_forever():
    while True:
        scene.render(spp=16, width=32)
def write_forever():
    while True:
        vkdiffrender.write_image(sys.argv[2], np.ones((1000, 1000, 3), np.float32))
for work in (render_forever, write_forever):
    threading.Thread(target=work, daemon=True).start()
time.sleep(0.5)
print("exiting", flush=True)
"""


def test_daemon_threads_in_device_work_let_the_process_exit(fog_scene_file, tmp_path):
    """Python 3.11 ends a daemon thread that takes its lock back during finalization by
    unwinding it, which aborted the process from the module's release of the lock; and
    work still running as exit() tears the libraries down may crash it
    (docs/python.md, "Errors and Ctrl-C")."""
    for attempt in range(3):
        child = subprocess.run([sys.executable, "-c", DAEMONS_AT_EXIT, str(fog_scene_file), str(tmp_path / "w.exr")],
                               capture_output=True, text=True, env=os.environ, timeout=120)
        assert child.returncode == 0, f"attempt {attempt}: exit status {child.returncode}: {child.stderr}"
        assert child.stdout == "exiting\n"
        assert "Traceback" not in child.stderr, child.stderr


FORK_WHILE_RENDERING = """
import atexit, os, sys
parent = os.getpid()
def leave_child():  # registered first, so run after the module's own handler
    if os.getpid() != parent:
        print("child's atexit handlers ran", flush=True)
        os._exit(0)  # as multiprocessing's children leave: TBB's exit handler is not fork-safe
atexit.register(leave_child)
import threading, time, numpy as np, vkdiffrender
scene = vkdiffrender.Scene(sys.argv[1])
def render_forever():
    while True:
        scene.render(spp=16, width=32)
threading.Thread(target=render_forever, daemon=True).start()
time.sleep(0.5)
pid = os.fork()
if pid == 0:
    vkdiffrender.write_image(sys.argv[2], np.ones((8, 8, 3), np.float32))
    sys.exit(0)
_, status = os.waitpid(pid, 0)
print("child", os.waitstatus_to_exitcode(status), flush=True)
"""


def test_a_child_forked_while_a_thread_renders_exits(fog_scene_file, tmp_path):
    """The child has none of its parent's other threads, nor their work in flight: its own
    exit must not wait for them (the module's atexit handler waited for ever)."""
    child = subprocess.run([sys.executable, "-c", FORK_WHILE_RENDERING, str(fog_scene_file), str(tmp_path / "c.exr")],
                           capture_output=True, text=True, env=os.environ, timeout=120)
    assert child.returncode == 0, child.stderr
    assert child.stdout == "child's atexit handlers ran\nchild 0\n", child.stderr
    assert vkdiffrender.read_image(tmp_path / "c.exr").shape == (8, 8, 3)


def interrupted_child(script, fog_scene_file, ready, wait, timeout=120):
    """Runs `script` with the scene's path in a Python of its own, sends it SIGINT `wait`
    seconds after it prints the line `ready`, and returns the rest of its output once it
    has exited with 0."""
    child = subprocess.Popen([sys.executable, "-c", script, str(fog_scene_file)], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True, env=os.environ)
    assert child.stdout.readline().strip() == ready
    time.sleep(wait)
    child.send_signal(signal.SIGINT)
    out, err = child.communicate(timeout=timeout)
    assert child.returncode == 0, err
    return out + err


def test_ctrl_c_interrupts_a_render(fog_scene_file):
    out = interrupted_child(CHILD, fog_scene_file, "rendering", 1.0)
    assert out.startswith("interrupted after"), out
    assert "still works: (8, 8, 3)" in out


HANDLED = """
import signal, sys, time, vkdiffrender
scene = vkdiffrender.Scene(sys.argv[1])
stops = []
signal.signal(signal.SIGINT, lambda number, frame: stops.append(number))
scene.render(spp=1, width=8)
print("rendering", flush=True)
image = scene.render(spp=64, width=64)
print("finished", image.shape, "handler called", len(stops), flush=True)
"""


def test_ctrl_c_runs_a_handler_of_ones_own_after_the_render(fog_scene_file):
    out = interrupted_child(HANDLED, fog_scene_file, "rendering", 0.5, timeout=300)
    assert out.strip() == "finished (64, 64, 3) handler called 1", out


def test_a_scene_from_before_a_fork_is_an_error_in_the_child_not_a_hang(scene):
    scene.render(spp=1, width=8)  # the device's threads are running
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read)
        try:
            scene.render(spp=1, width=8)
            message = "rendered"
        except vkdiffrender.Error as error:
            message = str(error)
        except BaseException as error:  # anything else is a failure the parent reports
            message = repr(error)
        os.write(write, message.encode())
        os._exit(0)
    os.close(write)
    try:
        ready, _, _ = select.select([read], [], [], 120)
        message = os.read(read, 4096).decode() if ready else "no answer in 120 s"
    finally:
        os.close(read)
        if not ready:
            os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
    assert message.startswith("this Scene was made in another process, before a fork"), message
    assert scene.render(spp=1, width=8).shape == (8, 8, 3)


WAITING = """
import sys, threading, time, vkdiffrender
scene = vkdiffrender.Scene(sys.argv[1])
scene.render(spp=1, width=64)
outcome = []

def work():
    try:
        scene.render(spp=1 << 14, width=64)
        outcome.append("finished")
    except KeyboardInterrupt:
        outcome.append("interrupted")

worker = threading.Thread(target=work)
worker.start()
time.sleep(0.5)
print("waiting", flush=True)
start = time.monotonic()
try:
    scene["media/fog/g"] = 0.1
    print("set after %.1f s" % (time.monotonic() - start), flush=True)
except KeyboardInterrupt:
    print("interrupted", flush=True)
worker.join()
print("worker", outcome[0], flush=True)
"""


def test_ctrl_c_stops_a_wait_for_another_threads_render(fog_scene_file):
    """The main thread waiting to set a parameter while a thread renders: Ctrl-C stops the
    render, as it stops device work under way in other threads, and the wait."""
    out = interrupted_child(WAITING, fog_scene_file, "waiting", 0.5)
    assert out.split("\n")[:2] == ["interrupted", "worker interrupted"], out
