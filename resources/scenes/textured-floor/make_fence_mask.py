#!/usr/bin/env python3
"""Writes fence-mask.png: the fence's alpha mask, 8 x 8 RGBA, white, with an
alpha checker of 2 x 2-texel squares (255 solid, 0 cut away). Bilinear lookups
of such a checker cross 0.5 exactly on the squares' edges, so exactly half of
the fence is solid. Standard library only (and tools/png_file.py); run it in
this folder."""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[3] / "tools"))
from png_file import RGBA, write_png  # noqa: E402


def main():
    def pixel(x, y):
        solid = ((x // 2) + (y // 2)) % 2 == 0
        return (255, 255, 255, 255 if solid else 0)

    write_png("fence-mask.png", 8, 8, RGBA, pixel)


if __name__ == "__main__":
    main()
