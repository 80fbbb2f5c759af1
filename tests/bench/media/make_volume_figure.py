#!/usr/bin/env python3
"""The four looks of Schwenk's figure 5.16 as one glTF scene: spheres of
emission only, absorption only, (single-colour) scattering only, and
scattering lit from behind, each an index-matched boundary (smooth glass
of index 1) around a TSR_materials_volume medium, in a grey room under a
ceiling lamp with a lamp behind the fourth sphere.

    python3 make_volume_figure.py OUT.gltf
    tessera-render OUT.gltf --size 640x240 --spp 128 --filter pixel --output docs/volume-looks.png
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "quality", "suite"))
from make_suite import Doc, box, ceiling_light, quad, room, sphere  # noqa: E402

if len(sys.argv) != 2:
    sys.exit(__doc__)
d = Doc("volume-looks")
grey = d.material((0.5, 0.5, 0.5))
room(d, 7.0, 3.0, 5.0, {"floor": grey, "ceiling": grey, "back": grey, "front": grey, "left": grey, "right": grey})
ceiling_light(d, (2.0, 1.0), (0.0, 2.99, 0.0), 8.0)


def medium_sphere(name, x, volume):
    boundary = d.material((1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.0, volume=volume)
    d.add(name, sphere(0.6), boundary, t=(x, 0.9, -0.5))


medium_sphere("emission", -2.4, {"emission": [1.2, 0.5, 0.1]})
medium_sphere("absorption", -0.8, {"absorption": [0.3, 1.5, 3.0]})
medium_sphere("scattering", 0.8, {"scattering": [3.0, 3.0, 3.0], "phaseG": 0.0})
medium_sphere("scattering, lit from behind", 2.4, {"scattering": [3.0, 3.0, 3.0], "phaseG": 0.6})
# A small lamp behind the fourth sphere, facing the camera.
lamp = d.material((0.0, 0.0, 0.0), emissive=(1.0, 0.9, 0.8), strength=40.0)
d.add("back lamp", quad((2.4, 0.9, -1.4), (0.25, 0.0, 0.0), (0.0, 0.25, 0.0)), lamp)  # x cross y: faces +z
d.add("stand", box((0.2, 0.3, 0.2)), grey, t=(2.4, 0.15, -1.4))
d.camera((0.0, 1.1, 2.4), (0.0, 0.9, -0.5), 55)
d.write(sys.argv[1])
print("wrote", sys.argv[1])
