"""Renders frame 0 of a glTF scene's animation with Blender Cycles 3.4 and
the shutter of Tessera's camera (docs/camera.md): open and close as
fractions of the frame interval 1/FPS, the animation posed at t = 0.

    blender -b --python cycles_motion_render.py -- SCENE.gltf OUT.exr SPP WIDTHxHEIGHT MAX_BOUNCES FPS OPEN CLOSE

The shutter: Blender's glTF importer keys an animation at frame =
time * scene.render.fps, so FPS is set before the import and frame f is
time f / FPS, as in `tessera-render --frames N --fps FPS`. Cycles' motion
blur with position 'START' exposes [frame, frame + shutter] (in frames,
intern/cycles/blender/sync.cpp); the frame is set to 0 with subframe OPEN,
so Cycles exposes [OPEN, OPEN + (CLOSE - OPEN)] = [OPEN, CLOSE] of frame 0,
Tessera's interval. (Cycles' default, 'CENTER', would put the interval
around the frame: [-shutter/2, shutter/2].) The shutter curve stays flat,
rolling shutter off; objects get Cycles' default 3 motion steps.
OPEN == CLOSE renders an instant (motion blur off) at that time.

Render settings are tests/bench/cycles_common.py's (no denoising, clamping
or glossy filter, a 1-pixel film filter, float EXR); materials are the glTF
importer's Principled BSDF (multiple-scattering GGX), emission from the
front face only, a black world; the glTF yfov spans the image height.
"""
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import cycles_common  # noqa: E402


def frame_rate(scene, job):
    """Before the import, which keys the animation at time * fps."""
    fps = int(job.extra[0])
    scene.render.fps, scene.render.fps_base = fps, 1.0


job = cycles_common.import_job(frame_rate)
fps, shutter_open, shutter_close = int(job.extra[0]), float(job.extra[1]), float(job.extra[2])
if not (0.0 <= shutter_open <= shutter_close <= 1.0):
    sys.exit("cycles_motion_render: the shutter must be 0 <= OPEN <= CLOSE <= 1")
scene = bpy.context.scene
cycles_common.shade_gltf_as_tessera()
cycles_common.black_world(scene)

camera = next(o for o in bpy.data.objects if o.type == "CAMERA").data
camera.sensor_fit = "VERTICAL"  # the glTF yfov spans the image height, as in Tessera
scene.render.use_motion_blur = shutter_close > shutter_open
scene.render.motion_blur_shutter = shutter_close - shutter_open
scene.cycles.motion_blur_position = "START"
scene.cycles.rolling_shutter_type = "NONE"
scene.frame_set(0, subframe=shutter_open)
for o in bpy.data.objects:
    if o.animation_data and o.animation_data.action:
        keys = sorted({round(k.co[0], 4) for c in o.animation_data.action.fcurves for k in c.keyframe_points})
        print("cycles_motion_render: %s keyed at frames %s" % (o.name, keys[:8]))
print("cycles_motion_render: fps %d, frame %d + subframe %.3f, shutter %.3f frames from the start, motion blur %s"
      % (scene.render.fps, scene.frame_current, scene.frame_subframe, scene.render.motion_blur_shutter,
         scene.render.use_motion_blur))
cycles_common.render_still(scene, job.spp, job.bounces, job.width, job.height, job.out_path)
