#!/usr/bin/env python3
"""ib_png.py: read pixels of the RGBA8 PNGs oit writes (standard library only).

usage: ib_png.py FILE.png X Y             prints "R G B" of pixel (X, Y), top row first
       ib_png.py FILE.png --diff OTHER.png lists pixels where they differ by > 2
As a module: read_png(path) -> (width, height, rows of bytes RGBA)."""
import struct
import sys
import zlib


def read_png(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    pos, idat = 8, b""
    width = height = None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour_type = struct.unpack(">IIBB", body[:10])
            if depth != 8 or colour_type not in (2, 6):
                raise ValueError(f"{path}: only 8-bit RGB/RGBA PNGs are supported")
            channels = 4 if colour_type == 6 else 3
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up = previous[i]
            up_left = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - up_left
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - up_left)
                pred = left if pa <= pb and pa <= pc else (up if pb <= pc else up_left)
                line[i] = (line[i] + pred) & 255
        if channels == 3:
            line = bytearray(b"".join(bytes(line[i:i + 3]) + b"\xff" for i in range(0, stride, 3)))
        rows.append(line)
        previous = line if channels == 4 else bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    return width, height, rows


def pixel(image, x, y):
    _, _, rows = image
    return tuple(rows[y][4 * x:4 * x + 3])


if __name__ == "__main__":
    image = read_png(sys.argv[1])
    if sys.argv[2] == "--diff":
        other = read_png(sys.argv[3])
        for y in range(image[1]):
            for x in range(image[0]):
                a, b = pixel(image, x, y), pixel(other, x, y)
                if max(abs(p - q) for p, q in zip(a, b)) > 2:
                    print(x, y, a, b)
    else:
        print(*pixel(image, int(sys.argv[2]), int(sys.argv[3])))
