#!/usr/bin/python3
"""Tessera's thin lens against Blender Cycles 3.4's on the quality suite's
depth-of-field scene (tests/bench/quality/suite/make_suite.py, key
`defocus`: TSR_camera_lens with aperture radius 8 cm, focus 2.5 m). Each
renderer makes its own high-spp image through the same lens
(cycles_lens_render.py maps the lens onto Cycles); the script reports the
mean of an in-focus region and of out-of-focus regions in each (target:
within 3 %), and the seen error between the two images
(tests/bench/quality/seen_error.py: clamp, sRGB, box blur of radius 2
twice, RMSE over the image and its worst 16x16 tile). The same pair
through the pinhole (aperture 0) is the baseline: what the two renderers
differ by without a lens (materials, light transport). From both pairs:
each region's change by the lens in each renderer, how far each lens
image is from its pinhole image, and the lens alone compared: Tessera's
lens image carried over to Cycles' shading (times the smoothed ratio of
the pinhole images) against Cycles' lens image. Last, the lens's own
geometry: a small lamp 10 m away, focus 2.5 m, 20° field of view, spreads
into a disc in each renderer, whose radius (from its second moment) is
set beside the lens equation's circle of confusion.

    cycles_lens_compare.py --render build/default/bin/tessera-render [--size 128x128]
                           [--spp 1024] [--bounces 16] [--out DIR] [--no-pinhole]

Regions are the projections of named nodes' boxes, shrunk to their middle
60 %: `poster` (on the plane in focus), `mid cube` (in focus), `near ball`
(about 1 m away: circle of confusion about 6 px radius at 128x128) and
`far poster` (11.5 m away: about 3 px). Needs Debian's blender,
python3-numpy and python3-openimageio. Images already in --out are reused.
At the defaults the four renders take about 9 minutes on two busy cores.
"""
import json, math, os, subprocess, sys, tempfile

import numpy as np
import OpenImageIO as oiio

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
import cycles_common  # noqa: E402
from cycles_common import load  # noqa: E402
sys.path.insert(0, os.path.join(HERE, "..", "quality"))
from seen_error import displayed, seen_error  # noqa: E402

SUITE = os.path.join(HERE, "..", "quality", "suite", "make_suite.py")
REGIONS = (("poster", "in focus"), ("mid cube", "in focus"), ("near ball", "out of focus, near"),
           ("far poster", "out of focus, far"))
LUM = np.array([0.2126, 0.7152, 0.0722])


def rotate(q, v):
    """Rotates v by the unit quaternion q = (x, y, z, w)."""
    x, y, z, w = q
    u = np.array([x, y, z])
    v = np.asarray(v, dtype=float)
    return v + 2.0 * np.cross(u, np.cross(u, v) + w * v)


def region_masks(doc, width, height, shrink=0.6):
    """Boolean masks of the named nodes' projected boxes (middle `shrink`)."""
    cam_node = next(n for n in doc["nodes"] if "camera" in n)
    eye = np.array(cam_node.get("translation", [0, 0, 0]), dtype=float)
    q = cam_node.get("rotation", [0, 0, 0, 1])
    qi = (-q[0], -q[1], -q[2], q[3])
    yfov = doc["cameras"][cam_node["camera"]]["perspective"]["yfov"]
    f = (height / 2) / math.tan(yfov / 2)
    masks = []
    for name, what in REGIONS:
        node = next(n for n in doc["nodes"] if n.get("name") == name)
        acc = doc["accessors"][doc["meshes"][node["mesh"]]["primitives"][0]["attributes"]["POSITION"]]
        lo, hi = acc["min"], acc["max"]
        t = np.array(node.get("translation", [0, 0, 0]), dtype=float)
        r = node.get("rotation", [0, 0, 0, 1])
        xs, ys = [], []
        for corner in ((a, b, c) for a in (lo[0], hi[0]) for b in (lo[1], hi[1]) for c in (lo[2], hi[2])):
            p = rotate(qi, rotate(r, corner) + t - eye)  # camera space: looking down -z
            xs.append(width / 2 + f * p[0] / -p[2])
            ys.append(height / 2 - f * p[1] / -p[2])
        cx, cy = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2
        hx, hy = shrink * (max(xs) - min(xs)) / 2, shrink * (max(ys) - min(ys)) / 2
        yy, xx = np.mgrid[0:height, 0:width] + 0.5
        mask = (abs(xx - cx) <= hx) & (abs(yy - cy) <= hy)
        masks.append((name, what, mask, (cx - hx, cy - hy, cx + hx, cy + hy)))
    return masks


