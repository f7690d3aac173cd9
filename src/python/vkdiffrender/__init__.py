"""vkdiffrender: a differentiable Monte Carlo path tracer for participating media.

Load a glTF scene onto a Vulkan device, read and set its named parameters as numpy
arrays, render a camera to an (H, W, 3) float32 array, and back-propagate any image
adjoint dLoss/dI to the parameters. vkdiffrender.torch wraps the render as a PyTorch
operation. The documentation is docs/python.md in the source tree.

    import vkdiffrender
    scene = vkdiffrender.Scene("scenes/cornell_fog.gltf")
    scene["media/fog/sigma_a"] = 0.05
    image = scene.render(spp=64, seed=1, width=128)
    vkdiffrender.write_image("fog.exr", image)
"""
import functools

from ._arguments import named_argument_errors
from ._vkdiffrender import (  # noqa: F401
    Error,
    Parameter,
    Scene,
    __version__,
    devices,
    read_image,
    write_image,
)

__all__ = ["Error", "Parameter", "Scene", "devices", "read_image", "write_image"]


def _refuse_reloading(init):
    """Scene.__init__ on a scene already loaded would load the file onto the device and
    keep the old scene (pybind11 leaves a constructed object alone): refused instead."""
    @functools.wraps(init)
    def __init__(self, *args, **kwargs):
        try:
            loaded = self.file
        except TypeError:  # made by __new__ and not loaded yet (or a failed __init__)
            return init(self, *args, **kwargs)
        raise TypeError(f"this Scene already holds {loaded}; make a new vkdiffrender.Scene(...) to load another "
                        f"file")
    return __init__


Scene.__init__ = _refuse_reloading(named_argument_errors(Scene.__init__, "Scene"))
for _method in ("render", "backpropagate", "loss_gradient", "write", "parameter", "__getitem__", "__setitem__",
                "__contains__"):
    setattr(Scene, _method, named_argument_errors(getattr(Scene, _method)))
# __getitem__ takes names, not indices: without this, iter() would call it with 0, 1, ...
Scene.__iter__ = None
read_image = named_argument_errors(read_image)
write_image = named_argument_errors(write_image)
