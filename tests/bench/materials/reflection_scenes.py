#!/usr/bin/env python3
"""Three scenes with mirrors and glass that are not in the quality suite,
for checking the rasterizer's reflection probes beyond the scenes they
were tuned on (docs/raster-look.md): a flat mirror on a wall, a glass cube
(not a ball: refraction through the inscribed ellipsoid is an
approximation), two mirror balls either side of a cube near the room's
centre. Written with the suite's glTF helpers:

    python3 tests/bench/materials/reflection_scenes.py OUTDIR
"""
import os
import sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'quality', 'suite'))
from make_suite import BLUE, GREEN, RED, WHITE, Doc, box, ceiling_light, quad, room, sphere  # noqa: E402

def wall_mirror(d):
    w = d.material(WHITE)
    room(d, 4.0, 2.6, 4.0, {"floor": d.material((0.6, 0.55, 0.5)), "ceiling": w, "back": d.material(BLUE),
                            "front": w, "left": w, "right": d.material(GREEN)})
    ceiling_light(d, (0.5, 0.5), (0.3, 2.59, -0.3), 30.0)
    # A 1.6 x 1.2 m mirror on the left wall, 1 cm in front of it, facing +x.
    d.add("mirror", quad((-1.99, 1.3, -0.4), (0.0, 0.0, 0.8), (0.0, 0.6, 0.0)), d.material((0.95, 0.95, 0.95), metallic=1.0, roughness=0.0))
    d.add("orange box", box((0.5, 0.7, 0.5)), d.material((0.8, 0.35, 0.08)), t=(-1.1, 0.35, -0.9), yaw=25)
    d.add("blue ball", sphere(0.3), d.material((0.1, 0.2, 0.7)), t=(-0.9, 0.3, 0.4))
    d.camera((1.2, 1.4, 1.6), (-1.5, 1.0, -0.5), 55)

def glass_cube(d):
    w = d.material(WHITE)
    room(d, 4.0, 2.6, 4.0, {"floor": d.material((0.5, 0.5, 0.5)), "ceiling": w, "back": d.material(RED),
                            "front": w, "left": d.material(BLUE), "right": d.material(GREEN)})
    ceiling_light(d, (0.6, 0.6), (0.0, 2.59, 0.2), 25.0)
    d.add("pedestal", box((0.6, 0.6, 0.6)), w, t=(0.3, 0.3, -0.6))
    d.add("glass cube", box((0.45, 0.45, 0.45)), d.material((1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.5), t=(0.3, 0.825, -0.6), yaw=30)
    d.add("yellow ball", sphere(0.25), d.material((0.8, 0.7, 0.1)), t=(-0.7, 0.25, -1.2))
    d.camera((0.2, 1.3, 2.0), (0.2, 0.7, -0.8), 50)

def mirror_pair(d):
    w = d.material(WHITE)
    room(d, 4.0, 2.6, 4.0, {"floor": d.material((0.55, 0.5, 0.45)), "ceiling": w, "back": w,
                            "front": w, "left": d.material(RED), "right": d.material(GREEN)})
    ceiling_light(d, (0.5, 0.5), (0.0, 2.59, 0.0), 30.0)
    m = d.material((0.95, 0.95, 0.95), metallic=1.0, roughness=0.0)
    d.add("mirror a", sphere(0.35), m, t=(-0.55, 1.3, 0.0))
    d.add("mirror b", sphere(0.35), m, t=(0.55, 1.3, 0.0))
    d.add("cube", box((0.3, 0.3, 0.3)), d.material((0.2, 0.6, 0.8)), t=(0.0, 1.3, 0.3), yaw=45)
    d.add("stand", box((0.2, 1.15, 0.2)), w, t=(0.0, 0.575, 0.3))
    d.camera((0.0, 1.5, 1.9), (0.0, 1.2, 0.0), 55)

if __name__ == "__main__":
    if len(sys.argv) != 2 or sys.argv[1].startswith("-"):
        sys.exit(__doc__)
    os.makedirs(sys.argv[1], exist_ok=True)
    for name, build in (("wall-mirror", wall_mirror), ("glass-cube", glass_cube), ("mirror-pair", mirror_pair)):
        d = Doc(name)
        build(d)
        d.write(os.path.join(sys.argv[1], name + ".gltf"))
