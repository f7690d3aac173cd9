#!/usr/bin/env python3
"""Times the Python module against the command line on the same scene and settings, in
one run: a forward render (Scene.render against `vkdiffrender bench`'s forward pass);
a gradient iteration by the command line's own estimator (Scene.loss_gradient with an
L2 loss against bench's gradient iteration); and one through PyTorch
(vkdiffrender.torch.render, an L2 loss written in torch, backward()), whose backward
pass renders again (docs/python.md, "Cost"). Each figure is the median of --iters runs
after a warm-up; bench runs before and after the module's runs, and both of its results
are shown.

Usage: PYTHONPATH=build/python /usr/bin/python3 tools/bench_python.py
           [--scene scenes/cornell_fog.gltf] [--width 128] [--spp 16] [--iters 5]
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import tempfile
import time

import torch
import vkdiffrender
import vkdiffrender.torch as vt

ROOT = pathlib.Path(__file__).resolve().parents[1]


def median_ms(work, iterations):
    work()
    times = []
    for _ in range(iterations):
        start = time.perf_counter()
        work()
        times.append(1000.0 * (time.perf_counter() - start))
    return statistics.median(times)


def command_line_ms(cli, options):
    with tempfile.TemporaryDirectory() as directory:
        report = pathlib.Path(directory) / "bench.json"
        subprocess.run([cli, "bench", str(options.scene), "--width", str(options.width), "--height",
                        str(options.width), "--spp", str(options.spp), "--iters", str(options.iters), "--json",
                        str(report)], check=True, capture_output=True)
        result = json.loads(report.read_text())["scenes"][0]
    return result["forward_ms"], result["gradient_ms"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", type=pathlib.Path, default=ROOT / "scenes" / "cornell_fog.gltf")
    parser.add_argument("--width", type=int, default=128)
    parser.add_argument("--spp", type=int, default=16)
    parser.add_argument("--iters", type=int, default=5)
    parser.add_argument("--cli", default=str(ROOT / "build" / "src" / "cli" / "vkdiffrender"))
    options = parser.parse_args()
    settings = dict(spp=options.spp, width=options.width, height=options.width)

    before = command_line_ms(options.cli, options)
    scene = vkdiffrender.Scene(options.scene)
    name = next(p.name for p in scene.parameters() if p.name.endswith("/sigma_a"))
    target = torch.from_numpy(scene.render(seed=12345, **settings))
    sigma_a = torch.tensor(scene[name], requires_grad=True)

    def gradient_iteration():
        image = vt.render(scene, {name: sigma_a}, **settings)
        ((image - target) ** 2).mean().backward()

    forward = median_ms(lambda: scene.render(**settings), options.iters)
    loss_gradient = median_ms(lambda: scene.loss_gradient(target.numpy(), [name], **settings), options.iters)
    torch_gradient = median_ms(gradient_iteration, options.iters)
    after = command_line_ms(options.cli, options)

    print(f"{options.scene.name}, {options.width}x{options.width}, {options.spp} spp, on {scene.device}; "
          f"median of {options.iters}, ms")
    print("| | command line (before) | Python module | command line (after) | module / command line |")
    print("|---|--:|--:|--:|--:|")
    rows = [("forward render: Scene.render", forward, before[0], after[0]),
            ("gradient iteration: Scene.loss_gradient", loss_gradient, before[1], after[1]),
            ("gradient iteration: vkdiffrender.torch, backward()", torch_gradient, before[1], after[1])]
    for label, mine, cli_before, cli_after in rows:
        ratio = mine / statistics.mean([cli_before, cli_after])
        print(f"| {label} | {cli_before:.1f} | {mine:.1f} | {cli_after:.1f} | {ratio:.2f} |")


if __name__ == "__main__":
    main()
