#!/usr/bin/python3
"""Tessera's path tracer against Blender Cycles 3.4, each against its own
high-spp reference, by the seen error (tests/bench/quality/seen_error.hpp:
clamped, sRGB, blurred by a box of radius 2 twice; RMSE whole and worst
16x16 tile): unfiltered at equal spp (issue 40), and how long Cycles takes
to reach the seen error of Tessera's filtered 8-spp image (issue 41).

    tests/bench/quality/cycles_sampling.py --bin build/default/bin --suite build/quality-cache/suite \\
        [--scenes builtin-cornell,indirect-room,corridor,small-lights] [--size 128x128] \\
        [--ref-spp 4096] [--bounces 8] [--filters pixel,denoise]

Scenes are suite keys or builtin-cornell (written by tessera-inspect
--write-glb). Times are wall-clock seconds of each renderer's process, less
that of a 1-spp run of the same scene (start-up, loading, BVH): one run on
this shared machine. Needs Debian's blender, python3-numpy and
python3-openimageio. Prints a markdown table.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from cycles_common import load, timed  # noqa: E402



def displayed(linear):
    c = np.clip(np.nan_to_num(linear, nan=0.0, posinf=0.0, neginf=0.0), 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1.0 / 2.4) - 0.055)


def box(plane, r, axis):
    """Mean over the window of radius r along `axis`, cut at the border."""
    n = plane.shape[axis]
    csum = np.cumsum(np.insert(plane, 0, 0.0, axis=axis), axis=axis)
    lo = np.clip(np.arange(n) - r, 0, n)
    hi = np.clip(np.arange(n) + r + 1, 0, n)
    take = lambda idx: np.take(csum, idx, axis=axis)
    shape = [1, 1, 1]
    shape[axis] = n
    return (take(hi) - take(lo)) / (hi - lo).reshape(shape)


def seen(image):
    p = displayed(image)
    for _ in range(2):
        p = box(box(p, 2, 1), 2, 0)
    return p


def seen_error(image, reference, tile=16):
    d = (seen(image) - seen(reference)) ** 2
    h, w = d.shape[:2]
    worst = 0.0
    for y in range(0, h, tile):
        for x in range(0, w, tile):
            worst = max(worst, float(np.sqrt(np.mean(d[y:y + tile, x:x + tile]))))
    return float(np.sqrt(np.mean(d))), worst


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", required=True, help="folder holding tessera-render and tessera-inspect")
    ap.add_argument("--suite", required=True, help="make_suite.py's output")
    ap.add_argument("--scenes", default="builtin-cornell,indirect-room,corridor,small-lights")
    ap.add_argument("--size", default="128x128")
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--bounces", type=int, default=8)
    ap.add_argument("--filters", default="pixel,denoise")
    ap.add_argument("--max-spp", type=int, default=1024, help="Cycles' curve goes 8, 16, ... up to this")
    ap.add_argument("--work", default=None, help="keep images here (default: a temporary folder)")
    a = ap.parse_args()
    cycles_spp = [8 << k for k in range(20) if (8 << k) <= a.max_spp]
    work = a.work or tempfile.mkdtemp(prefix="tsr-cycles-sampling-")
    os.makedirs(work, exist_ok=True)
    width, height = a.size.split("x")

    def scene_file(key):
        if key == "builtin-cornell":
            path = os.path.join(work, "cornell.glb")
            if not os.path.exists(path):
                subprocess.run([os.path.join(a.bin, "tessera-inspect"), "builtin:cornell", "--write-glb", path],
                               check=True, stdout=subprocess.DEVNULL)
            return path
        return os.path.join(a.suite, key + ".gltf")

    def cycles(scene, spp, key):
        out = os.path.join(work, "%s_cycles_%d.exr" % (key, spp))
        seconds = timed(["blender", "-b", "--python", os.path.join(HERE, "cycles_suite_render.py"), "--",
                         scene, out, str(spp), a.size, str(a.bounces)])
        return load(out), seconds

    def tessera(scene, spp, key, filt="none"):
        out = os.path.join(work, "%s_tessera_%s_%d.exr" % (key, filt, spp))
        stats = out + ".json"
        seconds = timed([os.path.join(a.bin, "tessera-render"), scene, "--size", a.size, "--spp", str(spp),
                         "--max-depth", str(a.bounces), "--seed", "1", "--filter", filt, "--quiet", "--output", out,
                         "--stats-json", stats])
        return load(out), seconds, json.load(open(stats))

    rows = []
    for key in a.scenes.split(","):
        scene = scene_file(key)
        print("[cycles_sampling] %s" % key, file=sys.stderr, flush=True)
        c_ref, _ = cycles(scene, a.ref_spp, key)
        _, c_base = cycles(scene, 1, key)
        c_curve = []
        for spp in cycles_spp:
            img, s = cycles(scene, spp, key)
            c_curve.append((spp, max(s - c_base, 1e-3), seen_error(img, c_ref)))
        t_ref, _, _ = tessera(scene, a.ref_spp, key)
        _, t_base, _ = tessera(scene, 1, key)
        t = {}
        for spp in (8, 64):
            img, s, _ = tessera(scene, spp, key)
            t[spp] = (max(s - t_base, 1e-3), seen_error(img, t_ref))
        filtered = {}
        for filt in a.filters.split(","):
            img, s, _ = tessera(scene, 8, key, filt)
            err = seen_error(img, t_ref)
            # Cycles' time to the same seen error, log-log between its points.
            reach = None
            for (s0, t0, e0), (s1, t1, e1) in zip(c_curve, c_curve[1:]):
                if e0[0] >= err[0] >= e1[0]:
                    f = (np.log(err[0]) - np.log(e0[0])) / (np.log(e1[0]) - np.log(e0[0]))
                    reach = float(np.exp(np.log(t0) + f * (np.log(t1) - np.log(t0))))
                    break
            if reach is None and c_curve[0][2][0] <= err[0]:
                reach = c_curve[0][1]
            filtered[filt] = (max(s - t_base, 1e-3), err, reach)
        c8 = next(c for c in c_curve if c[0] == 8)
        c64 = next(c for c in c_curve if c[0] == 64)
        rows.append((key, c8, c64, t, filtered, float(np.mean(c_ref)), float(np.mean(t_ref))))

    print("| scene | Cycles 8 spp | Tessera 8 spp | Cycles 64 spp | Tessera 64 spp | Cycles s / spp | Tessera s / spp |")
    print("|---|---|---|---|---|---|---|")
    for key, c8, c64, t, _, _, _ in rows:
        print("| %s | %.4f / %.4f | %.4f / %.4f | %.4f / %.4f | %.4f / %.4f | %.4f | %.4f |" % (
            key, *c8[2], *t[8][1], *c64[2], *t[64][1], c64[1] / 64, t[64][0] / 64))
    print()
    print("| scene | filter | Tessera 8 spp: seen error, seconds | Cycles: seconds to the same error | ratio |")
    print("|---|---|---|---|---|")
    for key, _, _, _, filtered, _, _ in rows:
        for filt, (s, err, reach) in filtered.items():
            ratio = "%.1fx" % (reach / s) if reach else "beyond %d spp" % cycles_spp[-1]
            print("| %s | %s | %.4f, %.3f s | %s | %s |" % (key, filt, err[0], s, "%.2f s" % reach if reach else "-",
                                                         ratio))
    print()
    print("Mean of the references (Cycles / Tessera): " +
          ", ".join("%s %.4f / %.4f" % (r[0], r[5], r[6]) for r in rows))
    print("Work folder: " + work)


if __name__ == "__main__":
    main()
