"""Renders a glTF scene with Blender Cycles 3.4 through the thin lens of
Tessera's camera extension TSR_camera_lens (docs/camera.md): the same
aperture radius and focus distance, the glTF camera's vertical field of
view on a square image.

    blender -b --python cycles_lens_render.py -- SCENE.gltf OUT.exr SPP WIDTHxHEIGHT MAX_BOUNCES [APERTURE FOCUS]

APERTURE and FOCUS (metres) override the file's lens; APERTURE 0 is the
pinhole. Render settings are tests/bench/cycles_common.py's (no denoising,
clamping or glossy filter, a 1-pixel film filter, float EXR).

The lens: Cycles 3.4 has no aperture-radius setting any more (2.7x's
aperture_type RADIUS is gone); it derives the radius of its disc aperture
from the f-number, radius = focal length / (2 f-number) with the focal
length `lens` in millimetres taken as lens * 1e-3 scene units (Blender's
intern/cycles/blender/camera.cpp). So f-number = lens * 1e-3 / (2 radius)
gives Tessera's apertureRadius exactly; blades 0 is a round aperture,
sampled uniformly like Tessera's. Both focus on a plane at focus distance
along the view direction.

Materials are the glTF importer's Principled BSDF (multiple-scattering
GGX), as in tests/bench/materials/cycles_render.py, which measures how
close it is to Tessera's glTF BSDF on its own; the pinhole pair of
cycles_lens_compare.py shows what the two renderers differ by without a
lens. Emission leaves the front face only, as in glTF and Tessera.
"""
import json
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import cycles_common  # noqa: E402

job = cycles_common.import_job()
doc = json.load(open(job.scene_path))
lens = doc["cameras"][0].get("extensions", {}).get("TSR_camera_lens", {})
aperture = float(job.extra[0]) if len(job.extra) > 0 else float(lens.get("apertureRadius", 0.0))
focus = float(job.extra[1]) if len(job.extra) > 1 else float(lens.get("focusDistance", 5.0))

cycles_common.shade_gltf_as_tessera()
scene = bpy.context.scene
cycles_common.black_world(scene)

camera = next(o for o in bpy.data.objects if o.type == "CAMERA").data
camera.sensor_fit = "VERTICAL"  # the glTF yfov spans the image height, as in Tessera
camera.dof.use_dof = aperture > 0
if aperture > 0:
    camera.dof.focus_object = None
    camera.dof.focus_distance = focus
    camera.dof.aperture_fstop = camera.lens * 1e-3 / (2.0 * aperture)
    camera.dof.aperture_blades = 0
    camera.dof.aperture_ratio = 1.0
print("cycles_lens_render: yfov %.6f rad, lens %.4f mm, aperture radius %.4f, f-number %.5f, focus %.4f"
      % (camera.angle_y, camera.lens, aperture, camera.dof.aperture_fstop if aperture > 0 else 0.0, focus))
cycles_common.render_still(scene, job.spp, job.bounces, job.width, job.height, job.out_path)
