"""Inside Blender: one scene of the quality suite (or builtin:cornell
written by tessera-inspect --write-glb) rendered by Cycles 3.4 as Tessera
sees it: Principled BSDFs with multiple-scattering GGX, emission from the
front face only, a black world, every sample counted alike (no adaptive
sampling, denoising, clamping or glossy filter).

    blender -b --python cycles_suite_render.py -- SCENE.gltf OUT.exr SPP WIDTHxHEIGHT BOUNCES
"""
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import cycles_common  # noqa: E402

job = cycles_common.import_job()
cycles_common.shade_gltf_as_tessera()
cycles_common.black_world(bpy.context.scene)
cycles_common.render_still(bpy.context.scene, job.spp, job.bounces, job.width, job.height, job.out_path)
