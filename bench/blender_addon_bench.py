"""Times the Blender add-on (blender/streak_blender) headless: F12 split into Blender's
evaluation and export of the keys, and streak's render.

  blender -b --factory-startup --python bench/blender_addon_bench.py -- BUILD_DIR [--repeats N]

Two scenes: tests/blender/scene_builder's (three small animated objects, 160x120) with
motion-path and analytic at --aa 4 and 8; and a dense one, Blender's monkey under a level-4
Subdivision Surface (251,916 triangles) turning, 320x240 --aa 4, with the keys chosen by the
tolerance and with 9 fixed keys. Prints one line per case (least wall time of the repeats)."""

import argparse
import os
import sys
import tempfile
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
args = argparse.ArgumentParser().parse_known_args(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])[1]
parser = argparse.ArgumentParser()
parser.add_argument("build")
parser.add_argument("--repeats", type=int, default=3)
options = parser.parse_args(args)
sys.path.insert(0, os.path.join(options.build, "python"))
sys.path.insert(0, os.path.join(HERE, "..", "blender"))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "blender"))

import scene_builder  # noqa: E402
import streak_blender  # noqa: E402
from streak_blender import engine  # noqa: E402

streak_blender.register()
folder = tempfile.mkdtemp(prefix="streak_blender_bench_")


def timed(label):
    best = None
    for _ in range(options.repeats):
        start = time.perf_counter()
        bpy.ops.render.render()
        wall = (time.perf_counter() - start) * 1000.0
        report = engine.last_render
        assert report["status"] == "done", report
        case = (wall, report["export_ms"], report["stats"]["time_ms"]["render"], report["keys"], report["triangles"])
        best = case if best is None or case[0] < best[0] else best
    print(f"{label}: {best[4]} triangles, {best[3]} keys, F12 {best[0]:.0f} ms = export {best[1]:.0f} ms + "
          f"streak render {best[2]:.0f} ms (+ Blender's result handling)", flush=True)


for method in ("motion-path", "analytic"):
    for aa in (4, 8):
        scene = scene_builder.build(folder)
        scene.render.engine = "STREAK"
        scene.streak.shading, scene.streak.aa, scene.streak.method = "UNLIT", aa, method
        timed(f"test scene 160x120, {method} --aa {aa}")

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
bpy.ops.mesh.primitive_monkey_add()
monkey = bpy.context.object
subsurf = monkey.modifiers.new("Subdivision", "SUBSURF")
subsurf.levels = subsurf.render_levels = 4
monkey.keyframe_insert("rotation_euler", frame=1)
monkey.rotation_euler.z = 1.0
monkey.keyframe_insert("rotation_euler", frame=3)
camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
scene.collection.objects.link(camera)
camera.location, camera.rotation_euler = (0.0, -5.0, 0.0), (1.5708, 0.0, 0.0)
scene.camera = camera
scene.frame_set(2)
scene.render.use_motion_blur = True
scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 320, 240, 100
scene.render.engine = "STREAK"
scene.streak.shading, scene.streak.aa = "UNLIT", 4
for keys in (0, 9):
    scene.streak.keys = keys
    timed(f"subdivided monkey 320x240, motion-path --aa 4, keys {'by tolerance' if keys == 0 else keys}")
