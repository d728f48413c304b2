#!/usr/bin/env python3
"""Writes wall-ridges.png: the wall's tangent-space normal map, 64 x 64 RGB,
8 columns of 8 texels, a washboard of flat facets tilted 30 degrees about the
v axis, alternately towards -u (even columns, counted from the left) and +u
(odd columns). Each texel is (n + 1) / 2 of its facet's normal n in the
frame (tangent = +u, bitangent = +v, normal), 8 bits per channel:
n = (-0.5, 0, 0.866) -> (64, 128, 238), n = (0.5, 0, 0.866) -> (191, 128, 238).
Standard library only (and tools/png_file.py); run it in this folder."""
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[3] / "tools"))
from png_file import RGB, write_png  # noqa: E402


def encode(x):
    return int(round((x + 1.0) / 2.0 * 255.0))


def main():
    tilt = math.radians(30.0)

    def pixel(x, _y):
        side = 1.0 if (x // 8) % 2 == 1 else -1.0
        return (encode(side * math.sin(tilt)), 128, encode(math.cos(tilt)))

    write_png("wall-ridges.png", 64, 64, RGB, pixel)


if __name__ == "__main__":
    main()
