"""vkdiffrender's render as a differentiable PyTorch operation.

    from vkdiffrender.torch import render
    sigma_a = torch.tensor([0.3, 0.3, 0.3], requires_grad=True)
    image = render(scene, {"media/fog/sigma_a": sigma_a}, spp=32, seed=it)
    loss = ((image - target) ** 2).mean()
    loss.backward()  # sigma_a.grad

The forward pass sets the scene's parameters to the tensors' values and renders. The
backward pass sets every parameter back to the values the forward pass rendered with and
hands the upstream gradient dLoss/dI to Scene.backpropagate, which
replays the paths with random numbers independent of the forward image's: the gradient
is then free of the covariance between the image and its own derivative, the bias a
nonlinear loss would otherwise get (docs/python.md, "Why the backward pass renders
again"). A pass that fails puts every parameter back as it found it.

Each pass holds the scene's lock from setting the parameters to rendering with them, so
that threads sharing a scene never render or differentiate each other's values.
"""
import contextlib
import threading
import weakref
from collections.abc import Mapping

import torch

from . import Scene

__all__ = ["render"]

_scene_locks = weakref.WeakKeyDictionary()
_scene_locks_guard = threading.Lock()


def _lock_of(scene):
    with _scene_locks_guard:
        lock = _scene_locks.get(scene)
        if lock is None:
            lock = _scene_locks[scene] = threading.Lock()
        return lock


@contextlib.contextmanager
def _restored_on_failure(scene):
    """Puts every parameter of `scene` back as it was where the block raises (an unknown
    name, a value out of range, a bad keyword, a gradient the tensor cannot hold)."""
    before = {parameter.name: scene[parameter.name] for parameter in scene.parameters()}
    try:
        yield
    except BaseException:
        for name, value in before.items():
            scene[name] = value
        raise


