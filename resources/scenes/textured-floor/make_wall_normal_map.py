#!/usr/bin/env python3
"""Writes wall-ridges.png: the wall's tangent-space normal map, 64 x 64 RGB,
8 columns of 8 texels, a washboard of flat facets tilted 30 degrees about the
v axis, alternately towards -u (even columns, counted from the left) and +u
(odd columns). Each texel is (n + 1) / 2 of its facet's normal n in the
frame (tangent = +u, bitangent = +v, normal), 8 bits per channel:
n = (-0.5, 0, 0.866) -> (64, 128, 238), n = (0.5, 0, 0.866) -> (191, 128, 238).
Standard library only; run it in this folder."""
import math
import struct
import zlib


def chunk(kind, data):
    return (struct.pack(">I", len(data)) + kind + data +
            struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))


def encode(x):
    return int(round((x + 1.0) / 2.0 * 255.0))


def main():
    size, column = 64, 8
    tilt = math.radians(30.0)
    rows = b""
    for _ in range(size):
        rows += b"\x00"  # filter: none
        for x in range(size):
            side = 1.0 if (x // column) % 2 == 1 else -1.0
            rows += bytes([encode(side * math.sin(tilt)), 128, encode(math.cos(tilt))])
    png = (b"\x89PNG\r\n\x1a\n" +
           chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))
    with open("wall-ridges.png", "wb") as f:
        f.write(png)


if __name__ == "__main__":
    main()
