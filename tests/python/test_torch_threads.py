"""vkdiffrender.torch.render from several threads sharing one Scene: each pass renders
and differentiates the values of its own thread, as it would alone."""
import threading

import numpy as np
import pytest
import vkdiffrender

torch = pytest.importorskip("torch")
import vkdiffrender.torch as vt  # noqa: E402

SETTINGS = dict(spp=2, width=16, seed=5)
# sigma_a of the fog in each thread: at 2.0 the fog hides the lamp, so the two threads'
# images and gradients differ in every run.
VALUES = (0.02, 2.0)
ITERATIONS = 8


def image_and_gradient(scene, value):
    sigma_a = torch.tensor(value, requires_grad=True)
    image = vt.render(scene, {"media/fog/sigma_a": sigma_a}, **SETTINGS)
    image.sum().backward()
    return image.detach().numpy(), sigma_a.grad.item()


def test_threads_sharing_a_scene_render_and_differentiate_their_own_values(fog_scene_file):
    scene = vkdiffrender.Scene(str(fog_scene_file))
    alone = [image_and_gradient(scene, value) for value in VALUES]
    assert not np.array_equal(alone[0][0], alone[1][0])
    assert alone[0][1] != alone[1][1]
    results = [[] for _ in VALUES]

    def work(k):
        for _ in range(ITERATIONS):
            results[k].append(image_and_gradient(scene, VALUES[k]))

    threads = [threading.Thread(target=work, args=(k,)) for k in range(len(VALUES))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for k, (image, gradient) in enumerate(alone):
        assert all(np.array_equal(i, image) for i, _ in results[k]), f"thread of sigma_a {VALUES[k]}: images"
        assert [g for _, g in results[k]] == [gradient] * ITERATIONS, f"thread of sigma_a {VALUES[k]}: gradients"


def test_a_list_of_tensors_that_require_grad_is_refused(fog_scene_file):
    scene = vkdiffrender.Scene(str(fog_scene_file))
    channels = [torch.tensor(0.05, requires_grad=True) for _ in range(3)]
    with pytest.raises(TypeError, match="media/fog/sigma_a: a list of tensors that require grad"):
        vt.render(scene, {"media/fog/sigma_a": channels}, **SETTINGS)
    with pytest.raises(TypeError, match="media/fog/sigma_a: a list of tensors that require grad"):
        vt.render(scene, {"media/fog/sigma_a": [[channel] for channel in channels]}, **SETTINGS)
