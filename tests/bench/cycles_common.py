"""What the Cycles comparisons (tests/bench/media, tests/bench/materials)
share: the render settings, inside Blender, and reading an EXR, outside.

Inside Blender (its own Python), after sys.path.insert of this folder:
    job = cycles_common.import_job()   # arguments after '--', glTF imported
    cycles_common.render_still(scene, job.spp, job.bounces, job.width, job.height, job.out_path)
Outside: cycles_common.load(path) -> float64 RGB array (numpy, OpenImageIO).
"""


def import_job(prepare=None):
    """Inside Blender: the arguments after '--' (SCENE OUT SPP WxH BOUNCES,
    then the script's own in job.extra), with SCENE's glTF imported into an
    empty scene. prepare(scene, job), when given, runs on the empty scene
    before the import (settings the importer reads, such as the fps)."""
    import sys
    from types import SimpleNamespace

    import bpy
    import numpy

    if not hasattr(numpy, "bool"):  # Debian: blender 3.4's glTF importer against numpy 1.24
        numpy.bool = bool
    argv = sys.argv[sys.argv.index("--") + 1:]
    width, height = (int(v) for v in argv[3].split("x"))
    job = SimpleNamespace(scene_path=argv[0], out_path=argv[1], spp=int(argv[2]), width=width, height=height,
                          bounces=int(argv[4]), extra=argv[5:])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    if prepare:
        prepare(bpy.context.scene, job)
    bpy.ops.import_scene.gltf(filepath=job.scene_path)
    return job


def shade_gltf_as_tessera():
    """Inside Blender, after the glTF importer: every Principled BSDF uses
    multiple-scattering GGX, and emission leaves the front face only (as in
    glTF and Tessera): the surface without emission plus an emission shader
    that a back face sees as black."""
    import bpy

    for mat in bpy.data.materials:
        tree = mat.node_tree
        bsdf = tree.nodes.get("Principled BSDF") if tree else None
        if not bsdf:
            continue
        bsdf.distribution = "MULTI_GGX"
        out = next(n for n in tree.nodes if n.type == "OUTPUT_MATERIAL")
        if bsdf.inputs["Emission"].is_linked:
            continue
        shader = with_front_emission(tree, bsdf.outputs[0], bsdf)
        if shader is not bsdf.outputs[0]:
            bsdf.inputs["Emission Strength"].default_value = 0.0  # the emission shader carries it now
            tree.links.new(shader, out.inputs["Surface"])


def with_front_emission(tree, surface, bsdf):
    """Inside Blender: `surface` plus the emission of Principled BSDF `bsdf`
    leaving the front face only (a back face sees black); `surface` itself
    when it emits nothing."""
    strength = bsdf.inputs["Emission Strength"].default_value
    if strength * max(bsdf.inputs["Emission"].default_value[:3]) <= 0:
        return surface
    emission = tree.nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = bsdf.inputs["Emission"].default_value
    emission.inputs["Strength"].default_value = strength
    geometry = tree.nodes.new("ShaderNodeNewGeometry")
    front = tree.nodes.new("ShaderNodeMixShader")
    black = tree.nodes.new("ShaderNodeBsdfTransparent")
    black.inputs["Color"].default_value = (0, 0, 0, 1)
    tree.links.new(geometry.outputs["Backfacing"], front.inputs["Fac"])
    tree.links.new(emission.outputs[0], front.inputs[1])
    tree.links.new(black.outputs[0], front.inputs[2])
    add = tree.nodes.new("ShaderNodeAddShader")
    tree.links.new(surface, add.inputs[0])
    tree.links.new(front.outputs[0], add.inputs[1])
    return add.outputs[0]


def black_world(scene):
    """Inside Blender: a black world, so only the scene's emitters light it."""
    import bpy

    world = bpy.data.worlds.new("world")
    scene.world = world
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)


def render_still(scene, spp, bounces, width, height, out_path):
    """Cycles on the CPU, every sample counted alike: no adaptive sampling,
    denoising, clamping or glossy filter, a 1-pixel film filter, caustics
    on, `bounces` for every kind of bounce, a float EXR in linear light."""
    import bpy

    scene.camera = next(o for o in bpy.data.objects if o.type == "CAMERA")
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = spp
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.sample_clamp_direct = 0.0
    scene.cycles.sample_clamp_indirect = 0.0
    scene.cycles.blur_glossy = 0.0
    scene.cycles.filter_width = 1.0
    scene.cycles.max_bounces = bounces
    for kind in ("diffuse", "glossy", "transmission", "volume", "transparent_max"):
        setattr(scene.cycles, kind if kind.endswith("_max") else kind + "_bounces", bounces)
    scene.cycles.caustics_reflective = True
    scene.cycles.caustics_refractive = True
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = out_path
    scene.view_settings.view_transform = "Standard"
    bpy.ops.render.render(write_still=True)


def load(path):
    """An image's RGB as float64, rows top first."""
    import numpy as np
    import OpenImageIO as oiio

    image = oiio.ImageInput.open(path)
    if not image:
        raise SystemExit("cannot read %s: %s" % (path, oiio.geterror()))
    pixels = np.asarray(image.read_image(format="float"))[..., :3].astype(np.float64)
    image.close()
    return pixels


def timed(command):
    """Outside Blender: wall-clock seconds of running `command` (its output dropped)."""
    import subprocess
    import time

    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def comparison_parser(doc):
    """Outside Blender: the arguments every Cycles comparison takes
    (--render, --size, --spp, --bounces, --out); a script adds its own."""
    import argparse

    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--render", required=True, help="tessera-render")
    ap.add_argument("--size", default="128x128")
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--bounces", type=int, default=16)
    ap.add_argument("--out", default=None)
    return ap
