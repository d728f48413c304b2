#!/usr/bin/env python3
"""Writes half-lit.png: the lamp's emissive texture, 64 x 8 RGB, the left 32
columns white (255), the right 32 black (0). Both decode from sRGB exactly
(to 1 and 0), and bilinear lookups with wrapping are symmetric about the
middle, so the texture's mean over the whole lamp is exactly one half.
Standard library only (and tools/png_file.py); run it in this folder."""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[3] / "tools"))
from png_file import RGB, write_png  # noqa: E402


def main():
    def pixel(x, _y):
        v = 255 if x < 32 else 0
        return (v, v, v)

    write_png("half-lit.png", 64, 8, RGB, pixel)


if __name__ == "__main__":
    main()
