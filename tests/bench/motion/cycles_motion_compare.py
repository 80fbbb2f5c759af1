#!/usr/bin/python3
"""Tessera's shutter against Blender Cycles 3.4's on the quality suite's
motion-blurred scene (tests/bench/quality/suite/make_suite.py, key
`motion`: a striped ball crossing the view at 4.8 m/s, a checker cube
spinning 240°/s, frame interval 0.1 s). Both render frame 0 (t = 0) with
the same shutter, as fractions of the frame interval (default 0.25,0.75:
an interval that does not start at the frame, so its placement is checked
too); cycles_motion_render.py maps it onto Cycles. Each renderer's own
high-spp image; the script reports the mean of a streak region (the path
the ball's centre sweeps while the shutter is open), of the spinning cube
and of a still region (the poster) in each (target: within 3 %), and the
seen error between the two images (tests/bench/quality/seen_error.py). The
same pair with the shutter closed (an instant at t = 0) is the baseline:
what the two renderers differ by without motion; from both, each region's
change by the motion in each renderer. Last, the streak's geometry: a 2 cm
lamp moving at constant speed on black (256x256, 20° field of view, the
same shutter), then the lamp still and the camera moving the other way,
leaves a streak in each renderer whose length (from its second moment
along the motion: a box of length L convolved with the lamp's still image
has variance L^2/12 plus the lamp's) and centre are set beside the lamp's
screen displacement over the shutter.

    cycles_motion_compare.py --render build/default/bin/tessera-render [--size 128x128]
                             [--spp 1024] [--bounces 16] [--shutter 0.25,0.75] [--out DIR]

Needs Debian's blender, python3-numpy and python3-openimageio. Images
already in --out are reused.
"""
import json, math, os, subprocess, sys, tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
import cycles_common  # noqa: E402
from cycles_common import load  # noqa: E402
sys.path.insert(0, os.path.join(HERE, "..", "quality"))
from seen_error import seen_error  # noqa: E402
sys.path.insert(0, os.path.join(HERE, "..", "lens"))
from cycles_lens_compare import rotate, save_png  # noqa: E402

SUITE = os.path.join(HERE, "..", "quality", "suite", "make_suite.py")
LUM = np.array([0.2126, 0.7152, 0.0722])


def projector(doc, width, height):
    """Scene point -> (x, y) pixel of the document's camera (y down)."""
    cam_node = next(n for n in doc["nodes"] if "camera" in n)
    eye = np.array(cam_node.get("translation", [0, 0, 0]), dtype=float)
    q = cam_node.get("rotation", [0, 0, 0, 1])
    qi = (-q[0], -q[1], -q[2], q[3])
    f = (height / 2) / math.tan(doc["cameras"][cam_node["camera"]]["perspective"]["yfov"] / 2)

    def project(p):
        c = rotate(qi, np.asarray(p, dtype=float) - eye)  # camera space, looking down -z
        return np.array([width / 2 + f * c[0] / -c[2], height / 2 - f * c[1] / -c[2]])
    return project


def channel_at(doc, node_name, path, t):
    """The node's animated value at time t (LINEAR keys), read from the glTF's data URI buffer."""
    import base64, struct
    blob = base64.b64decode(doc["buffers"][0]["uri"].split(",", 1)[1])
    node = next(i for i, n in enumerate(doc["nodes"]) if n.get("name") == node_name)
    for a in doc["animations"]:
        for ch in a["channels"]:
            if ch["target"] == {"node": node, "path": path}:
                s = a["samplers"][ch["sampler"]]
                def floats(acc, k):
                    acc = doc["accessors"][acc]
                    v = doc["bufferViews"][acc["bufferView"]]
                    return [struct.unpack_from("<%df" % k, blob, v["byteOffset"] + 4 * k * i) for i in range(acc["count"])]
                times = [x[0] for x in floats(s["input"], 1)]
                values = floats(s["output"], 3)
                i = max(0, min(len(times) - 2, next((j - 1 for j, x in enumerate(times) if x > t), len(times) - 2)))
                w = (t - times[i]) / (times[i + 1] - times[i])
                return np.array(values[i]) * (1 - w) + np.array(values[i + 1]) * w
    raise SystemExit("no %s channel on %s" % (path, node_name))


def box_mask(width, height, x0, y0, x1, y1):
    yy, xx = np.mgrid[0:height, 0:width] + 0.5
    return (xx >= x0) & (xx <= x1) & (yy >= y0) & (yy <= y1)


