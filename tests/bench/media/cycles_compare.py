#!/usr/bin/python3
"""Tessera's path tracer against Blender Cycles 3.4 on scenes with
participating media (the quality suite's fog-glass and foggy-room): the
mean pixel value of each renderer's high-spp reference, and the relMSE of
each at equal spp against Tessera's reference, with render times.

    cycles_compare.py --render build/default/bin/tessera-render --suite DIR
                      [--scenes fog-glass,foggy-room] [--size 96x96] [--spp 64]
                      [--ref-spp 2048] [--bounces 64]

DIR holds the suite (python3 tests/bench/quality/suite/make_suite.py DIR).
Needs Debian's blender, python3-numpy and python3-openimageio.
"""
import argparse, os, sys, tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from cycles_common import load, timed  # noqa: E402




def rel_mse(image, reference):
    """tests/bench/quality/rel_mse.hpp's relMSE: mean over pixels and RGB of (y^ - y)^2 / (y^2 + 0.01)."""
    return float(np.mean((image - reference) ** 2 / (reference ** 2 + 1e-2)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--render", required=True)
    ap.add_argument("--suite", required=True)
    ap.add_argument("--scenes", default="fog-glass,foggy-room")
    ap.add_argument("--size", default="96x96")
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--ref-spp", type=int, default=2048)
    ap.add_argument("--bounces", type=int, default=64)
    a = ap.parse_args()
    out = tempfile.mkdtemp(prefix="tsr-cycles-")

    def ours(scene, spp, name):
        path = os.path.join(out, name)
        seconds = timed([a.render, scene, "--backend", "embree", "--size", a.size, "--spp", str(spp),
                         "--max-depth", str(a.bounces), "--output", path, "--quiet"])
        return load(path), seconds

    def cycles(scene, spp, name):
        path = os.path.join(out, name)
        seconds = timed(["blender", "-b", "--python", os.path.join(HERE, "cycles_render.py"), "--", scene, path,
                         str(spp), a.size, str(a.bounces)])
        return load(path), seconds

    print("%s, %d spp against Tessera's %d-spp reference, %d bounces" % (a.size, a.spp, a.ref_spp, a.bounces))
    print("%-11s | %-26s | %-26s | %-8s | %-17s | %-17s" % ("scene", "mean, Tessera reference", "mean, Cycles reference",
                                                          "ratio", "relMSE T / C", "seconds T / C"))
    for key in a.scenes.split(","):
        scene = os.path.join(a.suite, key + ".gltf")
        ref, _ = ours(scene, a.ref_spp, key + "-ours-ref.exr")
        cref, _ = cycles(scene, a.ref_spp, key + "-cycles-ref.exr")
        mine, t_mine = ours(scene, a.spp, key + "-ours.exr")
        theirs, t_theirs = cycles(scene, a.spp, key + "-cycles.exr")
        m, c = ref.mean(axis=(0, 1)), cref.mean(axis=(0, 1))
        print("%-11s | %-26s | %-26s | %.4f | %.4f / %.4f | %6.2f / %6.2f" % (
            key, " ".join("%.4f" % v for v in m), " ".join("%.4f" % v for v in c), float(c.mean() / m.mean()),
            rel_mse(mine, ref), rel_mse(theirs, ref), t_mine, t_theirs))
    print("images in", out)


if __name__ == "__main__":
    main()
