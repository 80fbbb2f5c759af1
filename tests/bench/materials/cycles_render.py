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
import numpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import cycles_common  # noqa: E402

if not hasattr(numpy, "bool"):  # Debian: blender 3.4's glTF importer against numpy 1.24
    numpy.bool = bool

argv = sys.argv[sys.argv.index("--") + 1:]
scene_path, out_path, spp, size, bounces = argv[0], argv[1], int(argv[2]), argv[3], int(argv[4])
width, height = (int(v) for v in size.split("x"))

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=scene_path)

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
cycles_common.render_still(scene, spp, bounces, width, height, out_path)
