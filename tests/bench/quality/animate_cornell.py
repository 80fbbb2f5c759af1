#!/usr/bin/env python3
"""Animates make_cornell.py's Cornell box for the temporal quality harness.

    animate_cornell.py IN.gltf OUT.gltf [SECONDS]

Adds one glTF animation over SECONDS (default 4): the camera trucks 120
units to its right and 40 closer (a moving camera: what it sees changes
while the light does not), the point light rises towards the ceiling and
the first box slides along the floor (moving light, moving contact
shadow). Keys are linear; the rest of the file is copied unchanged.
"""
import base64
import json
import struct
import sys


def main() -> int:
    if len(sys.argv) not in (3, 4):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    src, dst = sys.argv[1], sys.argv[2]
    seconds = float(sys.argv[3]) if len(sys.argv) == 4 else 4.0
    if not seconds > 0:
        print(f"error: SECONDS must be positive, got {seconds}", file=sys.stderr)
        return 2
    with open(src) as f:
        gltf = json.load(f)
    nodes = gltf["nodes"]
    camera = next(i for i, n in enumerate(nodes) if "camera" in n)
    light = next(i for i, n in enumerate(nodes) if "KHR_lights_punctual" in n.get("extensions", {}))
    box = next(i for i, n in enumerate(nodes) if "mesh" in n and n["mesh"] == 1)

    cam0 = nodes[camera]["translation"]
    light0 = nodes[light]["translation"]
    tracks = {
        camera: [cam0, [cam0[0] + 120.0, cam0[1], cam0[2] + 40.0]],
        light: [light0, [light0[0] - 60.0, light0[1] + 180.0, light0[2] - 80.0]],
        box: [[0.0, 0.0, 0.0], [60.0, 0.0, -40.0]],
    }
    times = [0.0, seconds]
    blob = struct.pack("<2f", *times)
    offsets = []
    for keys in tracks.values():
        offsets.append(len(blob))
        blob += struct.pack("<6f", *keys[0], *keys[1])

    buffer = len(gltf["buffers"])
    gltf["buffers"].append({"byteLength": len(blob),
                            "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()})
    views, accessors = gltf["bufferViews"], gltf["accessors"]

    def accessor(offset, length, count, kind, lo, hi):
        views.append({"buffer": buffer, "byteOffset": offset, "byteLength": length})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": count, "type": kind,
                          "min": lo, "max": hi})
        return len(accessors) - 1

    time_accessor = accessor(0, 8, 2, "SCALAR", [0.0], [seconds])
    samplers, channels = [], []
    for (node, keys), offset in zip(tracks.items(), offsets):
        lo = [min(a, b) for a, b in zip(*keys)]
        hi = [max(a, b) for a, b in zip(*keys)]
        samplers.append({"input": time_accessor, "output": accessor(offset, 24, 2, "VEC3", lo, hi),
                         "interpolation": "LINEAR"})
        channels.append({"sampler": len(samplers) - 1, "target": {"node": node, "path": "translation"}})
    gltf["animations"] = [{"name": "moving camera, light and box", "samplers": samplers, "channels": channels}]
    with open(dst, "w") as f:
        json.dump(gltf, f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
