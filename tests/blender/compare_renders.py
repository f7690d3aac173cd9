"""Print, for each scene directory render_both.py wrote, vkdiffrender / Cycles image-mean
ratios per channel, their z-scores, the largest block |z| and the range of the 4 x 4
block-mean ratios (image_stats: noise from the renders' seeds).

/usr/bin/python3 tests/blender/compare_renders.py OUT [OUT...]"""
import pathlib
import sys

import numpy as np

import image_stats


def summary(directory):
    cycles = [np.load(f) for f in sorted(directory.glob("cycles_*.npy"))]
    vkdr = [np.load(f) for f in sorted(directory.glob("vkdr_*.npy"))]
    if len(cycles) < 2 or len(vkdr) < 2:
        return f"{directory.name}: fewer than two renders of each renderer"
    block_z, image_z, vkdr_mean, cycles_mean = image_stats.z_scores(vkdr, cycles, blocks=4)
    block_cycles, _ = image_stats.block_statistics(cycles, 4)
    block_vkdr, _ = image_stats.block_statistics(vkdr, 4)
    block_ratio = (block_vkdr / block_cycles).mean(axis=2)
    ratio = ", ".join(f"{r:.4f}" for r in vkdr_mean / cycles_mean)
    z = ", ".join(f"{v:.1f}" for v in image_z)
    return (f"{directory.name}: ratio {ratio} (z {z}); largest block |z| {np.abs(block_z).max():.1f}; "
            f"block ratios {block_ratio.min():.3f} to {block_ratio.max():.3f}")


def main():
    for root in sys.argv[1:]:
        for directory in sorted(p for p in pathlib.Path(root).iterdir() if p.is_dir()):
            print(summary(directory))


if __name__ == "__main__":
    main()
