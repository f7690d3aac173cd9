"""Means over seeds with their standard errors, and the agreement test every gradient
test uses."""
import math

import numpy as np

# Two estimates agree when they differ by at most this many combined standard errors.
# Each side is a mean over 16 seeds, so their difference over its estimated standard
# error follows Student's t with about 30 degrees of freedom, which exceeds 5 with
# probability 2e-5: even a test of a dozen such comparisons fails by chance once in a few
# thousand runs (and at fixed seeds every run on a device repeats bit for bit).
AGREEMENT_IN_STANDARD_ERRORS = 5.0


def mean_and_standard_error(samples):
    samples = np.asarray(samples, dtype=np.float64)
    return samples.mean(axis=0), samples.std(axis=0, ddof=1) / math.sqrt(samples.shape[0])


def assert_agree(what, mean_a, error_a, mean_b, error_b):
    mean_a, error_a, mean_b, error_b = (np.atleast_1d(np.asarray(x, dtype=np.float64))
                                        for x in (mean_a, error_a, mean_b, error_b))
    combined = np.sqrt(error_a ** 2 + error_b ** 2)
    assert np.all(combined > 0), f"{what}: zero standard error, the comparison would prove nothing"
    differences = np.abs(mean_a - mean_b) / combined
    assert np.all(differences <= AGREEMENT_IN_STANDARD_ERRORS), (
        f"{what}: {mean_a} +- {error_a} against {mean_b} +- {error_b} "
        f"({differences.max():.1f} standard errors apart)")
