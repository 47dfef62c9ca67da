"""The add-on as a user installs it: blender -b --factory-startup --python-exit-code 1 --python
tests/blender/test_addon_zip.py -- ZIP USER_SCRIPTS_DIR (with BLENDER_USER_SCRIPTS set to it).

Installs the zip through Blender's own operator, enables it, and renders a moving cube with F12's
operator. Nothing is put on Python's path: the module and libstreak come from the zip alone."""

import math
import os
import shutil
import sys
import tempfile

import bpy

ARGS = sys.argv[sys.argv.index("--") + 1:]
ZIP, USER_SCRIPTS = ARGS[0], ARGS[1]
assert os.environ.get("BLENDER_USER_SCRIPTS") == USER_SCRIPTS, "run with BLENDER_USER_SCRIPTS set to the scripts folder"
shutil.rmtree(USER_SCRIPTS, ignore_errors=True)
os.makedirs(os.path.join(USER_SCRIPTS, "addons"))
assert "streak" not in sys.modules

bpy.ops.preferences.addon_install(filepath=ZIP)
bpy.ops.preferences.addon_enable(module="streak_blender")
import streak_blender.engine as engine  # noqa: E402

scene = bpy.context.scene  # the factory scene: a cube, a light and a camera
cube = bpy.data.objects["Cube"]
cube.keyframe_insert("location", frame=1)
cube.location.x += 1.0
cube.keyframe_insert("location", frame=2)
scene.frame_set(1)
scene.render.use_motion_blur = True
scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 96, 72, 100
scene.render.engine = "STREAK"
scene.render.film_transparent = True
folder = tempfile.mkdtemp(prefix="streak_zip_")
scene.render.filepath = os.path.join(folder, "f12.png")
scene.render.image_settings.file_format = "PNG"
scene.render.image_settings.color_mode = "RGBA"
bpy.ops.render.render(write_still=True)

report = engine.last_render
assert report.get("status") == "done", report
assert os.path.dirname(sys.modules["streak"].__file__).startswith(USER_SCRIPTS), sys.modules["streak"].__file__
image = bpy.data.images.load(scene.render.filepath)
alpha = list(image.pixels)[3::4]
partial = sum(1 for a in alpha if 0.05 < a < 0.95)
covered = sum(1 for a in alpha if a >= 0.95)
print(f"zip add-on: {report['keys']} keys, {report['triangles']} triangles, {covered} covered and {partial} blurred pixels")
assert covered > 100 and partial > 50, (covered, partial)
shutil.rmtree(folder)
