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