def node_box(doc, project, name, shrink=0.6):
    """The middle `shrink` of a still node's projected bounding box (no rotation on these nodes)."""
    node = next(n for n in doc["nodes"] if n.get("name") == name)
    acc = doc["accessors"][doc["meshes"][node["mesh"]]["primitives"][0]["attributes"]["POSITION"]]
    t = np.array(node.get("translation", [0, 0, 0]), dtype=float)
    pts = [project(np.array(c) + t) for c in ((a, b, cc) for a in (acc["min"][0], acc["max"][0])
                                              for b in (acc["min"][1], acc["max"][1])
                                              for cc in (acc["min"][2], acc["max"][2]))]
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    cx, cy, hx, hy = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2, shrink * (max(xs) - min(xs)) / 2, \
        shrink * (max(ys) - min(ys)) / 2
    return cx - hx, cy - hy, cx + hx, cy + hy


def tessera(a, scene, path, fps, shutter, size, spp, bounces):
    if os.path.exists(path):
        return
    pattern = path[:-len(".exr")] + ".####.exr"
    subprocess.run([a.render, scene, "--backend", "embree", "--size", size, "--spp", str(spp), "--max-depth",
                    str(bounces), "--no-default-light", "--frames", "1", "--fps", str(fps), "--shutter",
                    "%g,%g" % shutter, "--output", pattern, "--quiet"], check=True)
    os.rename(pattern.replace("####", "0000"), path)


def cycles(scene, path, fps, shutter, size, spp, bounces):
    if os.path.exists(path):
        return
    log = subprocess.run(["blender", "-b", "--python", os.path.join(HERE, "cycles_motion_render.py"), "--", scene,
                          path, str(spp), size, str(bounces), str(fps), "%g" % shutter[0], "%g" % shutter[1]],
                         check=True, capture_output=True, text=True).stdout
    for line in log.splitlines():
        if line.startswith("cycles_motion_render:"):
            print("   ", line)


def region_table(title, ours, theirs, regions):
    print("\n%s\n" % title)
    print("| region | where (px) | Tessera | Cycles | Tessera / Cycles - 1 |")
    print("|---|---|---|---|---|")
    means = {}
    for name, box in regions:
        mask = box_mask(ours.shape[1], ours.shape[0], *box)
        m, c = (float(image[mask].mean(axis=0) @ LUM) for image in (ours, theirs))
        means[name] = (m, c)
        print("| %s | %.0f,%.0f-%.0f,%.0f | %.4f | %.4f | %+.1f %% |" % (name, *box, m, c, 100 * (m / c - 1)))
    m, c = (float(image.mean(axis=(0, 1)) @ LUM) for image in (ours, theirs))
    print("| whole image | | %.4f | %.4f | %+.1f %% |" % (m, c, 100 * (m / c - 1)))
    whole, tile, (tx, ty) = seen_error(ours, theirs)
    print("\nseen error Tessera against Cycles: whole %.4f, worst tile %.4f (at %d,%d)" % (whole, tile, tx, ty))
    return means


def streak_check(a, out, shutter):
    """A 2 cm lamp 5 m away moving 8 m/s across the view (0.8 m over a frame
    of 0.1 s), 256x256, yfov 20 degrees; then the lamp still and the camera
    moving the other way, which moves the lamp alike on screen."""
    sys.path.insert(0, os.path.dirname(SUITE))
    import make_suite as ms  # noqa: E402
    size, fov, z, fps, x0, x1 = 256, 20.0, -5.0, 10, -0.4, 0.4
    f = (size / 2) / math.tan(math.radians(fov) / 2)
    px = lambda x: size / 2 + f * x / -z  # noqa: E731
    xa, xb = (px(x0 + (x1 - x0) * s) for s in shutter)
    print("\nA lamp (radius 2 cm) %g m away moving %g m/s across the view (or the camera moving the other way), "
          "%dx%d, yfov %g deg, %d fps, shutter %g,%g: its screen displacement over the shutter is %.2f px "
          "(x %.2f to %.2f)" % (-z, (x1 - x0) * fps, size, size, fov, fps, *shutter, xb - xa, xa, xb))
    print("\n| renderer | what moves | streak length (px, 2nd moment) | against %.2f px | streak centre x (px) |"
          " against %.2f | total light, streak / still |" % (xb - xa, (xa + xb) / 2))
    print("|---|---|---|---|---|---|---|")
    yy, xx = np.mgrid[0:size, 0:size] + 0.5
    for mover in ("lamp", "camera"):
        scene = os.path.join(out, "streak_%s.gltf" % mover)
        d = ms.Doc("streak")
        lamp = d.material((0, 0, 0), emissive=(1, 1, 1), strength=100.0)
        if mover == "lamp":
            d.add("lamp", ms.sphere(0.02, rings=16), lamp, t=(x0, 0, z))
            d.animate(0, "translation", [0.0, 1.0 / fps], [(x0, 0.0, z), (x1, 0.0, z)])
            d.camera((0.0, 0.0, 0.0), (0.0, 0.0, -1.0), fov)
        else:
            d.add("lamp", ms.sphere(0.02, rings=16), lamp, t=(0.0, 0, z))
            d.camera((-x0, 0.0, 0.0), (-x0, 0.0, -1.0), fov)
            d.animate(1, "translation", [0.0, 1.0 / fps], [(-x0, 0.0, 0.0), (-x1, 0.0, 0.0)])
        d.write(scene)
        for name in ("Tessera", "Cycles"):
            moments = {}
            for tag, s in (("streak", shutter), ("still", (0.0, 0.0))):
                path = os.path.join(out, "%s_%s_%s.exr" % (mover, name.lower(), tag))
                if name == "Tessera":
                    tessera(a, scene, path, fps, s, "%dx%d" % (size, size), 256, 4)
                else:
                    cycles(scene, path, fps, s, "%dx%d" % (size, size), 256, 4)
                light = load(path).sum(axis=2)
                w = light / light.sum()
                cx = (w * xx).sum()
                moments[tag] = (cx, (w * (xx - cx) ** 2).sum(), light.sum())
            length = math.sqrt(max(0.0, 12 * (moments["streak"][1] - moments["still"][1])))
            print("| %s | %s | %.2f | %+.1f %% | %.2f | %+.2f px | %.3f |" % (
                name, mover, length, 100 * (length / (xb - xa) - 1), moments["streak"][0],
                moments["streak"][0] - (xa + xb) / 2, moments["streak"][2] / moments["still"][2]))


