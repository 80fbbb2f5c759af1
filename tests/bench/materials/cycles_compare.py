#!/usr/bin/python3
"""Tessera's glTF metallic-roughness BSDF against Blender Cycles 3.4's
Principled BSDF on the sphere grid (make_sphere_grid.py): each renderer's
own high-spp image, the mean of every sphere (an inner disc of its
projection) and the seen error of the whole image (tests/bench/quality/
seen_error.py: clamp, sRGB, box blur of radius 2 twice, RMSE). The
rasterizer's frame of the same scene is set beside both, measured against
the path tracer.

    cycles_compare.py --render build/default/bin/tessera-render [--size 160x80]
                      [--spp 1024] [--bounces 16] [--out DIR]

Needs Debian's blender, python3-numpy and python3-openimageio.
"""
import argparse, math, os, subprocess, sys, tempfile

import numpy as np
import OpenImageIO as oiio

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
from cycles_common import load  # noqa: E402
sys.path.insert(0, os.path.join(HERE, "..", "quality"))
from seen_error import displayed, seen_error  # noqa: E402
sys.path.insert(0, HERE)
import make_sphere_grid as grid  # noqa: E402




def save_png(path, pixels):
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(pixels.shape[1], pixels.shape[0], 3, "uint8"))
    out.write_image((displayed(pixels) * 255 + 0.5).astype(np.uint8))
    out.close()


def sphere_masks(width, height):
    """Inner discs (70 % of the projected radius) of every sphere."""
    f = (height / 2) / math.tan(grid.YFOV / 2)
    yy, xx = np.mgrid[0:height, 0:width] + 0.5
    masks = []
    for s in grid.spheres():
        x, y, z = s["centre"]
        d = grid.CAMERA_Z - z
        cx, cy = width / 2 + f * x / d, height / 2 - f * y / d
        r = 0.7 * f * grid.RADIUS / math.sqrt(d * d - grid.RADIUS ** 2)
        masks.append((s["name"], (xx - cx) ** 2 + (yy - cy) ** 2 <= r * r))
    return masks


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--render", required=True)
    ap.add_argument("--size", default="160x80")
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--bounces", type=int, default=16)
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    out = a.out or tempfile.mkdtemp(prefix="tsr-materials-")
    os.makedirs(out, exist_ok=True)
    scene = os.path.join(out, "sphere_grid.gltf")
    subprocess.run([sys.executable, os.path.join(HERE, "make_sphere_grid.py"), scene], check=True)
    ours_path, cycles_path = os.path.join(out, "tessera.exr"), os.path.join(out, "cycles.exr")
    raster_path = os.path.join(out, "rasterizer.exr")
    if not os.path.exists(ours_path):
        subprocess.run([a.render, scene, "--backend", "embree", "--size", a.size, "--spp", str(a.spp),
                        "--max-depth", str(a.bounces), "--no-default-light", "--output", ours_path, "--quiet"],
                       check=True)
    if not os.path.exists(cycles_path):
        subprocess.run(["blender", "-b", "--python", os.path.join(HERE, "cycles_render.py"), "--", scene,
                        cycles_path, str(a.spp), a.size, str(a.bounces)], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    subprocess.run([a.render, scene, "--backend", "vulkan", "--size", a.size, "--no-default-light", "--output",
                    raster_path, "--quiet"], check=True)
    ours, theirs, raster = load(ours_path), load(cycles_path), load(raster_path)
    save_png(os.path.join(out, "tessera.png"), ours)
    save_png(os.path.join(out, "cycles.png"), theirs)
    save_png(os.path.join(out, "side_by_side.png"), np.concatenate([raster, ours, theirs], axis=1))
    h, w = ours.shape[:2]
    print("%s, %d spp each, %d bounces; sphere means (luminance of the inner disc)" % (a.size, a.spp, a.bounces))
    print("| sphere | Tessera | Cycles | Tessera / Cycles - 1 | rasterizer | rasterizer / Tessera - 1 |")
    print("|---|---|---|---|---|---|")
    lum = np.array([0.2126, 0.7152, 0.0722])
    worst = 0.0
    for name, mask in sphere_masks(w, h):
        m, c, r = (float(image[mask].mean(axis=0) @ lum) for image in (ours, theirs, raster))
        worst = max(worst, abs(m / c - 1))
        print("| %s | %.4f | %.4f | %+.1f %% | %.4f | %+.1f %% |" % (name, m, c, 100 * (m / c - 1), r,
                                                                    100 * (r / m - 1)))
    print("worst sphere: %.1f %%; seen error, whole image: %.4f" % (100 * worst, seen_error(ours, theirs)[0]))
    whole, tile, _ = seen_error(raster, ours)
    print("rasterizer against the path tracer: seen error whole %.4f, worst tile %.4f" % (whole, tile))
    print("images in", out)


if __name__ == "__main__":
    main()
