#!/usr/bin/env python3
"""Writes fence-mask.png: the fence's alpha mask, 8 x 8 RGBA, white, with an
alpha checker of 2 x 2-texel squares (255 solid, 0 cut away). Bilinear lookups
of such a checker cross 0.5 exactly on the squares' edges, so exactly half of
the fence is solid. Standard library only; run it in this folder."""
import struct
import zlib


def chunk(kind, data):
    return (struct.pack(">I", len(data)) + kind + data +
            struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))


def main():
    size = 8
    rows = b""
    for y in range(size):
        rows += b"\x00"  # filter: none
        for x in range(size):
            solid = ((x // 2) + (y // 2)) % 2 == 0
            rows += bytes([255, 255, 255, 255 if solid else 0])
    png = (b"\x89PNG\r\n\x1a\n" +
           chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 6, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))
    with open("fence-mask.png", "wb") as f:
        f.write(png)


if __name__ == "__main__":
    main()
