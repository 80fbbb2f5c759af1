#!/usr/bin/python3
"""Writes the material comparison scene as one .gltf: nine spheres under
one surrounding environment. Top row: non-metals with roughness 0, 0.25,
0.5, 1 and a transmission sphere; bottom row: metals with the same
roughnesses. The environment is a closed box whose inward faces emit
different colours plus one bright panel, so smooth spheres reflect
structure and rough ones blur it. No lights: both renderers see emissive
geometry only.

    make_sphere_grid.py OUT.gltf

spheres() gives each sphere's centre, radius and parameters, for masks.
"""
import base64, json, math, struct, sys

RADIUS = 1.0
SPACING = 2.4
CAMERA_Z = 15.0
YFOV = math.radians(30.0)
ASPECT = 2.0
ROUGHNESS = (0.0, 0.25, 0.5, 1.0)
DIELECTRIC = (0.8, 0.35, 0.2)
METAL = (0.95, 0.75, 0.45)


def spheres():
    out = []
    for i, r in enumerate(ROUGHNESS):
        x = (i - 2) * SPACING
        out.append({"name": "dielectric r%.2f" % r, "centre": (x, 1.3, 0.0), "metallic": 0.0, "roughness": r,
                    "color": DIELECTRIC})
        out.append({"name": "metal r%.2f" % r, "centre": (x + SPACING / 2, -1.3, 0.0), "metallic": 1.0,
                    "roughness": r, "color": METAL})
    out.append({"name": "transmission r0", "centre": (2 * SPACING, 1.3, 0.0), "metallic": 0.0, "roughness": 0.0,
                "color": (0.95, 0.95, 0.95), "transmission": 1.0})
    return out


def uv_sphere(rings=48, segments=96):
    pos, nrm, idx = [], [], []
    for r in range(rings + 1):
        th = math.pi * r / rings
        for s in range(segments + 1):
            ph = 2 * math.pi * s / segments
            n = (math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph))
            pos.append(tuple(RADIUS * c for c in n))
            nrm.append(n)
    for r in range(rings):
        for s in range(segments):
            a = r * (segments + 1) + s
            b = a + segments + 1
            idx += [a, b, a + 1, a + 1, b, b + 1]
    return pos, nrm, idx


# Inward-facing box faces: (corners counter-clockwise seen from the lit side, emission rgb). glTF emits from
# the front face only; Cycles from both, so every face must face the spheres.
B = 20.0
FACES = [
    ([(-B, B, -B), (B, B, -B), (B, B, B), (-B, B, B)], (1.6, 1.5, 1.3)),      # ceiling, warm
    ([(-B, -B, B), (B, -B, B), (B, -B, -B), (-B, -B, -B)], (0.15, 0.12, 0.1)),  # floor, dark
    ([(-B, -B, -B), (B, -B, -B), (B, B, -B), (-B, B, -B)], (0.3, 0.45, 0.8)),  # behind the spheres, blue
    ([(B, -B, B), (-B, -B, B), (-B, B, B), (B, B, B)], (0.5, 0.5, 0.5)),       # behind the camera
    ([(-B, -B, B), (-B, -B, -B), (-B, B, -B), (-B, B, B)], (0.8, 0.3, 0.15)),  # left, red
    ([(B, -B, -B), (B, -B, B), (B, B, B), (B, B, -B)], (0.2, 0.6, 0.25)),      # right, green
    ([(-4, 12, 4), (4, 12, 4), (4, 12, 10), (-4, 12, 10)], (12.0, 12.0, 11.0)),  # a bright panel up front, facing down
]


def main():
    buf = bytearray()
    accessors, views, meshes, nodes, materials = [], [], [], [], []

    def add(data, fmt, count, kind, comp, target, minmax=None):
        while len(buf) % 4:
            buf.append(0)
        off = len(buf)
        buf.extend(struct.pack("<%d%s" % (len(data), fmt), *data))
        views.append({"buffer": 0, "byteOffset": off, "byteLength": len(buf) - off, "target": target})
        acc = {"bufferView": len(views) - 1, "componentType": comp, "count": count, "type": kind}
        if minmax:
            acc["min"], acc["max"] = minmax
        accessors.append(acc)
        return len(accessors) - 1

    def mesh(pos, nrm, idx):
        flat = [c for p in pos for c in p]
        lo = [min(p[k] for p in pos) for k in range(3)]
        hi = [max(p[k] for p in pos) for k in range(3)]
        attributes = {"POSITION": add(flat, "f", len(pos), "VEC3", 5126, 34962, (lo, hi))}
        if nrm:
            attributes["NORMAL"] = add([c for n in nrm for c in n], "f", len(nrm), "VEC3", 5126, 34962)
        return attributes, add(idx, "I", len(idx), "SCALAR", 5125, 34963)

    pos, nrm, idx = uv_sphere()
    sphere_attr, sphere_idx = mesh(pos, nrm, idx)
    for s in spheres():
        m = {"name": s["name"], "pbrMetallicRoughness": {"baseColorFactor": list(s["color"]) + [1.0],
                                                        "metallicFactor": s["metallic"],
                                                        "roughnessFactor": s["roughness"]}}
        if s.get("transmission"):
            m["extensions"] = {"KHR_materials_transmission": {"transmissionFactor": s["transmission"]},
                               "KHR_materials_ior": {"ior": 1.5}}
        materials.append(m)
        meshes.append({"name": s["name"], "primitives": [{"attributes": sphere_attr, "indices": sphere_idx,
                                                          "material": len(materials) - 1}]})
        nodes.append({"name": s["name"], "mesh": len(meshes) - 1, "translation": list(s["centre"])})
    for i, (corners, emission) in enumerate(FACES):
        a, b, c = corners[0], corners[1], corners[2]
        n = [(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
             (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
             (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])]
        ln = math.sqrt(sum(v * v for v in n))
        n = [v / ln for v in n]
        attr, ind = mesh(corners, [n] * 4, [0, 1, 2, 0, 2, 3])
        k = max(emission)
        materials.append({"name": "sky %d" % i, "emissiveFactor": [v / k for v in emission],
                          "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0,
                                                   "roughnessFactor": 1.0},
                          "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": k}}})
        meshes.append({"name": "sky %d" % i, "primitives": [{"attributes": attr, "indices": ind,
                                                              "material": len(materials) - 1}]})
        nodes.append({"name": "sky %d" % i, "mesh": len(meshes) - 1})
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 0.0, CAMERA_Z]})
    doc = {
        "asset": {"version": "2.0", "generator": "tessera make_sphere_grid.py"},
        "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength"],
        "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes,
        "materials": materials, "accessors": accessors, "bufferViews": views,
        "cameras": [{"type": "perspective", "perspective": {"yfov": YFOV, "aspectRatio": ASPECT, "znear": 0.1}}],
        "buffers": [{"byteLength": len(buf),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf)).decode()}],
    }
    with open(sys.argv[1], "w") as f:
        json.dump(doc, f)


if __name__ == "__main__":
    main()