def box_blur(image, radius):
    """Box mean of the given radius per channel, clamped at the borders (separable)."""
    out = image.astype(np.float64)
    for axis in (0, 1):
        pad = [(0, 0)] * out.ndim
        pad[axis] = (radius, radius)
        c = np.cumsum(np.pad(out, pad, mode="edge"), axis=axis)
        c = np.concatenate([np.zeros_like(np.take(c, [0], axis=axis)), c], axis=axis)
        n = out.shape[axis]
        out = (np.take(c, np.arange(n) + 2 * radius + 1, axis=axis) - np.take(c, np.arange(n), axis=axis)) / (
            2 * radius + 1)
    return out


def save_png(path, pixels):
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(pixels.shape[1], pixels.shape[0], 3, "uint8"))
    out.write_image((displayed(pixels) * 255 + 0.5).astype(np.uint8))
    out.close()


def render_pair(a, scene, out, tag, aperture):
    ours, theirs = os.path.join(out, "tessera_%s.exr" % tag), os.path.join(out, "cycles_%s.exr" % tag)
    if not os.path.exists(ours):
        subprocess.run([a.render, scene, "--backend", "embree", "--size", a.size, "--spp", str(a.spp),
                        "--max-depth", str(a.bounces), "--no-default-light", "--aperture", str(aperture),
                        "--output", ours, "--quiet"], check=True)
    if not os.path.exists(theirs):
        subprocess.run(["blender", "-b", "--python", os.path.join(HERE, "cycles_lens_render.py"), "--", scene,
                        theirs, str(a.spp), a.size, str(a.bounces), str(aperture)], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return load(ours), load(theirs)


def report(title, ours, theirs, masks):
    print("\n%s\n" % title)
    print("| region | where (px) | Tessera | Cycles | Tessera / Cycles - 1 |")
    print("|---|---|---|---|---|")
    worst = 0.0
    for name, what, mask, box in masks:
        m, c = (float(image[mask].mean(axis=0) @ LUM) for image in (ours, theirs))
        worst = max(worst, abs(m / c - 1))
        print("| %s (%s) | %.0f,%.0f-%.0f,%.0f | %.4f | %.4f | %+.1f %% |" % (name, what, *box, m, c, 100 * (m / c - 1)))
    m, c = (float(image.mean(axis=(0, 1)) @ LUM) for image in (ours, theirs))
    print("| whole image | | %.4f | %.4f | %+.1f %% |" % (m, c, 100 * (m / c - 1)))
    whole, tile, (tx, ty) = seen_error(ours, theirs)
    print("\nworst region: %.1f %% (target 3 %%); seen error Tessera against Cycles: whole %.4f, worst tile %.4f "
          "(at %d,%d)" % (100 * worst, whole, tile, tx, ty))


def disc_check(a, out):
    """A 2 cm lamp 10 m away through the same lens focused at 2.5 m, 256x256, yfov 20 degrees."""
    sys.path.insert(0, os.path.dirname(SUITE))
    import make_suite as ms  # noqa: E402
    aperture, focus, distance, fov, size = 0.08, 2.5, 10.0, 20.0, 256
    scene = os.path.join(out, "lens_disc.gltf")
    d = ms.Doc("lens disc")
    d.add("lamp", ms.sphere(0.02, rings=16), d.material((0, 0, 0), emissive=(1, 1, 1), strength=100.0),
          t=(0.0, 0.0, -distance))
    d.camera((0.0, 0.0, 0.0), (0.0, 0.0, -1.0), fov, lens=(aperture, focus))
    d.write(scene)
    f = (size / 2) / math.tan(math.radians(fov) / 2)
    predicted = aperture * abs(1 / focus - 1 / distance) * f
    print("\nA lamp (radius 2 cm) %g m away, focus %g m, aperture radius %g m, %dx%d, yfov %g deg: its disc" %
          (distance, focus, aperture, size, size, fov))
    print("\n| renderer | radius (px, 2nd moment) | against the lens equation's %.2f px | total light |" % predicted)
    print("|---|---|---|---|")
    for name, path in (("Tessera", "tessera_disc.exr"), ("Cycles", "cycles_disc.exr")):
        path = os.path.join(out, path)
        if not os.path.exists(path):
            if name == "Tessera":
                subprocess.run([a.render, scene, "--backend", "embree", "--size", "%dx%d" % (size, size), "--spp",
                                "256", "--no-default-light", "--output", path, "--quiet"], check=True)
            else:
                subprocess.run(["blender", "-b", "--python", os.path.join(HERE, "cycles_lens_render.py"), "--",
                                scene, path, "256", "%dx%d" % (size, size), "4"], check=True,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        light = load(path).sum(axis=2)
        yy, xx = np.mgrid[0:size, 0:size] + 0.5
        w = light / light.sum()
        cx, cy = (w * xx).sum(), (w * yy).sum()
        radius = math.sqrt(2 * (w * ((xx - cx) ** 2 + (yy - cy) ** 2)).sum())  # uniform disc: <r^2> = R^2 / 2
        print("| %s | %.2f | %+.1f %% | %.1f |" % (name, radius, 100 * (radius / predicted - 1), light.sum()))


def main():
    ap = cycles_common.comparison_parser(__doc__)
    ap.add_argument("--no-pinhole", action="store_true", help="skip the pinhole baseline pair")
    a = ap.parse_args()
    out = a.out or tempfile.mkdtemp(prefix="tsr-lens-")
    os.makedirs(out, exist_ok=True)
    subprocess.run([sys.executable, SUITE, out], check=True, stdout=subprocess.DEVNULL)
    scene = os.path.join(out, "defocus.gltf")
    doc = json.load(open(scene))
    lens = doc["cameras"][0]["extensions"]["TSR_camera_lens"]
    width, height = (int(v) for v in a.size.split("x"))
    masks = region_masks(doc, width, height)
    ours, theirs = render_pair(a, scene, out, "lens", lens["apertureRadius"])
    save_png(os.path.join(out, "side_by_side_lens.png"), np.concatenate([ours, theirs], axis=1))
    print("%s, %d spp each, %d bounces; lens: aperture radius %g m, focus %g m; mean luminance of each region"
          % (a.size, a.spp, a.bounces, lens["apertureRadius"], lens["focusDistance"]))
    report("Through the lens", ours, theirs, masks)
    if not a.no_pinhole:
        ours0, theirs0 = render_pair(a, scene, out, "pinhole", 0)
        save_png(os.path.join(out, "side_by_side_pinhole.png"), np.concatenate([ours0, theirs0], axis=1))
        report("Through the pinhole (aperture 0), the baseline", ours0, theirs0, masks)
        print("\nWhat the lens does to each region, (lens / pinhole - 1), in each renderer:\n")
        print("| region | Tessera | Cycles |")
        print("|---|---|---|")
        for name, what, mask, _ in masks:
            t = float(ours[mask].mean(axis=0) @ LUM) / float(ours0[mask].mean(axis=0) @ LUM) - 1
            c = float(theirs[mask].mean(axis=0) @ LUM) / float(theirs0[mask].mean(axis=0) @ LUM) - 1
            print("| %s | %+.1f %% | %+.1f %% |" % (name, 100 * t, 100 * c))
        # The lens alone: how far each renderer's lens image is from its
        # pinhole image, and Tessera's lens image carried over to Cycles'
        # shading (times Cycles' pinhole over Tessera's, both box-blurred
        # with radius 4 so the ratio is smooth) against Cycles' lens image.
        ratio = box_blur(theirs0, 4) / np.maximum(box_blur(ours0, 4), 1e-6)
        print("\nseen error, lens image against pinhole image: Tessera %.4f / %.4f, Cycles %.4f / %.4f (whole / worst "
              "tile)" % (*seen_error(ours, ours0)[:2], *seen_error(theirs, theirs0)[:2]))
        print("seen error, Tessera's lens image in Cycles' shading (x Cycles pinhole / Tessera pinhole) against "
              "Cycles' lens image: whole %.4f, worst tile %.4f (at %d,%d)" % (*seen_error(ours * ratio, theirs)[:2],
                                                                               *seen_error(ours * ratio, theirs)[2]))
    disc_check(a, out)
    print("\nimages in", out)


if __name__ == "__main__":
    main()
