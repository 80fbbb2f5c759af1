#!/usr/bin/env python3
"""The figure of docs/workload.md from balance.sh --out DIR: a frame beside
its workload images with the balancer off and on (8 px gaps), and the
colours' legend (rows: nodes 0 to 7; columns: a tile's time from none to
the frame's slowest, as cluster::workloadShade draws it).

    /usr/bin/python3 workload_figure.py DIR FRAME OUT.png LEGEND.png
FRAME is the four-digit frame number (0011). Needs numpy and OpenImageIO.
"""
import sys

import numpy as np
import OpenImageIO as oiio


def read(path):
    buf = oiio.ImageBuf(path)
    return buf.get_pixels(oiio.FLOAT)[:, :, :3]


def write(path, pixels):
    spec = oiio.ImageSpec(pixels.shape[1], pixels.shape[0], 3, oiio.UINT8)
    out = oiio.ImageOutput.create(path)
    out.open(path, spec)
    out.write_image(np.clip(pixels * 255 + 0.5, 0, 255).astype(np.uint8))
    out.close()


def main():
    folder, frame, figure, legend = sys.argv[1:5]
    images = [read("%s/on.%s.png" % (folder, frame)), read("%s/off.%s.workload.png" % (folder, frame)),
              read("%s/on.%s.workload.png" % (folder, frame))]
    h, w = images[0].shape[:2]
    gap = 8
    out = np.ones((h, 3 * w + 2 * gap, 3), np.float32)
    for i, image in enumerate(images):
        out[:, i * (w + gap):i * (w + gap) + w] = image
    write(figure, out)

    srgb = [(230, 159, 0), (86, 180, 233), (0, 158, 115), (240, 228, 66), (0, 114, 178), (213, 94, 0),
            (204, 121, 167), (153, 153, 153)]
    cell, shades = 24, [0.2, 0.4, 0.6, 0.8, 1.0]
    swatches = np.ones((len(srgb) * cell, len(shades) * cell, 3), np.float32)
    for n, c in enumerate(srgb):
        lin = np.array([v / 255 for v in c])
        lin = np.where(lin <= 0.04045, lin / 12.92, ((lin + 0.055) / 1.055) ** 2.4)
        for k, s in enumerate(shades):
            v = lin * s
            v = np.where(v <= 0.0031308, v * 12.92, 1.055 * v ** (1 / 2.4) - 0.055)
            swatches[n * cell + 2:(n + 1) * cell - 2, k * cell + 2:(k + 1) * cell - 2] = v
    write(legend, swatches)


if __name__ == "__main__":
    main()
