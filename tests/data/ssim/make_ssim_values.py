#!/usr/bin/python3
"""Reference SSIM values for tests/unit/test_metrics_ssim.cpp.

Computes scikit-image's structural_similarity on small deterministic image
pairs, defined by closed formulas (and a 64-bit LCG) that the C++ test
rebuilds exactly. Regenerate with

    apt-get install python3-skimage   # Debian 12: scikit-image 0.19.3
    /usr/bin/python3 tests/data/ssim/make_ssim_values.py   # Debian's python, which sees the package

and paste the printed values into the test.
"""
import math

import numpy as np
import skimage
from skimage.metrics import structural_similarity


def lcg_image(width, height, seed):
    """Uniform [0, 1) values from the 64-bit LCG (Knuth's MMIX constants)."""
    state = seed
    out = np.zeros((height, width))
    for y in range(height):
        for x in range(width):
            state = (state * 6364136223846793005 + 1442695040888963407) % (1 << 64)
            out[y, x] = (state >> 11) / float(1 << 53)
    return out


def pattern(width, height, fx, fy, phase):
    out = np.zeros((height, width))
    for y in range(height):
        for x in range(width):
            out[y, x] = 0.5 + 0.4 * math.sin(fx * x + phase) * math.cos(fy * y)
    return out


def pairs():
    # 1: a smooth pattern against itself plus a shifted, weaker pattern.
    a = pattern(24, 20, 0.31, 0.23, 0.0)
    yield "pattern_vs_perturbed", a, a + 0.1 * pattern(24, 20, 0.7, 0.5, 1.0) - 0.05, 1.0
    # 2: pattern against noise.
    yield "pattern_vs_noise", pattern(24, 20, 0.31, 0.23, 0.0), lcg_image(24, 20, 7), 1.0
    # 3: noise against noise mixed with it (correlated), data range 2.
    n1 = lcg_image(17, 15, 1)
    yield "noise_vs_mixed", 2.0 * n1, 2.0 * (0.7 * n1 + 0.3 * lcg_image(17, 15, 2)), 2.0
    # 4: 12 x 11, barely bigger than the window: the mirrored edges matter.
    yield "small_contrast", pattern(12, 11, 0.9, 0.8, 0.3), 0.5 * pattern(12, 11, 0.9, 0.8, 0.3), 1.0


print("# scikit-image", skimage.__version__, "numpy", np.__version__)
for name, x, y, data_range in pairs():
    v = structural_similarity(x, y, gaussian_weights=True, sigma=1.5,
                              use_sample_covariance=False, data_range=data_range)
    print(f"{name} {v:.17g}")

# Masked: scikit-image's full SSIM map of pair 1, averaged over the pixels at
# least 5 from the border (its crop) with x < 12 (the mask the C++ test uses).
a = pattern(24, 20, 0.31, 0.23, 0.0)
b = a + 0.1 * pattern(24, 20, 0.7, 0.5, 1.0) - 0.05
_, smap = structural_similarity(a, b, gaussian_weights=True, sigma=1.5,
                                use_sample_covariance=False, data_range=1.0, full=True)
print(f"pattern_vs_perturbed_left_half {smap[5:-5, 5:12].mean():.17g}")
