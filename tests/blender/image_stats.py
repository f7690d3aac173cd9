"""Comparing two renderers' images within their Monte Carlo noise.

Each renderer gives n >= 2 renders from independent seeds. A pixel's variance is
estimated by its sample variance over the seeds; pixels are independent (each has its
own samples, box filter one pixel wide), so the variance of a block's mean of the
seed-averaged image is the sum of its pixels' variances / n over the block's pixel
count squared. z = (mean_a - mean_b) / sqrt(se_a^2 + se_b^2) per block and channel."""
import numpy as np


def block_statistics(renders, blocks):
    """Block means of the seed average, and their standard errors: arrays (blocks, blocks, 3)."""
    stack = np.stack(renders).astype(np.float64)
    n, height, width, _ = stack.shape
    mean = stack.mean(axis=0)
    pixel_variance_of_mean = stack.var(axis=0, ddof=1) / n
    bh, bw = height // blocks, width // blocks

    def per_block(image):
        return image[:bh * blocks, :bw * blocks].reshape(blocks, bh, blocks, bw, 3).sum(axis=(1, 3))
    pixels = bh * bw
    return per_block(mean) / pixels, np.sqrt(per_block(pixel_variance_of_mean)) / pixels


def z_scores(renders_a, renders_b, blocks):
    """z of the difference of block means (blocks x blocks x 3) and of the image means (3)."""
    mean_a, se_a = block_statistics(renders_a, blocks)
    mean_b, se_b = block_statistics(renders_b, blocks)
    image_a, image_se_a = block_statistics(renders_a, 1)
    image_b, image_se_b = block_statistics(renders_b, 1)
    block_z = (mean_a - mean_b) / np.sqrt(se_a ** 2 + se_b ** 2)
    image_z = (image_a - image_b) / np.sqrt(image_se_a ** 2 + image_se_b ** 2)
    return block_z, image_z.reshape(3), image_a.reshape(3), image_b.reshape(3)
