#!/usr/bin/env python3
"""Times the Python module against the command line on the same scene and settings, in
one run: a forward render (Scene.render against `vkdiffrender bench`'s forward pass);
a gradient iteration by the command line's own estimator (Scene.loss_gradient with an
L2 loss against bench's gradient iteration); and one through PyTorch
(vkdiffrender.torch.render, an L2 loss written in torch, backward()), whose backward
pass renders again (docs/python.md, "Cost").

Shared machines drift by tens of per cent over a minute, so the two are interleaved:
each of --pairs rounds runs `bench --iters 1` (one timed iteration after its warm-up)
and then each of the module's calls once, and the table gives the median over the
rounds of each time and of the per-round ratio, with the ratios' range.

Usage: PYTHONPATH=build/python /usr/bin/python3 tools/bench_python.py
           [--scene scenes/cornell_fog.gltf] [--width 128] [--spp 16] [--pairs 7]
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


def milliseconds(work):
    start = time.perf_counter()
    work()
    return 1000.0 * (time.perf_counter() - start)


def command_line_ms(cli, options):
    with tempfile.TemporaryDirectory() as directory:
        report = pathlib.Path(directory) / "bench.json"
        subprocess.run([cli, "bench", str(options.scene), "--width", str(options.width), "--height",
                        str(options.width), "--spp", str(options.spp), "--iters", "1", "--json",
                        str(report)], check=True, capture_output=True)
        result = json.loads(report.read_text())["scenes"][0]
    return result["forward_ms"], result["gradient_ms"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", type=pathlib.Path, default=ROOT / "scenes" / "cornell_fog.gltf")
    parser.add_argument("--width", type=int, default=128)
    parser.add_argument("--spp", type=int, default=16)
    parser.add_argument("--pairs", type=int, default=7)
    parser.add_argument("--cli", default=str(ROOT / "build" / "src" / "cli" / "vkdiffrender"))
    options = parser.parse_args()
    settings = dict(spp=options.spp, width=options.width, height=options.width)

    scene = vkdiffrender.Scene(options.scene)
    name = next(p.name for p in scene.parameters() if p.name.endswith("/sigma_a"))
    target = scene.render(seed=12345, **settings)
    target_tensor = torch.from_numpy(target)
    sigma_a = torch.tensor(scene[name], requires_grad=True)

    def torch_iteration():
        image = vt.render(scene, {name: sigma_a}, **settings)
        ((image - target_tensor) ** 2).mean().backward()

    module_calls = {
        "forward render: Scene.render": lambda: scene.render(**settings),
        "gradient iteration: Scene.loss_gradient": lambda: scene.loss_gradient(target, [name], **settings),
        "gradient iteration: vkdiffrender.torch, backward()": torch_iteration,
    }
    for call in module_calls.values():
        call()  # warm-up: pipelines and buffers, as bench's own
    rows = {label: ([], []) for label in module_calls}
    for _ in range(options.pairs):
        forward_ms, gradient_ms = command_line_ms(options.cli, options)
        for label, call in module_calls.items():
            cli_ms = forward_ms if label.startswith("forward") else gradient_ms
            rows[label][0].append(cli_ms)
            rows[label][1].append(milliseconds(call))

    print(f"{options.scene.name}, {options.width}x{options.width}, {options.spp} spp, on {scene.device}; "
          f"medians over {options.pairs} interleaved rounds, ms")
    print("| | command line | Python module | module / command line | range of the ratio |")
    print("|---|--:|--:|--:|--:|")
    for label, (cli_times, module_times) in rows.items():
        ratios = [m / c for m, c in zip(module_times, cli_times)]
        print(f"| {label} | {statistics.median(cli_times):.1f} | {statistics.median(module_times):.1f} | "
              f"{statistics.median(ratios):.2f} | {min(ratios):.2f}-{max(ratios):.2f} |")


if __name__ == "__main__":
    main()
