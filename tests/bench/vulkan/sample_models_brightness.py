#!/usr/bin/python3
"""Mean brightness of the rasterizer against the path tracer on glTF files.

    /usr/bin/python3 tests/bench/vulkan/sample_models_brightness.py BIN_DIR \\
        [--models /usr/share/assimp/models/glTF2] [--size 96] [--spp 256] [--keep DIR]

Every .gltf and .glb under --models is rendered by both back-ends at
SIZExSIZE under whatever light it has (the default rig when it has none);
files the importer refuses are listed as such. For each file the table gives
the mean of the two images (RGB, linear) and their ratio raster / path
tracer; the last line counts the files within 10 % (issue 46's target).
--keep writes each pair side by side as PNG (raster left) to look at.
Needs Debian's python3-openimageio (hence /usr/bin/python3).
"""
import argparse
import os
import subprocess
import sys
import tempfile

import OpenImageIO as oiio


def render(binary, model, backend, size, spp, out):
    args = [binary, model, "--backend", backend, "--size", f"{size}x{size}", "--quiet", "--output", out]
    if backend == "embree":
        args += ["--spp", str(spp)]
    run = subprocess.run(args, capture_output=True, text=True)
    if run.returncode != 0:
        lines = [l for l in run.stderr.splitlines() if "error" in l.lower()] or run.stderr.splitlines() or ["?"]
        return None, lines[-1].strip()
    return oiio.ImageBuf(out), ""


def mean(buf):
    return float(buf.get_pixels(oiio.FLOAT)[..., :3].mean())


def side_by_side(a, b, size, path):
    out = oiio.ImageBuf(oiio.ImageSpec(2 * size, size, 3, oiio.UINT8))
    for buf, x in ((a, 0), (b, size)):
        rgb = oiio.ImageBufAlgo.channels(buf, (0, 1, 2))  # colour as written; alpha is coverage
        srgb = oiio.ImageBufAlgo.colorconvert(rgb, "linear", "sRGB")
        oiio.ImageBufAlgo.paste(out, x, 0, 0, 0, srgb, roi=oiio.ROI(0, size, 0, size, 0, 1, 0, 3))
    out.write(path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bin")
    parser.add_argument("--models", default="/usr/share/assimp/models/glTF2")
    parser.add_argument("--size", type=int, default=96)
    parser.add_argument("--spp", type=int, default=256)
    parser.add_argument("--keep", help="folder for side-by-side PNGs")
    o = parser.parse_args()
    binary = os.path.join(o.bin, "tessera-render")
    if not os.access(binary, os.X_OK):
        sys.exit(f"error: {binary} is missing")
    if o.keep:
        os.makedirs(o.keep, exist_ok=True)
    models = sorted(os.path.join(d, f) for d, _, files in os.walk(o.models) for f in files
                    if f.endswith((".gltf", ".glb")))
    within = compared = 0
    with tempfile.TemporaryDirectory() as work:
        print(f"{'model':<58} {'raster':>8} {'traced':>8} {'ratio':>7}")
        for model in models:
            name = os.path.relpath(model, o.models)
            raster, err = render(binary, model, "vulkan", o.size, o.spp, os.path.join(work, "raster.exr"))
            if raster is None:
                print(f"{name:<58} refused: {err[:90]}")
                continue
            traced, err = render(binary, model, "embree", o.size, o.spp, os.path.join(work, "traced.exr"))
            if traced is None:
                print(f"{name:<58} path tracer refused: {err[:80]}")
                continue
            r, t = mean(raster), mean(traced)
            ratio = r / t if t > 0 else float("inf")
            ok = abs(ratio - 1.0) <= 0.10
            compared += 1
            within += ok
            print(f"{name:<58} {r:8.4f} {t:8.4f} {ratio:7.3f}{'' if ok else '  <- off by more than 10 %'}")
            if o.keep:
                side_by_side(raster, traced, o.size, os.path.join(o.keep, name.replace("/", "_") + ".png"))
    print(f"{within} of {compared} imported files within 10 % of the path tracer's mean brightness")


if __name__ == "__main__":
    main()
