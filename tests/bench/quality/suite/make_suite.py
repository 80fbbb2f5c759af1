#!/usr/bin/env python3
"""Write a suite of glTF 2.0 scenes on which denoising filters are judged,
and a manifest OUTDIR/suite.json (see README.md beside this script).

    python3 make_suite.py OUTDIR

Each scene stresses one thing (indirect light, rough metal, thin geometry,
textures, caustics, an environment map, small lights, darkness, ...). They
are plain test scenes, not tuned to flatter any filter. Units are metres,
+y is up, every scene has one perspective camera with aspect ratio 1.
Standard library only; buffers and PNG textures are embedded as data URIs.
"""
import base64, json, math, os, struct, sys, zlib

ASSIMP = "/usr/share/assimp/models/glTF2"

# ---------------------------------------------------------------- vectors

def add(a, b): return tuple(x + y for x, y in zip(a, b))
def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def mul(a, k): return tuple(x * k for x in a)
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def norm(a):
    n = math.sqrt(sum(x * x for x in a))
    return tuple(x / n for x in a)


def yaw_quat(deg):
    """Rotation about +y, as a glTF (x, y, z, w) quaternion."""
    h = math.radians(deg) / 2
    return [0.0, math.sin(h), 0.0, math.cos(h)]


def look_quat(eye, at):
    """Quaternion turning glTF's camera (looking down -z, +y up) towards `at`."""
    f = norm(sub(at, eye))
    r = norm(cross(f, (0.0, 1.0, 0.0)))
    u = cross(r, f)
    m = [[r[0], u[0], -f[0]], [r[1], u[1], -f[1]], [r[2], u[2], -f[2]]]  # columns r, u, -f
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = 2 * math.sqrt(tr + 1)
        return [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4]
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2 * math.sqrt(1 + m[i][i] - m[j][j] - m[k][k])
    q = [0.0] * 4
    q[i], q[j], q[k], q[3] = s / 4, (m[j][i] + m[i][j]) / s, (m[k][i] + m[i][k]) / s, (m[k][j] - m[j][k]) / s
    return q

# --------------------------------------------------------------- geometry
# A mesh is a dict of lists: p (positions), n (normals), t (uvs), i (indices).
# Front faces wind counter-clockwise: emission leaves the front side only.

def mesh():
    return {"p": [], "n": [], "t": [], "i": []}


def merge(*meshes):
    out = mesh()
    for m in meshes:
        base = len(out["p"])
        for k in "pnt":
            out[k] += m[k]
        out["i"] += [base + x for x in m["i"]]
    return out


