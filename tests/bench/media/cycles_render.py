"""Renders a glTF scene of the quality suite with Blender Cycles, reading
Tessera's volume extensions (docs/volumes.md) into Cycles' volume shaders:
TSR_materials_volume on a material and TSR_scene_medium on the scene.

    blender -b --python cycles_render.py -- SCENE.gltf OUT.exr SPP WIDTHxHEIGHT MAX_BOUNCES

Cycles settings that differ from its defaults, to match Tessera's path
tracer: no denoising, no clamping, no glossy filter, a 1-pixel film
filter, volume bounces as many as the others, float EXR output.
"""
import json
import sys

import os

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import cycles_common  # noqa: E402

job = cycles_common.import_job()

doc = json.load(open(job.scene_path))


def volume_shader(tree, volume):
    """sigma_s = Volume Scatter's density x colour, sigma_a = Volume Absorption's density x (1 - colour)."""
    scatter = [float(v) for v in volume.get("scattering", [0, 0, 0])]
    absorb = [float(v) for v in volume.get("absorption", [0, 0, 0])]
    add = tree.nodes.new("ShaderNodeAddShader")
    s = tree.nodes.new("ShaderNodeVolumeScatter")
    ds = max(scatter) or 1.0
    s.inputs["Color"].default_value = (*[v / ds for v in scatter], 1.0)
    s.inputs["Density"].default_value = max(scatter)
    s.inputs["Anisotropy"].default_value = float(volume.get("phaseG", 0.0))
    a = tree.nodes.new("ShaderNodeVolumeAbsorption")
    da = max(absorb) or 1.0
    a.inputs["Color"].default_value = (*[1.0 - v / da for v in absorb], 1.0)
    a.inputs["Density"].default_value = max(absorb)
    tree.links.new(s.outputs[0], add.inputs[0])
    tree.links.new(a.outputs[0], add.inputs[1])
    return add.outputs[0]


# Tessera's diffuse is Lambert alone. The importer's Principled BSDF adds
# a specular layer (F0 0.04) and Disney diffuse's grazing retro-reflection,
# which a white room's many bounces turn into 12-20 % more light: rough
# non-metals get Cycles' Lambertian Diffuse BSDF (emission kept).
for mat in bpy.data.materials:
    tree = mat.node_tree
    bsdf = tree.nodes.get("Principled BSDF") if tree else None
    if not bsdf or bsdf.inputs["Metallic"].default_value != 0 or bsdf.inputs["Transmission"].default_value != 0 \
            or bsdf.inputs["Roughness"].default_value < 0.99 or bsdf.inputs["Base Color"].is_linked:
        continue
    out = next(n for n in tree.nodes if n.type == "OUTPUT_MATERIAL")
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = bsdf.inputs["Base Color"].default_value
    shader = cycles_common.with_front_emission(tree, diffuse.outputs[0], bsdf)  # glTF emits from the front only
    tree.links.new(shader, out.inputs["Surface"])

# The importer names unnamed materials Material_<index>, in the file's order.
for i, m in enumerate(doc.get("materials", [])):
    volume = m.get("extensions", {}).get("TSR_materials_volume")
    if not volume:
        continue
    mat = bpy.data.materials.get(m.get("name") or "Material_%d" % i)
    out = next(n for n in mat.node_tree.nodes if n.type == "OUTPUT_MATERIAL")
    mat.node_tree.links.new(volume_shader(mat.node_tree, volume), out.inputs["Volume"])

scene = bpy.context.scene
world = bpy.data.worlds.new("world")
scene.world = world
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
medium = doc["scenes"][doc.get("scene", 0)].get("extensions", {}).get("TSR_scene_medium")
if medium:
    out = next(n for n in world.node_tree.nodes if n.type == "OUTPUT_WORLD")
    world.node_tree.links.new(volume_shader(world.node_tree, medium), out.inputs["Volume"])

cycles_common.render_still(scene, job.spp, job.bounces, job.width, job.height, job.out_path)