def main():
    ap = cycles_common.comparison_parser(__doc__)
    ap.add_argument("--shutter", default="0.25,0.75", help="OPEN,CLOSE as fractions of the frame interval")
    a = ap.parse_args()
    shutter = tuple(float(v) for v in a.shutter.split(","))
    out = a.out or tempfile.mkdtemp(prefix="tsr-motion-")
    os.makedirs(out, exist_ok=True)
    subprocess.run([sys.executable, SUITE, out], check=True, stdout=subprocess.DEVNULL)
    entry = next(e for e in json.load(open(os.path.join(out, "suite.json")))["scenes"] if e["key"] == "motion")
    fps = round(1.0 / entry["frameInterval"])
    scene = os.path.join(out, "motion.gltf")
    doc = json.load(open(scene))
    width, height = (int(v) for v in a.size.split("x"))
    project = projector(doc, width, height)
    dt = 1.0 / fps
    ball = [project(channel_at(doc, "moving ball", "translation", s * dt)) for s in shutter]
    radius = 0.25 * (height / 2) / math.tan(doc["cameras"][0]["perspective"]["yfov"] / 2) / \
        np.linalg.norm(channel_at(doc, "moving ball", "translation", 0.0) - doc["nodes"][-1]["translation"])
    # The streak region: between the ball's centre at shutter open and close, half its radius high.
    regions = [("streak (moving ball)", (min(ball[0][0], ball[1][0]), ball[0][1] - radius / 2,
                                         max(ball[0][0], ball[1][0]), ball[0][1] + radius / 2)),
               ("spinning cube", node_box(doc, project, "spinning cube", 0.5)),
               ("poster (still)", node_box(doc, project, "poster"))]
    print("%s, %d spp each, %d bounces; frame 0 at %d fps, shutter %g,%g of the frame interval; the ball's centre "
          "moves %.1f px over the shutter; mean luminance of each region" % (a.size, a.spp, a.bounces, fps, *shutter,
                                                                             ball[1][0] - ball[0][0]))
    images = {}
    for tag, s in (("shutter", shutter), ("still", (0.0, 0.0))):
        ours, theirs = os.path.join(out, "tessera_%s.exr" % tag), os.path.join(out, "cycles_%s.exr" % tag)
        tessera(a, scene, ours, fps, s, a.size, a.spp, a.bounces)
        cycles(scene, theirs, fps, s, a.size, a.spp, a.bounces)
        images[tag] = (load(ours), load(theirs))
        save_png(os.path.join(out, "side_by_side_%s.png" % tag), np.concatenate(images[tag], axis=1))
    moving = region_table("Shutter %g,%g" % shutter, *images["shutter"], regions)
    still = region_table("Shutter closed (an instant at t = 0), the baseline", *images["still"], regions)
    print("\nWhat the motion does to each region, (shutter / instant - 1), in each renderer:\n")
    print("| region | Tessera | Cycles |")
    print("|---|---|---|")
    for name, _ in regions:
        print("| %s | %+.1f %% | %+.1f %% |" % (name, 100 * (moving[name][0] / still[name][0] - 1),
                                             100 * (moving[name][1] / still[name][1] - 1)))
    print("\nseen error, shutter image against instant image: Tessera %.4f / %.4f, Cycles %.4f / %.4f (whole / worst "
          "tile)" % (*seen_error(images["shutter"][0], images["still"][0])[:2],
                     *seen_error(images["shutter"][1], images["still"][1])[:2]))
    streak_check(a, out, shutter)
    print("\nimages in", out)


if __name__ == "__main__":
    main()
