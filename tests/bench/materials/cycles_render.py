"""Renders the sphere grid (make_sphere_grid.py) with Blender Cycles 3.4
as its glTF importer maps it onto the Principled BSDF (metallic,
roughness, transmission, ior; specular 0.5 = F0 0.04), lit by the
emissive environment box alone.

    blender -b --python cycles_render.py -- SCENE.gltf OUT.exr SPP WIDTHxHEIGHT MAX_BOUNCES

Settings as in tests/bench/media/cycles_render.py: no denoising, no
clamping, no glossy filter, a 1-pixel film filter, float EXR output.
"""
import sys

import os

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import cycles_common  # noqa: E402

job = cycles_common.import_job()


# The glTF importer leaves Cycles' default distribution; say which is used.
for mat in bpy.data.materials:
    bsdf = mat.node_tree.nodes.get("Principled BSDF") if mat.node_tree else None
    if bsdf:
        bsdf.distribution = "MULTI_GGX"
        bsdf.subsurface_method = "BURLEY"

scene = bpy.context.scene
world = bpy.data.worlds.new("world")
scene.world = world
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
cycles_common.render_still(scene, job.spp, job.bounces, job.width, job.height, job.out_path)
