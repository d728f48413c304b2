"""Writes small 8-bit PNG files with the standard library alone, for the test
images the shipped scenes generate (resources/scenes/*/make_*.py)."""
import struct
import zlib

GREY, RGB, RGBA = 0, 2, 6  # PNG colour types
CHANNELS = {GREY: 1, RGB: 3, RGBA: 4}


def _chunk(kind, data):
    return (struct.pack(">I", len(data)) + kind + data +
            struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))


def write_png(path, width, height, colour_type, pixel):
    """Writes `path`: pixel(x, y) gives the channel bytes (a sequence of
    CHANNELS[colour_type] ints in 0..255) of the pixel in column x, row y
    (row 0 at the top)."""
    rows = b""
    for y in range(height):
        rows += b"\x00"  # filter: none
        for x in range(width):
            rows += bytes(pixel(x, y))
    header = struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", header) +
                _chunk(b"IDAT", zlib.compress(rows, 9)) + _chunk(b"IEND", b""))
