#!/usr/bin/env python3
"""Checks an editor screenshot without PIL or numpy: decodes the PNG with zlib and the five PNG filter
types (8-bit RGB or RGBA, non-interlaced: what stb_image_write produces), then tests colours.

usage: check_screenshot.py PNG WIDTH HEIGHT meadow|pile

Checks (pixel values are display sRGB-ish 0..255):
  both    size is WIDTH x HEIGHT; not uniform (luminance standard deviation > 12);
          sky at the top: the mean of the top 5 % of rows is bright (> 150) and blue-dominant (b > r + 10);
  meadow  the ground: in the central 20 % x 20 % of the frame the mean is not sky (b is the smallest
          channel, g >= b + 15); the lower half holds ground (>= 25 % of its pixels have b < min(r, g) - 10,
          earth and grass, where sky has b largest) and at least 3 % of those ground pixels are green
          (g > r + 10 and g > b + 20: the grass tufts; the opening view looks at a patch of the meadow
          where tufts stand apart on textured olive ground);
  pile    objects on the ground: the central 20 % x 20 % has a luminance spread (std > 12: lit rocks and
          shadowed gaps; the bare grid floor is about 10, its lines on flat grey) and the bottom 10 % of
          rows is grey ground (|r - b| < 40).
"""
import struct
import sys
import zlib


def decode_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, width = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or color not in (2, 6) or interlace != 0:
                raise ValueError("unsupported PNG: depth %d colour type %d interlace %d" % (depth, color, interlace))
            channels = 3 if color == 2 else 4
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, prev, i = [], bytearray(stride), 0
    for _ in range(height):
        ftype = raw[i]
        line = bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        for x in range(stride):
            a = line[x - channels] if x >= channels else 0
            b = prev[x]
            c = prev[x - channels] if x >= channels else 0
            if ftype == 1:
                line[x] = (line[x] + a) & 255
            elif ftype == 2:
                line[x] = (line[x] + b) & 255
            elif ftype == 3:
                line[x] = (line[x] + ((a + b) >> 1)) & 255
            elif ftype == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[x] = (line[x] + pred) & 255
            elif ftype != 0:
                raise ValueError("bad filter type %d" % ftype)
        rows.append([tuple(line[x * channels:x * channels + 3]) for x in range(width)])
        prev = line
    return width, height, rows


def region_mean(rows, x0, x1, y0, y1):
    n, s = 0, [0, 0, 0]
    for y in range(y0, y1):
        for x in range(x0, x1):
            p = rows[y][x]
            s[0] += p[0]; s[1] += p[1]; s[2] += p[2]
            n += 1
    return [v / n for v in s]


def lum_std(pixels):
    lums = [0.299 * r + 0.587 * g + 0.114 * b for r, g, b in pixels]
    m = sum(lums) / len(lums)
    return (sum((v - m) ** 2 for v in lums) / len(lums)) ** 0.5


def main():
    path, want_w, want_h, kind = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
    w, h, rows = decode_png(path)
    failures = []
    if (w, h) != (want_w, want_h):
        failures.append("size %dx%d, wanted %dx%d" % (w, h, want_w, want_h))
    every = [rows[y][x] for y in range(0, h, 4) for x in range(0, w, 4)]
    std = lum_std(every)
    if std <= 12:
        failures.append("image nearly uniform (luminance std %.1f)" % std)
    top = region_mean(rows, 0, w, 0, max(1, h // 20))
    if not (sum(top) / 3 > 150 and top[2] > top[0] + 10):
        failures.append("top rows are not sky: mean %s" % [round(v) for v in top])
    cx0, cx1, cy0, cy1 = int(w * 0.4), int(w * 0.6), int(h * 0.4), int(h * 0.6)
    centre = region_mean(rows, cx0, cx1, cy0, cy1)
    if kind == "meadow":
        if not (centre[2] <= min(centre[0], centre[1]) and centre[1] >= centre[2] + 15):
            failures.append("centre is not ground/grass: mean %s" % [round(v) for v in centre])
        lower = [rows[y][x] for y in range(h // 2, h, 2) for x in range(0, w, 2)]
        ground = [p for p in lower if p[2] < min(p[0], p[1]) - 10]
        if len(ground) < 0.25 * len(lower):
            failures.append("only %.1f %% of the lower half is ground" % (100.0 * len(ground) / len(lower)))
        green = sum(1 for r, g, b in ground if g > r + 10 and g > b + 20) / max(len(ground), 1)
        if green < 0.03:
            failures.append("only %.1f %% of the ground pixels are green (grass)" % (100 * green))
        print("meadow: std %.1f, top %s, centre %s, green %.1f %% of the ground" % (std, [round(v) for v in top],
                                                                  [round(v) for v in centre], 100 * green))
    else:
        c_std = lum_std([rows[y][x] for y in range(cy0, cy1) for x in range(cx0, cx1)])
        if c_std <= 12:
            failures.append("centre has no objects (luminance std %.1f)" % c_std)
        bottom = region_mean(rows, 0, w, h - max(1, h // 10), h)
        if abs(bottom[0] - bottom[2]) >= 40:
            failures.append("bottom rows are not grey ground: mean %s" % [round(v) for v in bottom])
        print("pile: std %.1f, top %s, centre std %.1f, bottom %s" % (std, [round(v) for v in top], c_std,
                                                                    [round(v) for v in bottom]))
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
