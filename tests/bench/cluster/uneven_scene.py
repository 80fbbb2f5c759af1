#!/usr/bin/env python3
"""A scene whose path-tracing cost is uneven over the frame, for the
cooperative load-balancing bench (balance.sh): a finely tessellated glass
torus knot turning in the top left corner (refraction: long paths) and the
default dome elsewhere (a miss ends the path at once); --floor adds a
diffuse floor across the bottom. glTF 2.0 with KHR_materials_transmission;
one camera; a two-second rotation of the knot.

    uneven_scene.py OUT.gltf [--segments 600 --sides 24] [--floor]
"""
import argparse
import base64
import json
import math
import struct


def knot(segments, sides, p=2, q=3, radius=0.11):
    """A (p, q) torus knot tube: positions, normals, triangle indices."""
    def centre(t):
        r = 0.35 + 0.15 * math.cos(q * t)
        return (r * math.cos(p * t), r * math.sin(p * t), 0.15 * math.sin(q * t))

    pos, nrm, idx = [], [], []
    for i in range(segments):
        t = 2 * math.pi * i / segments
        c = centre(t)
        d = centre(t + 1e-3)
        tx, ty, tz = d[0] - c[0], d[1] - c[1], d[2] - c[2]
        tl = math.sqrt(tx * tx + ty * ty + tz * tz)
        tx, ty, tz = tx / tl, ty / tl, tz / tl
        # a frame around the tangent
        ux, uy, uz = (0.0, 0.0, 1.0) if abs(tz) < 0.9 else (1.0, 0.0, 0.0)
        bx, by, bz = ty * uz - tz * uy, tz * ux - tx * uz, tx * uy - ty * ux
        bl = math.sqrt(bx * bx + by * by + bz * bz)
        bx, by, bz = bx / bl, by / bl, bz / bl
        nx, ny, nz = by * tz - bz * ty, bz * tx - bx * tz, bx * ty - by * tx
        for j in range(sides):
            a = 2 * math.pi * j / sides
            ox = math.cos(a) * bx + math.sin(a) * nx
            oy = math.cos(a) * by + math.sin(a) * ny
            oz = math.cos(a) * bz + math.sin(a) * nz
            pos += [c[0] + radius * ox, c[1] + radius * oy, c[2] + radius * oz]
            nrm += [ox, oy, oz]
    for i in range(segments):
        for j in range(sides):
            a = i * sides + j
            b = ((i + 1) % segments) * sides + j
            c = ((i + 1) % segments) * sides + (j + 1) % sides
            d = i * sides + (j + 1) % sides
            idx += [a, b, c, a, c, d]
    return pos, nrm, idx


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--segments", type=int, default=600)
    ap.add_argument("--sides", type=int, default=24)
    ap.add_argument("--floor", action="store_true", help="a diffuse floor across the bottom of the frame")
    a = ap.parse_args()

    kp, kn, ki = knot(a.segments, a.sides)
    fp = [-12, 0, -12, 12, 0, -12, 12, 0, 6, -12, 0, 6]
    fn = [0, 1, 0] * 4
    fi = [0, 2, 1, 0, 3, 2]
    times = [0.0, 1.0, 2.0]
    axis = (1 / math.sqrt(3), 1 / math.sqrt(3), 1 / math.sqrt(3))
    quats = []
    for k in range(3):
        h = math.pi * k / 2  # 0, 180 and 360 degrees
        quats += [axis[0] * math.sin(h), axis[1] * math.sin(h), axis[2] * math.sin(h), math.cos(h)]

    blob = bytearray()
    views, accessors = [], []

    def add(values, fmt, component, kind, count, target=None, minmax=False):
        while len(blob) % 4:
            blob.append(0)
        offset = len(blob)
        blob.extend(struct.pack("<%d%s" % (len(values), fmt), *values))
        view = {"buffer": 0, "byteOffset": offset, "byteLength": len(blob) - offset}
        if target:
            view["target"] = target
        views.append(view)
        acc = {"bufferView": len(views) - 1, "componentType": component, "count": count, "type": kind}
        if minmax:
            acc["min"] = [min(values[i::3]) for i in range(3)]
            acc["max"] = [max(values[i::3]) for i in range(3)]
        accessors.append(acc)
        return len(accessors) - 1

    F, U = 5126, 5125
    kpos = add(kp, "f", F, "VEC3", len(kp) // 3, 34962, True)
    knrm = add(kn, "f", F, "VEC3", len(kn) // 3, 34962)
    kidx = add(ki, "I", U, "SCALAR", len(ki), 34963)
    fpos = add(fp, "f", F, "VEC3", 4, 34962, True)
    fnrm = add(fn, "f", F, "VEC3", 4, 34962)
    fidx = add(fi, "I", U, "SCALAR", 6, 34963)
    tin = add(times, "f", F, "SCALAR", 3)
    accessors[tin]["min"], accessors[tin]["max"] = [0.0], [2.0]
    tout = add(quats, "f", F, "VEC4", 3)

    gltf = {
        "asset": {"version": "2.0", "generator": "tessera tests/bench/cluster/uneven_scene.py"},
        "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2] if a.floor else [0, 2]}],
        "nodes": [
            {"name": "camera", "camera": 0, "translation": [0, 0.2, 5]},
            {"name": "floor", "mesh": 1, "translation": [0, -1.2, 0]},
            {"name": "knot", "mesh": 0, "translation": [-1.75, 1.15, 0]},
        ],
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": math.radians(42), "aspectRatio": 4 / 3, "znear": 0.05}}],
        "meshes": [
            {"name": "glass knot",
             "primitives": [{"attributes": {"POSITION": kpos, "NORMAL": knrm}, "indices": kidx, "material": 0}]},
            {"name": "floor",
             "primitives": [{"attributes": {"POSITION": fpos, "NORMAL": fnrm}, "indices": fidx, "material": 1}]},
        ],
        "materials": [
            {"name": "glass",
             "pbrMetallicRoughness": {"baseColorFactor": [0.55, 0.8, 1.0, 1.0], "metallicFactor": 0.0,
                                      "roughnessFactor": 0.0},
             "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                            "KHR_materials_ior": {"ior": 1.5}}},
            {"name": "floor",
             "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1.0], "metallicFactor": 0.0,
                                      "roughnessFactor": 0.8}},
        ],
        "animations": [{"name": "turn",
                        "samplers": [{"input": tin, "output": tout, "interpolation": "LINEAR"}],
                        "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}}]}],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
        "bufferViews": views,
        "accessors": accessors,
    }
    with open(a.out, "w") as f:
        json.dump(gltf, f)
    print("wrote %s: %d knot triangles" % (a.out, len(ki) // 3))


if __name__ == "__main__":
    main()