def quad(c, u, v, uv=(1.0, 1.0)):
    """Rectangle c +- u +- v facing u x v; uv (0, 0) at the corner c - u + v
    so an image reads upright when u points right and v up."""
    n = norm(cross(u, v))
    m = mesh()
    m["p"] = [add(add(c, mul(u, su)), mul(v, sv)) for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    m["n"] = [n] * 4
    m["t"] = [(0.0, uv[1]), (uv[0], uv[1]), (uv[0], 0.0), (0.0, 0.0)]
    m["i"] = [0, 1, 2, 0, 2, 3]
    return m


def box(size, c=(0.0, 0.0, 0.0)):
    """Axis-aligned box of full size `size` centred at c; flat normals."""
    h = mul(size, 0.5)
    faces = []
    for k in range(3):
        for s in (1, -1):
            n = [0.0, 0.0, 0.0]; n[k] = s
            u = [0.0, 0.0, 0.0]; u[(k + 1) % 3] = h[(k + 1) % 3]
            v = mul(norm(cross(n, u)), h[(k + 2) % 3])
            faces.append(quad(add(c, mul(n, h[k])), tuple(u), v))
    return merge(*faces)


def sphere(r, c=(0.0, 0.0, 0.0), rings=24):
    """UV sphere with smooth normals; the seam column is duplicated for uvs."""
    segs = 2 * rings
    m = mesh()
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(segs + 1):
            ph = 2 * math.pi * j / segs
            n = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            m["p"].append(add(c, mul(n, r)))
            m["n"].append(n)
            m["t"].append((j / segs, i / rings))
    for i in range(rings):
        for j in range(segs):
            a, b = i * (segs + 1) + j, i * (segs + 1) + j + 1
            cc, d = a + segs + 1, b + segs + 1
            if i > 0:
                m["i"] += [a, b, d]
            if i < rings - 1:
                m["i"] += [a, d, cc]
    return m


def frustum(r0, r1, h, c=(0.0, 0.0, 0.0), segs=24):
    """Cylinder (r0 == r1) or cone (r1 == 0) standing on c, smooth sides, flat bottom cap."""
    m = mesh()
    for j in range(segs + 1):
        ph = 2 * math.pi * j / segs
        cs, sn = math.cos(ph), math.sin(ph)
        n = norm((cs * h, r0 - r1, sn * h))
        m["p"] += [add(c, (r0 * cs, 0.0, r0 * sn)), add(c, (r1 * cs, h, r1 * sn))]
        m["n"] += [n, n]
        m["t"] += [(j / segs, 1.0), (j / segs, 0.0)]
    for j in range(segs):
        b0, t0, b1, t1 = 2 * j, 2 * j + 1, 2 * j + 2, 2 * j + 3
        m["i"] += [b0, t0, b1, b1, t0, t1]
    cap = mesh()  # bottom disc, facing down
    cap["p"] = [c] + [add(c, (r0 * math.cos(2 * math.pi * j / segs), 0.0, r0 * math.sin(2 * math.pi * j / segs)))
                      for j in range(segs)]
    cap["n"] = [(0.0, -1.0, 0.0)] * (segs + 1)
    cap["t"] = [(0.5, 0.5)] * (segs + 1)
    cap["i"] = sum(([0, 1 + j, 1 + (j + 1) % segs] for j in range(segs)), [])
    return merge(m, cap)


def prism_roof(w, d, h, c=(0.0, 0.0, 0.0)):
    """Gable roof: a triangular prism along z on top of c, flat normals."""
    a, b, top = (-w / 2, 0.0, 0.0), (w / 2, 0.0, 0.0), (0.0, h, 0.0)
    z0, z1 = (0.0, 0.0, -d / 2), (0.0, 0.0, d / 2)
    def tri(p, q, r):
        n = norm(cross(sub(q, p), sub(r, p)))
        return {"p": [add(c, x) for x in (p, q, r)], "n": [n] * 3, "t": [(0, 0), (1, 0), (0, 1)], "i": [0, 1, 2]}
    def slope(p, q):  # quad p..q along z
        return merge(tri(add(p, z1), add(q, z1), add(q, z0)), tri(add(p, z1), add(q, z0), add(p, z0)))
    return merge(slope(b, top), slope(top, a), tri(add(a, z1), add(b, z1), add(top, z1)),
                 tri(add(b, z0), add(a, z0), add(top, z0)))


def room(doc, w, h, d, mats, cz=0.0):
    """Six inward-facing walls of x in [-w/2, w/2], y in [0, h], z in cz +- d/2.
    mats: floor, ceiling, left, right, back (far, -z), front (behind the
    camera, +z); a missing key leaves that wall out. Floor uv repeat: mats['floor_uv']."""
    X, Y, Z = (w / 2, 0.0, 0.0), (0.0, h / 2, 0.0), (0.0, 0.0, d / 2)
    walls = {
        "floor": quad((0.0, 0.0, cz), Z, X, mats.get("floor_uv", (1.0, 1.0))),
        "ceiling": quad((0.0, h, cz), X, Z),
        "back": quad((0.0, h / 2, cz - d / 2), X, Y),
        "front": quad((0.0, h / 2, cz + d / 2), Y, X),
        "left": quad((-w / 2, h / 2, cz), Y, Z),
        "right": quad((w / 2, h / 2, cz), Z, Y),
    }
    for k, m in walls.items():
        if mats.get(k) is not None:
            doc.add(k, m, mats[k])

# ------------------------------------------------------------------ images

def png(w, h, pixel):
    """8-bit RGB PNG; pixel(x, y) -> (r, g, b) in 0..255, y = 0 at the top."""
    raw = b"".join(b"\0" + bytes(c for x in range(w) for c in pixel(x, y)) for y in range(h))
    def chunk(t, data):
        return struct.pack(">I", len(data)) + t + data + struct.pack(">I", zlib.crc32(t + data) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


# 5x7 glyphs, one 5-bit row each, top row first: just the letters used.
FONT = {
    "A": (14, 17, 17, 31, 17, 17, 17), "D": (30, 17, 17, 17, 17, 17, 30), "E": (31, 16, 16, 30, 16, 16, 31),
    "F": (31, 16, 16, 30, 16, 16, 16), "I": (14, 4, 4, 4, 4, 4, 14), "L": (16, 16, 16, 16, 16, 16, 31),
    "N": (17, 25, 21, 19, 17, 17, 17), "O": (14, 17, 17, 17, 17, 17, 14), "R": (30, 17, 17, 30, 20, 18, 17),
    "S": (15, 16, 16, 14, 1, 1, 30), "T": (31, 4, 4, 4, 4, 4, 4), "1": (4, 12, 4, 4, 4, 4, 14),
    "2": (14, 17, 1, 2, 4, 8, 31), "8": (14, 17, 17, 14, 17, 17, 14), " ": (0,) * 7,
}


def poster_png():
    """64x32 poster: three lines of 5x7 text, dark on cream, the first red."""
    lines = ["TESSERA", "DENOISE", "TEST 128"]
    ink = {}
    for li, text in enumerate(lines):
        x0, y0 = (64 - 6 * len(text) + 1) // 2, 3 + 10 * li
        for ci, ch in enumerate(text):
            for row, bits in enumerate(FONT[ch]):
                for col in range(5):
                    if bits >> (4 - col) & 1:
                        ink[(x0 + 6 * ci + col, y0 + row)] = (200, 20, 20) if li == 0 else (20, 20, 30)
    return png(64, 32, lambda x, y: ink.get((x, y), (235, 225, 190)))


def checker_png(cell=3, size=64):
    return png(size, size, lambda x, y: (225, 225, 215) if (x // cell + y // cell) % 2 else (35, 35, 45))


def stripes_png():
    return png(32, 32, lambda x, y: (30, 60, 180) if (x + y) // 4 % 2 else (230, 200, 40))


def write_pfm(path, w, h, radiance):
    """Colour PFM, little-endian (scale -1); rows are stored bottom first, as PFM defines.
    radiance(x, y) with y = 0 the top row of the image (the zenith)."""
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (w, h))
        for y in reversed(range(h)):
            f.write(b"".join(struct.pack("<3f", *radiance(x, y)) for x in range(w)))

# ----------------------------------------------------------------- document

class Doc:
    def __init__(self, name):
        self.name = name
        self.blob, self.views, self.accessors = bytearray(), [], []
        self.meshes, self.materials, self.nodes, self.lights = [], [], [], []
        self.images, self.textures, self.cameras, self.ext = [], [], [], set()
        self.cache = {}
        self.medium = None  # TSR_scene_medium: fog filling the scene
        self.animations = []
        self.motion = None  # the harness's shutter and frame interval (suite.json), for scenes that move

    def material(self, color, metallic=0.0, roughness=1.0, emissive=None, strength=None, texture=None,
                 transmission=None, ior=None, volume=None):
        m = {"pbrMetallicRoughness": {"baseColorFactor": [*color, 1.0], "metallicFactor": metallic,
                                      "roughnessFactor": roughness}}
        ext = {}
        if texture is not None:
            m["pbrMetallicRoughness"]["baseColorTexture"] = {"index": self.texture(texture)}
        if emissive is not None:
            m["emissiveFactor"] = list(emissive)
        if strength is not None:
            ext["KHR_materials_emissive_strength"] = {"emissiveStrength": strength}
        if transmission is not None:
            ext["KHR_materials_transmission"] = {"transmissionFactor": transmission}
        if ior is not None:
            ext["KHR_materials_ior"] = {"ior": ior}
        if volume is not None:  # Tessera's volume extension (docs/volumes.md)
            ext["TSR_materials_volume"] = volume
        if ext:
            m["extensions"] = ext
            self.ext.update(ext)
        self.materials.append(m)
        return len(self.materials) - 1

    def texture(self, png_bytes):
        """A PNG as a texture of the document; returns its index."""
        self.images.append({"uri": "data:image/png;base64," + base64.b64encode(png_bytes).decode()})
        self.textures.append({"sampler": 0, "source": len(self.images) - 1})
        return len(self.textures) - 1

    def view(self, data, target):
        while len(self.blob) % 4:
            self.blob.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)})
        if target is not None:  # animation data has no buffer target
            self.views[-1]["target"] = target
        self.blob.extend(data)
        return len(self.views) - 1

    def accessor(self, rows, fmt, typ, target=34962):
        acc = {"bufferView": self.view(b"".join(struct.pack("<" + fmt, *r) for r in rows), target),
               "componentType": 5126, "count": len(rows), "type": typ}
        if typ == "VEC3":
            acc["min"] = [min(r[k] for r in rows) for k in range(3)]
            acc["max"] = [max(r[k] for r in rows) for k in range(3)]
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def add(self, name, m, material, t=None, yaw=None):
        key = (id(m), material)  # the same mesh object and material: one glTF mesh, instanced
        if key not in self.cache:
            attrs = {"POSITION": self.accessor(m["p"], "3f", "VEC3"), "NORMAL": self.accessor(m["n"], "3f", "VEC3"),
                     "TEXCOORD_0": self.accessor(m["t"], "2f", "VEC2")}
            idx = self.view(struct.pack("<%dI" % len(m["i"]), *m["i"]), 34963)
            self.accessors.append({"bufferView": idx, "componentType": 5125, "count": len(m["i"]), "type": "SCALAR"})
            self.meshes.append({"name": name, "primitives": [{"attributes": attrs, "material": material,
                                                              "indices": len(self.accessors) - 1}]})
            self.cache[key] = (len(self.meshes) - 1, m)  # keeps m alive so its id stays unique
        node = {"name": name, "mesh": self.cache[key][0]}
        if t is not None:
            node["translation"] = list(t)
        if yaw is not None:
            node["rotation"] = yaw_quat(yaw)
        self.nodes.append(node)

    def animate(self, node, path, times, values):
        """A LINEAR channel of the document's one animation (importers such
        as Blender's play one glTF animation at a time): node index `node`,
        path translation (xyz rows) or rotation (xyzw quaternion rows)."""
        def scalars(xs):
            acc = {"bufferView": self.view(struct.pack("<%df" % len(xs), *xs), None), "componentType": 5126,
                   "count": len(xs), "type": "SCALAR", "min": [min(xs)], "max": [max(xs)]}
            self.accessors.append(acc)
            return len(self.accessors) - 1
        out = self.accessor(values, "%df" % len(values[0]), "VEC3" if len(values[0]) == 3 else "VEC4", None)
        if not self.animations:
            self.animations.append({"name": self.name, "samplers": [], "channels": []})
        a = self.animations[0]
        a["samplers"].append({"input": scalars(times), "output": out, "interpolation": "LINEAR"})
        a["channels"].append({"sampler": len(a["samplers"]) - 1, "target": {"node": node, "path": path}})

    def point_light(self, name, pos, intensity, color=(1.0, 1.0, 1.0)):
        """KHR_lights_punctual point light; Tessera reads intensity as W/sr."""
        self.ext.add("KHR_lights_punctual")
        self.lights.append({"name": name, "type": "point", "color": list(color), "intensity": intensity})
        self.nodes.append({"name": name, "translation": list(pos),
                           "extensions": {"KHR_lights_punctual": {"light": len(self.lights) - 1}}})

    def camera(self, eye, at, fov_deg, lens=None):
        """lens: (aperture radius, focus distance) in metres, as Tessera's
        TSR_camera_lens (docs/camera.md); None is glTF's pinhole."""
        self.cameras.append({"name": "camera", "type": "perspective", "perspective": {
            "yfov": math.radians(fov_deg), "aspectRatio": 1.0, "znear": 0.01, "zfar": 1000.0}})
        if lens is not None:
            self.cameras[-1]["extensions"] = {"TSR_camera_lens": {"apertureRadius": lens[0], "focusDistance": lens[1]}}
            self.ext.add("TSR_camera_lens")
        self.nodes.append({"name": "camera", "camera": 0, "translation": list(eye), "rotation": look_quat(eye, at)})

    def write(self, path):
        assert len(self.cameras) == 1
        doc = {"asset": {"version": "2.0", "generator": "tests/bench/quality/suite/make_suite.py"},
               "scene": 0, "scenes": [{"name": self.name, "nodes": list(range(len(self.nodes)))}],
               "nodes": self.nodes, "meshes": self.meshes, "materials": self.materials,
               "accessors": self.accessors, "bufferViews": self.views, "cameras": self.cameras,
               "buffers": [{"byteLength": len(self.blob), "uri": "data:application/octet-stream;base64," +
                            base64.b64encode(bytes(self.blob)).decode()}]}
        if self.images:
            doc.update(images=self.images, textures=self.textures,
                       samplers=[{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}])
        if self.lights:
            doc["extensions"] = {"KHR_lights_punctual": {"lights": self.lights}}
        if self.animations:
            doc["animations"] = self.animations
        if self.medium:
            doc["scenes"][0]["extensions"] = {"TSR_scene_medium": self.medium}
            self.ext.add("TSR_scene_medium")
        if self.ext:
            doc["extensionsUsed"] = sorted(self.ext)
        with open(path, "w") as f:
            json.dump(doc, f)

# ------------------------------------------------------------------ scenes
# Shared colours (linear). Walls are matte paint, not pure primaries.
WHITE, RED, GREEN, BLUE = (0.73, 0.73, 0.73), (0.63, 0.07, 0.05), (0.12, 0.45, 0.09), (0.1, 0.18, 0.55)
DOWN_X, DOWN_Z = (0.5, 0.0, 0.0), (0.0, 0.0, 0.5)  # a 1 m ceiling quad X x Z faces down: x cross z = -y


def ceiling_light(doc, size, pos, radiance, color=(1.0, 0.95, 0.88)):
    """Emissive quad facing down, just under the ceiling (a diffuse area light)."""
    lamp = doc.material((0.8, 0.8, 0.8), emissive=color, strength=radiance)
    doc.add("ceiling light", quad(pos, mul(DOWN_X, size[0]), mul(DOWN_Z, size[1])), lamp)


def indirect_room(d):
    """The issue's scene: light reaches the room only after bouncing off the ceiling."""
    w = d.material(WHITE)
    room(d, 5.0, 3.0, 5.0, {"floor": w, "ceiling": w, "back": w, "front": w,
                            "left": d.material(RED), "right": d.material(GREEN)})
    # Panel 0.5 m under the ceiling, emitting upwards (z x x = +y); its back
    # (dark, non-emitting) faces the room.
    panel = d.material((0.05, 0.05, 0.05), emissive=(1.0, 0.95, 0.85), strength=70.0)
    d.add("panel", quad((0.0, 2.5, -0.6), (0.0, 0.0, 0.3), (0.3, 0.0, 0.0)), panel)
    d.add("metal sphere", sphere(0.6), d.material((0.9, 0.8, 0.6), metallic=1.0, roughness=0.3), t=(-0.9, 0.6, -0.9))
    d.add("box", box((0.9, 1.2, 0.9)), d.material((0.7, 0.7, 0.7)), t=(1.0, 0.6, -1.1), yaw=25)
    d.camera((0.0, 1.4, 2.4), (0.0, 1.1, -1.0), 60)


def foggy_room(d):
    """A hazy room: light scattered by the air itself, a lamp's glow, soft shafts past a pillar."""
    w = d.material(WHITE)
    room(d, 5.0, 3.0, 5.0, {"floor": w, "ceiling": w, "back": w, "front": w,
                            "left": d.material(RED), "right": d.material(BLUE)})
    ceiling_light(d, (0.6, 0.6), (0.4, 2.99, -0.8), 60.0)
    d.add("pillar", box((0.3, 3.0, 0.3)), d.material((0.2, 0.2, 0.2)), t=(-0.2, 1.5, -0.6))
    d.add("sphere", sphere(0.45), d.material((0.8, 0.75, 0.6), metallic=1.0, roughness=0.3), t=(1.0, 0.45, -1.2))
    d.medium = {"scattering": [0.12, 0.12, 0.12], "absorption": [0.02, 0.02, 0.02], "phaseG": 0.3}
    d.camera((0.0, 1.4, 2.4), (0.0, 1.1, -1.0), 60)


def fog_glass(d):
    """The volume issue's scene: a glass sphere of milky medium in a hazy Cornell-like room."""
    w = d.material(WHITE)
    room(d, 4.0, 3.0, 4.0, {"floor": w, "ceiling": w, "back": w, "front": w,
                            "left": d.material(RED), "right": d.material(GREEN)})
    ceiling_light(d, (1.0, 1.0), (0.0, 2.99, -0.5), 15.0)
    milk = {"scattering": [4.0, 4.2, 4.4], "absorption": [0.1, 0.2, 0.4], "phaseG": 0.3}
    d.add("milk glass", sphere(0.5), d.material((1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.5,
                                               volume=milk), t=(-0.6, 0.5, -0.8))
    d.add("box", box((0.8, 1.4, 0.8)), d.material((0.7, 0.7, 0.7)), t=(0.8, 0.7, -1.0), yaw=20)
    d.medium = {"scattering": [0.08, 0.08, 0.08], "absorption": [0.01, 0.01, 0.01], "phaseG": 0.2}
    d.camera((0.0, 1.4, 1.9), (0.0, 1.0, -1.0), 60)


def rough_metal(d):
    w = d.material(WHITE)
    room(d, 6.0, 3.0, 5.0, {"floor": w, "ceiling": w, "back": w, "front": d.material(BLUE),
                            "left": d.material(RED), "right": d.material(GREEN)})
    ceiling_light(d, (1.2, 1.2), (0.0, 2.99, 0.0), 12.0)
    for x, r in ((-1.15, 0.1), (0.0, 0.3), (1.15, 0.6)):
        d.add("metal %.1f" % r, sphere(0.5), d.material((0.9, 0.9, 0.9), metallic=1.0, roughness=r),
              t=(x, 0.5, -0.8))
    # A dark pillar and a yellow box give the reflections edges to blur.
    d.add("pillar", box((0.3, 3.0, 0.3)), d.material((0.08, 0.08, 0.08)), t=(-2.2, 1.5, 1.6))
    d.add("crate", box((0.8, 0.8, 0.8)), d.material((0.75, 0.6, 0.1)), t=(1.9, 0.4, 1.5), yaw=30)
    d.camera((0.0, 1.3, 2.4), (0.0, 0.6, -0.8), 60)


def glossy_dielectric(d):
    w = d.material(WHITE)
    room(d, 5.0, 3.0, 5.0, {"floor": d.material((0.55, 0.45, 0.35), roughness=0.25), "ceiling": w, "back": w,
                            "front": w, "left": d.material(BLUE), "right": w})
    ceiling_light(d, (0.8, 0.8), (0.0, 2.99, 0.5), 8.0)
    d.point_light("key", (1.2, 2.2, 0.6), 6.0)
    # Rough glass: the glossy dielectric Tessera's path tracer has (GGX
    # reflection and refraction); a metallic-0 opaque "plastic" is Lambert there.
    d.add("frosted sphere", sphere(0.6),
          d.material((0.95, 0.75, 0.6), roughness=0.2, transmission=1.0, ior=1.5), t=(-0.3, 0.6, -0.7))
    d.add("block", box((0.6, 0.6, 0.6)), d.material((0.6, 0.6, 0.6)), t=(1.2, 0.3, -1.3), yaw=-20)
    d.camera((0.3, 1.4, 2.3), (-0.1, 0.6, -0.8), 55)


def textures(d):
    w = d.material(WHITE)
    floor = d.material((1.0, 1.0, 1.0), texture=checker_png())
    room(d, 5.0, 3.0, 6.0, {"floor": floor, "floor_uv": (4.0, 4.0), "ceiling": w, "back": w, "front": w,
                            "left": d.material((0.6, 0.55, 0.45)), "right": d.material((0.45, 0.55, 0.6))})
    ceiling_light(d, (1.0, 1.0), (0.0, 2.99, 0.0), 16.0)
    d.add("poster", quad((0.0, 1.6, -2.99), (1.2, 0.0, 0.0), (0.0, 0.6, 0.0)),
          d.material((1.0, 1.0, 1.0), texture=poster_png()))
    d.add("checker cube", box((0.7, 0.7, 0.7)), d.material((1.0, 1.0, 1.0), texture=checker_png(2, 32)),
          t=(1.0, 0.35, -1.2), yaw=35)
    d.camera((0.0, 1.5, 2.7), (0.0, 1.0, -3.0), 55)


def grille(d):
    dim = d.material((0.35, 0.35, 0.35))
    room(d, 5.0, 3.0, 5.0, {"floor": d.material((0.3, 0.25, 0.2)), "ceiling": dim, "back": dim, "front": dim,
                            "left": dim, "right": dim})
    # A bright window in the back wall, 1 cm in front of it, facing the room.
    d.add("window", quad((0.0, 1.6, -2.49), (1.5, 0.0, 0.0), (0.0, 0.8, 0.0)),
          d.material((0.8, 0.8, 0.8), emissive=(0.9, 0.95, 1.0), strength=4.0))
    bar = d.material((0.15, 0.15, 0.15), metallic=1.0, roughness=0.4)
    bar_mesh = box((0.045, 1.8, 0.045))
    for k in range(30):  # 3 m / 30 = 10 cm pitch; 4.5 cm bars are about 1.4 px wide
        d.add("bar %d" % k, bar_mesh, bar, t=(-1.45 + 0.1 * k, 1.6, -2.3))
    d.add("sill", box((3.2, 0.08, 0.3)), dim, t=(0.0, 0.76, -2.35))
    d.add("table", box((1.2, 0.75, 0.7)), d.material((0.45, 0.3, 0.18)), t=(-0.9, 0.375, -0.2), yaw=10)
    d.camera((0.3, 1.4, 1.0), (0.0, 1.4, -2.5), 60)


def caustics(d):
    w = d.material(WHITE)
    room(d, 5.0, 3.0, 5.0, {"floor": d.material((0.7, 0.7, 0.7)), "ceiling": w, "back": w, "front": w,
                            "left": d.material(RED), "right": d.material(GREEN)})
    # Small light behind and above the spheres, so their caustics land in front of them.
    ceiling_light(d, (0.25, 0.25), (0.0, 2.99, -1.9), 250.0)
    d.add("glass sphere", sphere(0.45), d.material((1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.5),
          t=(-0.6, 0.45, -0.5))
    d.add("mirror sphere", sphere(0.45), d.material((0.95, 0.95, 0.95), metallic=1.0, roughness=0.0),
          t=(0.7, 0.45, -0.6))
    d.camera((0.0, 1.6, 2.3), (0.0, 0.3, -0.4), 50)


def outdoor(d, outdir):
    """No lights, no emission: only the environment (sky.pfm) lights it."""
    d.add("ground", quad((0.0, 0.0, -10.0), (0.0, 0.0, 30.0), (30.0, 0.0, 0.0), (20.0, 20.0)),
          d.material((0.25, 0.3, 0.15)))
    wall, roof = d.material((0.75, 0.7, 0.6)), d.material((0.45, 0.12, 0.08))
    for x, z, yaw, s in ((-4.0, -9.0, 20, 1.0), (3.5, -14.0, -10, 1.3)):
        d.add("house", box((4 * s, 3 * s, 5 * s), (0.0, 1.5 * s, 0.0)), wall, t=(x, 0.0, z), yaw=yaw)
        d.add("roof", prism_roof(4.4 * s, 5.4 * s, 1.8 * s, (0.0, 3 * s, 0.0)), roof, t=(x, 0.0, z), yaw=yaw)
    bark, leaves = d.material((0.3, 0.2, 0.12)), d.material((0.1, 0.35, 0.08))
    for x, z in ((1.5, -6.0), (-1.0, -16.0)):
        d.add("trunk", frustum(0.15, 0.15, 1.5), bark, t=(x, 0.0, z))
        d.add("crown", merge(frustum(1.1, 0.0, 2.5, (0.0, 1.2, 0.0)), sphere(0.8, (0.0, 1.6, 0.0), 12)), leaves,
              t=(x, 0.0, z))
    d.add("ball", sphere(0.5), d.material((0.8, 0.8, 0.8)), t=(-0.5, 0.5, -4.0))
    d.camera((0.0, 1.7, 2.0), (0.0, 0.9, -10.0), 55)
    # Lat-long map as Tessera reads it: u = atan2(x, -z) / 2pi + 0.5 (u = 0.5
    # looks along -z), v = acos(y) / pi (top row the zenith).
    W, H = 256, 128
    sun_el, sun_az, sun_r = math.radians(35.0), math.radians(-130.0), math.radians(2.0)
    sun = (math.cos(sun_el) * math.sin(sun_az), math.sin(sun_el), -math.cos(sun_el) * math.cos(sun_az))
    def sky(x, y):
        u, v = (x + 0.5) / W, (y + 0.5) / H
        th, ph = v * math.pi, (u - 0.5) * 2 * math.pi
        dr = (math.sin(th) * math.sin(ph), math.cos(th), -math.sin(th) * math.cos(ph))
        if sum(a * b for a, b in zip(dr, sun)) > math.cos(sun_r):
            return (3000.0, 2800.0, 2500.0)  # about 3000x the sky: a hard shadow caster
        if dr[1] < 0:  # below the horizon: dim ground bounce colour
            return (0.12, 0.11, 0.09)
        t = dr[1] ** 0.5
        return (0.9 - 0.7 * t, 1.0 - 0.6 * t, 1.2 - 0.3 * t)  # pale horizon to deep blue zenith
    write_pfm(os.path.join(outdir, "sky.pfm"), W, H, sky)


def small_lights(d):
    w = d.material(WHITE)
    # Glossy floor: metallic 1 with a low F0, since Tessera shades metallic 0 as Lambert.
    room(d, 5.0, 3.0, 5.0, {"floor": d.material((0.3, 0.3, 0.32), metallic=1.0, roughness=0.2), "ceiling": w,
                            "back": w, "front": w, "left": d.material((0.6, 0.5, 0.4)), "right": w})
    for k, (pos, col) in enumerate((((-1.8, 2.2, -1.8), (1.0, 0.6, 0.3)), ((1.7, 1.9, -2.0), (0.4, 0.6, 1.0)),
                                    ((-0.3, 2.6, -0.5), (1.0, 1.0, 0.9)), ((1.2, 0.9, 0.4), (1.0, 0.85, 0.7)),
                                    ((-1.6, 0.6, 0.8), (0.7, 1.0, 0.6)))):
        d.add("bulb %d" % k, sphere(0.02, rings=8), d.material(col, emissive=col, strength=1000.0), t=pos)
    d.add("box", box((0.8, 1.0, 0.8)), d.material((0.7, 0.7, 0.7)), t=(0.9, 0.5, -1.0), yaw=20)
    d.add("ball", sphere(0.4), d.material((0.7, 0.7, 0.7)), t=(-0.8, 0.4, -0.9))
    d.add("column", frustum(0.25, 0.25, 1.6), d.material((0.5, 0.2, 0.15)), t=(0.0, 0.0, -2.0))
    d.camera((0.0, 1.5, 2.4), (0.0, 0.8, -1.0), 58)


def dark(d):
    g = d.material((0.15, 0.15, 0.15))
    room(d, 5.0, 3.0, 5.0, {"floor": d.material((0.12, 0.11, 0.1)), "ceiling": g, "back": g, "front": g,
                            "left": g, "right": d.material((0.18, 0.16, 0.14))})
    # A wall across the back with a doorway (x -0.2..1.0, 2 m high); the only
    # light, a small lamp above door height behind it, faces the camera side
    # (x cross y = +z): it is hidden, its light falls through the doorway.
    for size, t in (((2.3, 3.0, 0.15), (-1.35, 1.5, -1.2)), ((1.5, 3.0, 0.15), (1.75, 1.5, -1.2)),
                    ((1.2, 1.0, 0.15), (0.4, 2.5, -1.2))):
        d.add("partial wall", box(size), g, t=t)
    d.add("lamp", quad((0.4, 2.6, -2.2), (0.1, 0.0, 0.0), (0.0, 0.1, 0.0)),
          d.material((0.1, 0.1, 0.1), emissive=(1.0, 0.85, 0.6), strength=1200.0))
    d.add("crate", box((0.7, 0.7, 0.7)), d.material((0.2, 0.17, 0.12)), t=(1.2, 0.35, 0.3), yaw=15)
    d.add("ball", sphere(0.35), d.material((0.15, 0.15, 0.18)), t=(-0.6, 0.35, 0.4))
    d.camera((-0.6, 1.5, 2.4), (0.3, 0.9, -1.5), 60)


def glossy_rough_mix(d):
    w = d.material(WHITE)
    room(d, 5.0, 3.0, 5.0, {"floor": d.material((0.4, 0.42, 0.45), roughness=0.5), "ceiling": w, "back": w,
                            "front": d.material((0.5, 0.4, 0.3)), "left": d.material((0.5, 0.6, 0.5)), "right": w})
    ceiling_light(d, (0.8, 0.8), (0.0, 2.99, 0.0), 2.0)
    d.point_light("key", (-1.5, 2.3, 0.5), 8.0, (1.0, 0.92, 0.8))
    d.add("metal cube", box((0.9, 0.9, 0.9)), d.material((0.95, 0.64, 0.54), metallic=1.0, roughness=0.6),
          t=(-0.9, 0.45, -1.0), yaw=30)
    d.add("metal ball", sphere(0.35), d.material((0.9, 0.9, 0.9), metallic=1.0, roughness=0.6),
          t=(0.2, 0.35, -0.3))
    d.add("striped ball", sphere(0.5), d.material((1.0, 1.0, 1.0), texture=stripes_png()), t=(1.1, 0.5, -1.2))
    d.camera((0.2, 1.5, 2.4), (0.0, 0.6, -1.0), 55)


def corridor(d):
    w = d.material(WHITE)
    room(d, 2.0, 2.8, 30.0, {"floor": d.material((0.35, 0.3, 0.25)), "ceiling": w, "back": w, "front": w,
                             "left": d.material((0.6, 0.55, 0.45)), "right": d.material((0.6, 0.55, 0.45))}, cz=-13.0)
    for k in range(10):  # lamps every 3 m: equal brightness fading only by distance
        ceiling_light(d, (0.5, 0.3), (0.0, 2.79, 0.5 - 3.0 * k), 20.0)
    wood = d.material((0.3, 0.2, 0.12))
    for k in range(0, 10, 2):  # door frames: depth edges at every distance
        z = -2.0 - 3.0 * k
        for x in (-0.95, 0.95):
            d.add("jamb", box((0.1, 2.2, 0.15)), wood, t=(x, 1.1, z))
        d.add("lintel", box((2.0, 0.15, 0.15)), wood, t=(0.0, 2.275, z))
    d.camera((0.3, 1.6, 1.5), (-0.1, 1.3, -20.0), 55)


def defocus(d):
    """Depth of field: a thin lens focused on a poster 2.5 m away; a striped
    ball and a checker cube about 1 m from the lens and the far wall
    (9-11.5 m) with its text and three small lamps are clearly out of focus."""
    w = d.material(WHITE)
    floor = d.material((1.0, 1.0, 1.0), texture=checker_png(4, 64))
    room(d, 5.0, 3.0, 12.0, {"floor": floor, "floor_uv": (6.0, 3.0), "ceiling": w, "back": w, "front": w,
                             "left": d.material((0.6, 0.5, 0.4)), "right": d.material((0.4, 0.5, 0.6))}, cz=-4.0)
    for z in (0.0, -5.0):
        ceiling_light(d, (0.8, 0.8), (0.0, 2.99, z), 14.0)
    # In focus, 2.5 m along the view: a poster on a post, a checker cube.
    d.add("poster", quad((-0.55, 1.3, -1.0), (0.5, 0.0, 0.0), (0.0, 0.25, 0.0)),
          d.material((1.0, 1.0, 1.0), texture=poster_png()))
    d.add("post", box((0.06, 1.05, 0.06), (0.0, 0.525, 0.0)), d.material((0.1, 0.1, 0.12)), t=(-0.55, 0.0, -1.04))
    d.add("mid cube", box((0.5, 0.5, 0.5)), d.material((1.0, 1.0, 1.0), texture=checker_png(2, 32)),
          t=(0.15, 0.25, -1.0), yaw=30)
    # Out of focus in front, about 1 m away: a striped ball and a checker cube.
    d.add("near ball", sphere(0.15), d.material((1.0, 1.0, 1.0), texture=stripes_png()), t=(-0.35, 1.0, 0.45))
    d.add("near cube", box((0.2, 0.2, 0.2)), d.material((1.0, 1.0, 1.0), texture=checker_png(4, 32)),
          t=(0.36, 1.05, 0.5), yaw=20)
    # Out of focus behind, 9-11.5 m away: the far wall's poster and three small bright lamps.
    d.add("far poster", quad((0.9, 1.6, -9.99), (1.2, 0.0, 0.0), (0.0, 0.6, 0.0)),
          d.material((1.0, 1.0, 1.0), texture=poster_png()))
    for k, (pos, col) in enumerate((((-1.6, 2.2, -8.5), (1.0, 0.7, 0.4)), ((1.7, 2.4, -9.0), (0.5, 0.7, 1.0)),
                                    ((1.2, 0.5, -7.5), (1.0, 0.95, 0.85)))):
        d.add("far lamp %d" % k, sphere(0.05, rings=8), d.material(col, emissive=col, strength=60.0), t=pos)
    d.camera((0.0, 1.35, 1.5), (0.1, 1.1, -1.0), 50, lens=(0.08, 2.5))


def motion(d):
    """Motion blur: a striped ball crossing the view at 4.8 m/s (about 22 px
    over one frame of 0.1 s at 128x128) and a checker cube spinning at 240°/s
    (24° a frame), in front of a still poster with 5x7-pixel text and a
    checker floor; a ceiling light in a closed room with red and green walls,
    so much of the light arrives after a bounce. The harness renders frame 0
    (t = 0) with the shutter open over the whole frame interval."""
    w = d.material(WHITE)
    floor = d.material((1.0, 1.0, 1.0), texture=checker_png())
    room(d, 5.0, 3.0, 5.0, {"floor": floor, "floor_uv": (4.0, 4.0), "ceiling": w, "back": w, "front": w,
                            "left": d.material(RED), "right": d.material(GREEN)})
    ceiling_light(d, (0.8, 0.8), (0.0, 2.99, 0.3), 16.0)
    d.add("poster", quad((0.0, 1.45, -2.49), (1.2, 0.0, 0.0), (0.0, 0.6, 0.0)),
          d.material((1.0, 1.0, 1.0), texture=poster_png()))
    # Moving: x goes -0.5 -> 0.7 -> -1.7 -> -0.5 over a second, linear (4.8 m/s).
    d.add("moving ball", sphere(0.25), d.material((1.0, 1.0, 1.0), texture=stripes_png()), t=(-0.5, 0.9, -0.3))
    d.animate(len(d.nodes) - 1, "translation", [0.0, 0.25, 0.75, 1.0],
              [(-0.5, 0.9, -0.3), (0.7, 0.9, -0.3), (-1.7, 0.9, -0.3), (-0.5, 0.9, -0.3)])
    d.add("spinning cube", box((0.6, 0.6, 0.6)), d.material((1.0, 1.0, 1.0), texture=checker_png(2, 32)),
          t=(0.8, 0.3, -1.0))
    d.animate(len(d.nodes) - 1, "rotation", [0.25 * k for k in range(7)], [yaw_quat(60.0 * k) for k in range(7)])
    d.camera((0.0, 1.3, 2.4), (0.0, 1.0, -1.5), 55)
    d.motion = {"time": 0.0, "frameInterval": 0.1, "shutter": [0.0, 1.0]}


SCENES = [  # key, label, builder, stresses, kind
    ("indirect-room", "Indirectly lit room", indirect_room,
     "light only after a ceiling bounce; rough metal sphere (roughness 0.3) reflecting an indirectly lit room",
     "diffuse"),
    ("rough-metal", "Rough metal spheres", rough_metal,
     "blurred reflections at roughness 0.1, 0.3 and 0.6 of coloured walls", "glossy"),
    ("glossy-dielectric", "Frosted glass", glossy_dielectric,
     "rough dielectric sphere (transmission 1, roughness 0.2, ior 1.5) on a floor with a point-light highlight",
     "glossy"),
    ("textures", "High-frequency textures", textures,
     "fine checkerboard floor and 5x7-pixel text: texture detail a filter must keep", "diffuse"),
    ("grille", "Thin bars against a window", grille,
     "30 bars about 1.5 px wide in front of a bright window: thin geometry, high contrast edges", "diffuse"),
    ("caustics", "Glass and mirror caustics", caustics,
     "caustics from a glass and a mirror sphere under a small light; specular chains", "specular"),
    ("outdoor", "Outdoor, sky only", outdoor,
     "lit only by an environment map with a small bright sun: hard shadows, sky light", "diffuse"),
    ("small-lights", "Tiny bright lights", small_lights,
     "five 4 cm (radius 2 cm) very bright lights over a glossy floor: fireflies", "mixed"),
    ("dark", "Dark room", dark,
     "dark materials, one dim light behind a partial wall: low light everywhere", "diffuse"),
    ("glossy-rough-mix", "Glossy and rough mix", glossy_rough_mix,
     "rough dielectric floor, rough metal cube and ball, striped diffuse ball; point + dim area light", "mixed"),
    ("corridor", "Long corridor", corridor,
     "long perspective: depth from 0.5 to 30 m, repeated lamps and door frames shrinking", "diffuse"),
    ("defocus", "Depth of field", defocus,
     "thin lens (radius 8 cm) focused at 2.5 m on a poster: a near ball and cube (circle of confusion about 6 px at "
     "128x128) and the far wall's text and small lamps (about 3 px) out of focus", "lens"),
    ("motion", "Motion blur", motion,
     "shutter open over a frame of 0.1 s: a striped ball crossing the view (about 22 px streak at 128x128) and a "
     "checker cube spinning 24 degrees, before a still poster with 5x7-pixel text; closed room under a ceiling light", "motion"),
    ("fog-glass", "Milky glass in haze", fog_glass,
     "glass sphere (ior 1.5) of scattering medium (sigma_s about 4/m, g 0.3) in a hazy room: media behind glass",
     "volume"),
    ("foggy-room", "Foggy room", foggy_room,
     "haze (sigma_s 0.12/m, g 0.3) lit by a ceiling lamp past a pillar: volume scattering everywhere", "volume"),
]

MODELS = [  # real models from Debian's assimp-testmodels, rendered under the default light rig
    ("engine", "2CylinderEngine (assimp-testmodels)", ASSIMP + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
     "real CAD model: many small parts, default light rig", "diffuse"),
    # Khronos' TextureCoordinateTest (as assimp's issue_3269 test): textured
    # quads with fine print. ClearCoatTest would be richer, but its emissive
    # labels count as lighting, so no default rig is added and it renders black.
    ("texcoord", "TextureCoordinateTest (assimp-testmodels)", ASSIMP + "/issue_3269/texcoord_crash.gltf",
     "real textured model: coloured quads with thin print and corner marks; default light rig", "diffuse"),
]


def main():
    if len(sys.argv) != 2 or sys.argv[1].startswith("-"):
        sys.exit(__doc__)
    outdir = sys.argv[1]
    os.makedirs(outdir, exist_ok=True)
    entries = []
    for key, label, build, stresses, kind in SCENES:
        d = Doc(key)
        if build is outdoor:
            build(d, outdir)
        else:
            build(d)
        d.write(os.path.join(outdir, key + ".gltf"))
        e = {"key": key, "label": label, "file": key + ".gltf", "stresses": stresses, "kind": kind}
        if build is outdoor:
            e["environment"] = "sky.pfm"
        if d.motion:
            e.update(d.motion)
        entries.append(e)
    for key, label, path, stresses, kind in MODELS:
        if not os.path.exists(path):
            print("note: %s is missing (install assimp-testmodels); listed anyway" % path, file=sys.stderr)
        entries.append({"key": key, "label": label, "file": path, "stresses": stresses, "kind": kind})
    with open(os.path.join(outdir, "suite.json"), "w") as f:
        json.dump({"scenes": entries}, f, indent=1)
    print("wrote %d scenes and suite.json to %s" % (len(entries), outdir))


if __name__ == "__main__":
    main()
