"""What the Cycles comparisons (tests/bench/media, tests/bench/materials)
share: the render settings, inside Blender, and reading an EXR, outside.

Inside Blender (its own Python), after sys.path.insert of this folder:
    job = cycles_common.import_job()   # arguments after '--', glTF imported
    cycles_common.render_still(scene, job.spp, job.bounces, job.width, job.height, job.out_path)
Outside: cycles_common.load(path) -> float64 RGB array (numpy, OpenImageIO).
"""


def import_job():
    """Inside Blender: the arguments after '--' (SCENE OUT SPP WxH BOUNCES,
    then the script's own in job.extra), with SCENE's glTF imported into an
    empty scene."""
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
    bpy.ops.import_scene.gltf(filepath=job.scene_path)
    return job


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
