#!/usr/bin/env python3
"""Textured (heterogeneous) media as one glTF scene: a cloud of white
scattering medium whose density is a 3D texture of soft blobs, and a cube
of absorbing medium banded along its height, each behind an index-matched
boundary, in a grey room under a ceiling lamp. The textures are PNGs of
textureSlices slices stacked top (lowest z) to bottom (docs/volumes.md).

    python3 make_cloud_figure.py OUT.gltf
    tessera-render OUT.gltf --size 480x270 --spp 256 --filter pixel --output docs/volume-textures.png
"""
import math
import os
import random
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "quality", "suite"))
from make_suite import Doc, box, ceiling_light, png, room  # noqa: E402

N = 32  # texels along each axis of the cloud


def cloud_density():
    """Soft blobs inside the unit cube, fading to nothing at its faces."""
    rng = random.Random(5)
    blobs = [((rng.uniform(0.2, 0.8), rng.uniform(0.25, 0.6), rng.uniform(0.2, 0.8)), rng.uniform(0.07, 0.15))
             for _ in range(24)]

    def density(x, y, z):
        d = sum(math.exp(-((x - c[0]) ** 2 + (y - c[1]) ** 2 + (z - c[2]) ** 2) / (r * r)) for c, r in blobs)
        return min(1.0, 1.5 * d * d)

    def pixel(px, py):
        z, row = divmod(py, N)
        v = density((px + 0.5) / N, 1.0 - (row + 0.5) / N, (z + 0.5) / N)  # top row: highest y
        return (round(255 * v),) * 3
    return png(N, N * N, pixel)


def bands():
    """Absorption colour by height: one slice of 1 x 8, bands of tinted glass."""
    colours = [(40, 200, 230), (230, 230, 230), (230, 120, 30), (230, 230, 230)] * 2
    return png(1, 8, lambda x, y: colours[y])


if len(sys.argv) != 2:
    sys.exit(__doc__)
d = Doc("volume-textures")
grey = d.material((0.5, 0.5, 0.5))
room(d, 5.0, 3.0, 4.0, {"floor": grey, "ceiling": grey, "back": grey, "front": grey, "left": grey, "right": grey})
ceiling_light(d, (1.5, 1.0), (0.0, 2.99, -0.5), 10.0)
cloud = {"scattering": [25.0, 25.0, 25.0], "phaseG": 0.3,
         "scatteringTexture": {"index": d.texture(cloud_density())}, "textureSlices": N}
d.add("cloud", box((1.4, 1.4, 1.4)), d.material((1, 1, 1), roughness=0.0, transmission=1.0, ior=1.0, volume=cloud),
      t=(-0.9, 1.2, -0.8))
banded = {"absorption": [2.5, 2.5, 2.5], "absorptionTexture": {"index": d.texture(bands())}}
d.add("banded cube", box((0.9, 1.4, 0.9)),
      d.material((1, 1, 1), roughness=0.0, transmission=1.0, ior=1.0, volume=banded), t=(1.1, 0.7, -0.9), yaw=25)
d.camera((0.0, 1.4, 1.9), (0.0, 1.0, -0.8), 62)
d.write(sys.argv[1])
print("wrote", sys.argv[1])