def render(scene, parameters, *, spp=16, seed=0, width=0, height=0, max_depth=8, camera="", paths_per_pass=0,
           equiangular=True):
    """Renders `scene` with `parameters` (a dict of parameter name -> tensor) and returns
    an (H, W, 3) float32 tensor, on the device of the first parameter tensor, whose
    gradient flows back to every tensor that requires it.

    A tensor may have the parameter's shape (scene.parameter(name).shape) or a single
    element, which sets every channel (and texel); its gradient then sums theirs. A value
    that is not a tensor is set as `scene[name] = value` sets it, and gets no gradient.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene: expected a vkdiffrender.Scene, got {type(scene).__name__}")
    if not isinstance(parameters, Mapping):
        raise TypeError(f"parameters: expected a dict of parameter name -> tensor, got {type(parameters).__name__}")
    settings = dict(spp=spp, seed=seed, width=width, height=height, max_depth=max_depth, camera=camera,
                    paths_per_pass=paths_per_pass, equiangular=equiangular)
    names = list(parameters)
    for name in names:
        if not isinstance(name, str):
            raise TypeError(f"parameters: a name must be a str, got {type(name).__name__} ({name!r})")
    values = [_checked_value(name, parameters[name]) for name in names]
    _refuse_aliases(scene, names)
    return _Render.apply(scene, names, settings, *values)


def _refuse_aliases(scene, names):
    """Two names of the same values (a texture that materials share) would set them twice,
    the second winning, and give each tensor the whole gradient."""
    given = set(names)
    for name in names:
        if name not in scene:
            continue  # the forward pass names it as unknown
        for alias in scene.parameter(name).aliases:
            if alias in given:
                raise ValueError(f"parameters: {name} and {alias} name the same values (a texture both "
                                 f"materials use); give one of them")


def _checked_value(name, value):
    """`value` if it is a dense tensor of real numbers with values, or not a tensor at all (a
    number, a list, an array), which the forward pass sets as `scene[name] = value` does, with
    the same checks; otherwise a TypeError naming the parameter."""
    # A list's tensors would be taken by their values alone, losing their gradients.
    if isinstance(value, (list, tuple)) and _holds_tensor_requiring_grad(value):
        raise TypeError(f"{name}: a list of tensors that require grad loses their gradients; "
                        "pass torch.stack(...) of them instead")
    if not isinstance(value, torch.Tensor):
        return value
    # Converting to float32 would drop an imaginary part with a mere warning.
    if value.is_complex():
        raise TypeError(f"{name}: expected real numbers, got a tensor of {value.dtype}")
    if value.device.type == "meta":
        raise TypeError(f"{name}: a tensor on the meta device holds no values")
    if value.layout != torch.strided:
        raise TypeError(f"{name}: expected a dense tensor, got one of layout {value.layout}; pass value.to_dense()")
    return value


def _values_of(tensor):
    """The tensor's values as numpy holds them for the scene: float64 as it is, so that a value
    beyond float's range is named as such rather than as an infinity; every other dtype
    (bfloat16, which numpy lacks, included) as float32."""
    values = tensor.detach().to("cpu")
    if values.is_quantized:
        values = values.dequantize()
    values = values.resolve_conj().resolve_neg()  # numpy() refuses a lazily negated view
    return (values if values.dtype == torch.float64 else values.to(torch.float32)).numpy()


def _holds_tensor_requiring_grad(items):
    return any(_holds_tensor_requiring_grad(item) if isinstance(item, (list, tuple))
               else isinstance(item, torch.Tensor) and item.requires_grad for item in items)


class _Render(torch.autograd.Function):
    @staticmethod
    def forward(ctx, scene, names, settings, *values):
        with _lock_of(scene), _restored_on_failure(scene):
            for name, value in zip(names, values):
                scene[name] = _values_of(value) if isinstance(value, torch.Tensor) else value
            image = scene.render(**settings)
            # Every parameter, not only the tensors': the backward pass must differentiate
            # the scene this pass rendered, whatever is set in between (another view, say).
            ctx.values = {parameter.name: scene[parameter.name] for parameter in scene.parameters()}
        ctx.scene, ctx.names, ctx.settings = scene, names, settings
        ctx.tensor_shapes = [(value.shape, value.dtype, value.device) if isinstance(value, torch.Tensor) else None
                             for value in values]
        tensors = [value for value in values if isinstance(value, torch.Tensor)]
        device = tensors[0].device if tensors else torch.device("cpu")
        return torch.from_numpy(image).to(device)

    @staticmethod
    @torch.autograd.function.once_differentiable
    def backward(ctx, image_gradient):
        wanted = [name for name, needed in zip(ctx.names, ctx.needs_input_grad[3:]) if needed]
        if not wanted:
            return (None, None, None) + (None,) * len(ctx.names)
        adjoint = image_gradient.detach().to("cpu", torch.float32).contiguous().numpy()
        with _lock_of(ctx.scene), _restored_on_failure(ctx.scene):
            for name, value in ctx.values.items():
                ctx.scene[name] = value
            gradients = ctx.scene.backpropagate(adjoint, wanted, **ctx.settings)
            results = [_gradient_tensor(name, gradients[name], *place) if name in gradients else None
                       for name, place in zip(ctx.names, ctx.tensor_shapes)]
        return (None, None, None) + tuple(results)


def _gradient_tensor(name, gradient, shape, dtype, device):
    """A parameter's gradient as its tensor holds it: summed where the tensor has one
    element for many values, in its dtype, on its device."""
    gradient = torch.from_numpy(gradient)
    if shape.numel() == 1 and gradient.numel() != 1:
        gradient = gradient.sum()
    cast = gradient.reshape(shape).to(dtype=dtype)
    # The renderer's gradients are finite floats: only a narrower dtype overflows.
    if not torch.isfinite(cast).all():
        raise OverflowError(f"{name}: its gradient (up to {gradient.abs().max().item():g} in magnitude) "
                            f"exceeds the range of the tensor's {dtype}; pass it in a wider dtype "
                            f"(torch.float32 or torch.float64)")
    return cast.to(device=device)
