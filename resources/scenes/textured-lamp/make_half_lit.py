#!/usr/bin/env python3
"""Writes half-lit.png: the lamp's emissive texture, 64 x 8 RGB, the left 32
columns white (255), the right 32 black (0). Both decode from sRGB exactly
(to 1 and 0), and bilinear lookups with wrapping are symmetric about the
middle, so the texture's mean over the whole lamp is exactly one half.
Standard library only; run it in this folder."""
import struct
import zlib


def chunk(kind, data):
    return (struct.pack(">I", len(data)) + kind + data +
            struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))


def main():
    width, height = 64, 8
    rows = b""
    for _ in range(height):
        rows += b"\x00"  # filter: none
        for x in range(width):
            v = 255 if x < width // 2 else 0
            rows += bytes([v, v, v])
    png = (b"\x89PNG\r\n\x1a\n" +
           chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))
    with open("half-lit.png", "wb") as f:
        f.write(png)


if __name__ == "__main__":
    main()
