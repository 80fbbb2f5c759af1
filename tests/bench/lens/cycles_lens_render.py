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


for mat in bpy.data.materials:
    tree = mat.node_tree
    bsdf = tree.nodes.get("Principled BSDF") if tree else None
    if not bsdf:
        continue
    bsdf.distribution = "MULTI_GGX"
    out = next(n for n in tree.nodes if n.type == "OUTPUT_MATERIAL")
    surface = bsdf.outputs[0]
    strength = bsdf.inputs["Emission Strength"].default_value
    if bsdf.inputs["Emission"].is_linked or strength * max(bsdf.inputs["Emission"].default_value[:3]) <= 0:
        continue
    # Front face only: the surface without emission, plus an
    # emission shader that a back face sees as black.
    emission = tree.nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = bsdf.inputs["Emission"].default_value
    emission.inputs["Strength"].default_value = strength
    bsdf.inputs["Emission Strength"].default_value = 0.0
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
    tree.links.new(add.outputs[0], out.inputs["Surface"])

scene = bpy.context.scene
world = bpy.data.worlds.new("world")
scene.world = world
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)

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
