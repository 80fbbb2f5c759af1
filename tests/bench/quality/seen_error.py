#!/usr/bin/env python3
"""The seen error of seen_error.hpp for two image files (EXR, PFM, ...):
both mapped to what a PNG shows (clamp to [0, 1], sRGB encode), blurred by
a box of radius 2 applied twice, compared by RMSE over the whole image and
over the worst 16x16 tile. A port of the C++ header, for comparing renders
of different back-ends from the command line:

  /usr/bin/python3 tests/bench/quality/seen_error.py IMAGE REFERENCE
"""
import sys

import numpy as np
import OpenImageIO as oiio

RADIUS, TILE = 2, 16


def displayed(linear):
    c = np.clip(np.nan_to_num(linear, nan=0.0, posinf=0.0, neginf=0.0), 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1.0 / 2.4) - 0.055)


def box(plane, axis):
    # Windows cut at the border: the mean over the pixels inside.
    n = plane.shape[axis]
    csum = np.cumsum(np.insert(plane, 0, 0.0, axis=axis), axis=axis, dtype=np.float64)
    i = np.arange(n)
    lo, hi = np.maximum(0, i - RADIUS), np.minimum(n - 1, i + RADIUS)
    take = lambda idx: np.take(csum, idx, axis=axis)
    shape = [1, 1]
    shape[axis] = n
    return (take(hi + 1) - take(lo)) / (hi - lo + 1).reshape(shape)


def seen_planes(rgb):
    out = displayed(rgb.astype(np.float64))
    for c in range(3):
        p = out[:, :, c]
        for _ in range(2):
            p = box(box(p, 1), 0)
        out[:, :, c] = p
    return out


def seen_error(image, reference):
    a, b = seen_planes(image[:, :, :3]), seen_planes(reference[:, :, :3])
    d2 = (a - b) ** 2
    h, w = d2.shape[:2]
    worst, at = 0.0, (0, 0)
    for ty in range(0, h, TILE):
        for tx in range(0, w, TILE):
            t = np.sqrt(d2[ty:ty + TILE, tx:tx + TILE].mean())
            if t > worst:
                worst, at = t, (tx, ty)
    return np.sqrt(d2.mean()), worst, at


def load(path):
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        sys.exit(f"{path}: {buf.geterror()}")
    return buf.get_pixels(oiio.FLOAT)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    img, ref = load(sys.argv[1]), load(sys.argv[2])
    if img.shape[:2] != ref.shape[:2]:
        sys.exit(f"sizes differ: {img.shape[:2]} and {ref.shape[:2]}")
    whole, worst, (x, y) = seen_error(img, ref)
    print(f"seen error whole {whole:.4f} worst tile {worst:.4f} at ({x}, {y})")
